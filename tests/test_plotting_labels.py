"""Figure labels: spectra in their quantity's unit, sea-state labels as in the sea-state
tables, tick labels of the averaging 3-D panels that do not overlap (issue 19)."""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from seahelm.environment.sea_state import TABLE1, sea_state_grade  # noqa: E402
from seahelm.environment.rational_spectra import (  # noqa: E402
    ordinate_rate_spectrum,
    slope_spectrum,
)
from seahelm.environment.spectra import spectrum_from_wave_height  # noqa: E402
from seahelm.plotting.waves import (  # noqa: E402
    grade_label,
    plot_spectrum,
    spectrum_unit,
)
from seahelm.studies.sushchenko2010 import plot_paper_figure  # noqa: E402

_ROMAN = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX")


def test_spectra_are_labelled_in_their_quantitys_unit():
    spec = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0)
    assert spectrum_unit(spec) == "m²·s/rad"
    assert spectrum_unit(slope_spectrum(spec)) == "rad²·s/rad"
    assert spectrum_unit(ordinate_rate_spectrum(spec)) == "(m/s)²·s/rad"
    ax = plot_spectrum(spec)
    assert ax.get_ylabel() == "S₁(ω) [m²·s/rad] (one-sided)"
    plt.close(ax.figure)


@pytest.fixture(scope="module")
def paper_figure():
    fig = plot_paper_figure(duration=20.0)
    fig.canvas.draw()
    yield fig
    plt.close(fig)


def test_the_paper_figure_has_no_placeholder_unit(paper_figure):
    labels = [ax.get_ylabel() for ax in paper_figure.axes]
    assert not any("unit" in label for label in labels), labels
    assert sum("[m²·s/rad]" in label for label in labels) == 2  # ordinate spectra, a and b
    assert sum("[rad²·s/rad]" in label for label in labels) == 2  # slope spectra, c and d


def test_sea_state_labels_agree_with_table_1(paper_figure):
    entries = [t.get_text() for ax in paper_figure.axes if ax.get_legend()
               for t in ax.get_legend().get_texts()]
    assert len(entries) == 10
    for text in entries:
        m = re.fullmatch(r"sea state ([IVX]+) \(h3% (=|≥) ([\d.]+) m\)(, drawn at ([\d.]+) m)?",
                         text)
        assert m, text
        grade = _ROMAN.index(m.group(1)) + 1
        lo, hi = TABLE1[grade]
        if m.group(2) == "=":  # drawn at a height of its own grade
            assert int(sea_state_grade(float(m.group(3)))) == grade, text
        else:  # a grade beyond Table 2 says where it was drawn
            assert float(m.group(3)) == lo and not lo <= float(m.group(5)) < hi, text
    assert grade_label(9, 10.0) == "sea state IX (h3% ≥ 11 m), drawn at 10 m"
    assert grade_label("VI", 4.75) == "sea state VI (h3% = 4.75 m)"


def test_averaging_3d_panels_have_few_enough_ticks_not_to_overlap():
    # matplotlib does not report where a 3-D axis draws its tick labels (their window extents
    # are those of unprojected positions), so the check is on what made them overlap: at the
    # size `seahelm averaging cpp --plot` writes (12 x 5 in at 120 dpi, checked by eye), the
    # default 0.25 steps put 9 labels on an axis foreshortened to ~300 px. At most 5 fit.
    from seahelm.studies.platonov.flat_set import cpp_admissible_set
    from seahelm.studies.platonov.figures import plot_control_sets

    fig = plot_control_sets(cpp_admissible_set(1.2, 0.96, n_azimuth=24, n_elevation=12))
    fig.canvas.draw()
    for ax in fig.axes:
        for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim()),
                               (ax.zaxis, ax.get_zlim())):
            shown = [v for v in axis.get_ticklocs() if lo <= v <= hi]
            assert 3 <= len(shown) <= 5, (axis.axis_name, shown)
    plt.close(fig)


# ------------------------------------------------------------------------------------------
# manoeuvre figures: no text over another, none outside the figure (issue 36)
# ------------------------------------------------------------------------------------------
def _drawn_texts(fig):
    """(text, window extent) of every text the saved figure shows: visible, not empty, and
    for tick labels only those of ticks inside the view limits (matplotlib keeps labels of
    ticks outside them, which it does not draw)."""
    from matplotlib.text import Text

    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    hidden = set()
    for ax in fig.axes:
        for axis, limits in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            lo, hi = sorted(limits)
            pad = 1e-9 * (hi - lo)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                if not lo - pad <= tick.get_loc() <= hi + pad:
                    hidden.update({id(tick.label1), id(tick.label2)})
    return [(t.get_text(), t.get_window_extent(renderer)) for t in fig.findobj(Text)
            if t.get_visible() and t.get_text().strip() and id(t) not in hidden]


def _text_problems(fig):
    texts = _drawn_texts(fig)
    box = fig.bbox
    out = [f"outside the figure: {name!r}" for name, bb in texts
           if bb.x0 < box.x0 - 1 or bb.y0 < box.y0 - 1 or bb.x1 > box.x1 + 1
           or bb.y1 > box.y1 + 1]
    for i, (a, bb_a) in enumerate(texts):
        for b, bb_b in texts[i + 1:]:
            w = min(bb_a.x1, bb_b.x1) - max(bb_a.x0, bb_b.x0)
            h = min(bb_a.y1, bb_b.y1) - max(bb_a.y0, bb_b.y0)
            if w > 1 and h > 1:  # (more than touching)
                out.append(f"{a!r} over {b!r}")
    return out


@pytest.mark.parametrize("figure", ["turning", "zigzag", "stopping", "pullout", "one-circle"])
def test_manoeuvre_figures_have_no_text_over_another(kvlcc2_l7_imo, figure):
    import math

    from seahelm.analysis.maneuvers import pull_out, turning_circle
    from seahelm.plotting import maneuvers as plots

    draw = {"turning": lambda: plots.plot_turning(kvlcc2_l7_imo.turning).figure,
            "zigzag": lambda: plots.plot_zigzag(kvlcc2_l7_imo.zigzag),
            "stopping": lambda: plots.plot_stopping(kvlcc2_l7_imo.stopping),
            "pullout": lambda: plots.plot_pullout(pull_out("kvlcc2-l7",
                                                           math.radians(20))).figure,
            "one-circle": lambda: plots.plot_turning(turning_circle(
                "kvlcc2-l7", math.radians(35), sides=1)).figure}
    fig = draw[figure]()
    assert _text_problems(fig) == []
    if figure == "turning":  # four circles: the values in the legend, not beside arrows
        labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert sum("tactical diameter" in label for label in labels) == 4
    plt.close(fig)


def test_the_overlap_check_finds_overlapping_text():
    fig, ax = plt.subplots()
    ax.text(0.5, 0.5, "transfer 9.321 m")
    ax.text(0.52, 0.5, "transfer 9.323 m")
    ax.set_title("x" * 400)  # wider than the figure
    problems = _text_problems(fig)
    plt.close(fig)
    assert any("over" in p and "transfer" in p for p in problems)
    assert any(p.startswith("outside the figure") for p in problems)


# ------------------------------------------------------------------------------------------
# the overview figure of a simulation batch (issue 36: a blob of 50 runs, labels cut off,
# snake_case labels, diverged runs not marked)
# ------------------------------------------------------------------------------------------
def _batch_result(runs, grid=True):
    from conftest import REPORT_BATCH_SCENARIO
    from seahelm.scenario import parse_scenario, run_scenario

    text = REPORT_BATCH_SCENARIO.replace("runs = 5", f"runs = {runs}")
    if not grid:
        text = text.replace('"controller.params.kp" = [1.0, 4.0]', '"controller.params.kp" = [1.0]')
    return run_scenario(parse_scenario(text)).to_xarray()


def test_a_big_batch_is_drawn_as_a_band_with_its_median_and_says_so():
    from matplotlib.collections import PolyCollection

    from seahelm.plotting.timeseries import BAND_RUNS, plot_result

    ds = _batch_result(30, grid=False)  # 30 runs, none diverged
    fig = plot_result(ds)
    heading = fig.axes[0]
    assert any(isinstance(c, PolyCollection) for c in heading.collections)  # the band
    assert len(heading.lines) <= 2 * 5 + 1  # a few runs (and their references), the median
    assert "30 runs: 5-95 % band and median" in fig._suptitle.get_text()
    assert fig.axes[1].get_ylabel() == "rudder angle [deg]"
    assert _text_problems(fig) == []
    plt.close(fig)
    assert BAND_RUNS < 30


def test_diverged_runs_are_marked_where_their_record_ends():
    from seahelm.plotting.timeseries import plot_result

    ds = _batch_result(5)  # kp = 4: the 5 samples diverge, kp = 1: none
    status = ds["status"].values.reshape(-1)
    n_diverged = int((status != 0).sum())
    assert n_diverged == 5
    fig = plot_result(ds)
    marks = [line for line in fig.axes[0].lines if line.get_marker() == "x"]
    assert len(marks) == n_diverged
    assert f"{n_diverged} diverged (x: where the record ends)" in fig._suptitle.get_text()
    assert _text_problems(fig) == []
    plt.close(fig)


def test_small_values_keep_their_axis_labels_inside_the_figure():
    """Heading in thousandths of a degree (an irregular sea's course keeping): the tick
    labels were long enough to push the y label off the figure."""
    import numpy as np

    from seahelm.plotting.timeseries import plot_result

    ds = _batch_result(2, grid=False)
    for name in ("heading", "yaw_rate", "rudder_angle"):
        ds[name] = ds[name] * 1e-4 + np.float64(1.234e-6)
    fig = plot_result(ds)
    assert _text_problems(fig) == []
    plt.close(fig)
