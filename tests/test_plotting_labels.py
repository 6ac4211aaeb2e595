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
