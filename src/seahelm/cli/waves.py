"""``seahelm waves``: sea-state tables, wave spectra and seeded disturbance samples.

Implements Sushchenko & Lutsko (2010) on the command line. Exit codes: 0 success, 2 bad
input (one-line reason on stderr), 1 other failure. ``--json`` prints one JSON object on
stdout and nothing else.
"""

from __future__ import annotations

import math
import typing
import warnings
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
import typer
from rich.markup import escape

from ..errors import ParameterError
from ..output_files import WRITTEN_BY_ATTR
from ..results import write_netcdf
from ._common import (
    ForceFlag,
    JsonFlag,
    OneLineErrors,
    check_figure_suffix,
    command_path,
    console,
    handle_errors,
    output_file,
    print_json,
)

app = typer.Typer(
    cls=OneLineErrors,
    help="Sea-wave disturbances (Sushchenko & Lutsko 2010): tables, spectra, samples.",
    no_args_is_help=True,
)

#: Largest runs × steps the CLI will generate in memory.
MAX_SAMPLES = 200_000_000
#: Longest realisation the paper's figure draws [s] (it plots every sample).
MAX_FIGURE_DURATION = 100_000.0

#: The names of :data:`seahelm.studies.sushchenko2010.SPECTRA` (the component spectra and the
#: paper's printed third one) and, of those, the rational ones (a shaping filter, so
#: ``sample``), and the versions of :data:`seahelm.studies.sushchenko2010.TABLE2_VERSIONS`:
#: spelled out so that the command line does not import the spectra (tests/test_cli_style.py
#: checks that they agree).
RationalSpectrumName = Literal["rakhmanin-firsov-1", "rakhmanin-firsov-2", "rakhmanin-firsov-3",
                               "rakhmanin-firsov-3-printed"]
SpectrumName = Literal[RationalSpectrumName, "pierson-moskowitz", "jonswap", "bretschneider",
                       "ittc"]
TableVersion = Literal["corrected", "printed"]


def _names(choices: Any) -> str:
    return ", ".join(typing.get_args(choices))


_H3 = Annotated[float, typer.Option("--h3", help="Height of 3 % exceedance waves h3% [m].")]
_Table = Annotated[TableVersion, typer.Option(
    "--table", help="Table 2 version: as printed, or with its two misprints corrected.")]
_Extrapolate = Annotated[bool, typer.Option(
    "--extrapolate", help="Beyond Table 2 (h3% outside [1, 10] m): extend μ and λ with "
                          "the h^(-1/2) law (with a warning) instead of refusing.")]


def _table_height(h3: float, extrapolate: bool) -> None:
    """Refuse an ``--h3`` outside Table 2 unless ``--extrapolate`` (checked before any work)."""
    from ..environment.sea_state import check_table_height

    if not extrapolate:
        check_table_height("--h3", h3, "--extrapolate extends the table with the h^(-1/2) law")


@app.command("table")
@handle_errors
def table_cmd(json_out: JsonFlag = False, table: _Table = "corrected") -> None:
    """Table 1 (grade → h3%) and Table 2 (μ, λ versus h3%)."""
    from ..environment.sea_state import TABLE1, TABLE2_COLUMNS, table2
    from ..studies.sushchenko2010 import get_table2

    version = get_table2(table)
    cols = table2(version)
    grades = [
        {"grade": g, "roman": _roman(g), "h3_min": lo, "h3_max": (hi if math.isfinite(hi) else None)}
        for g, (lo, hi) in TABLE1.items()
    ]
    rows = [{k: float(cols[k][i]) for k in ("h3",) + TABLE2_COLUMNS} for i in range(cols["h3"].size)]
    note = version.note
    if json_out:
        print_json({"table1": grades, "table2": {"version": table, "note": note, "rows": rows}})
        return
    from rich.table import Table

    t1 = Table(title=escape("Table 1: sea state vs h3% [m]"))
    t1.add_column("grade")
    t1.add_column("h3% [m]")
    for g in grades:
        hi = "above" if g["h3_max"] is None else f"{g['h3_max']:g}"
        t1.add_row(str(g["roman"]), f"{g['h3_min']:g} – {hi}")
    console.print(t1)
    t2 = Table(title=escape(f"Table 2 ({table}): μ [1/s], λ [rad/s] vs h3% [m]"), caption=note)
    for c in ("h3",) + TABLE2_COLUMNS:
        t2.add_column(c, justify="right")
    for r in rows:
        t2.add_row(*(f"{v:g}" for v in r.values()))
    console.print(t2)


def _roman(g: int) -> str:
    return ("I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX")[g - 1]


@app.command("spectrum")
@handle_errors
def spectrum_cmd(
    h3: _H3,
    model: Annotated[SpectrumName, typer.Option(
        "--model", metavar="NAME", help=f"Spectrum: {_names(SpectrumName)}.")
    ] = "rakhmanin-firsov-2",
    plot: Annotated[Path | None, typer.Option("--plot", help="Write a PNG of the spectrum.")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    table: _Table = "corrected",
    extrapolate: _Extrapolate = False,
) -> None:
    """Spectrum for a wave height: D_r, μ, λ, m0 (numerical), peak frequency."""
    from ..environment.sea_state import sea_state_parameters
    from ..environment.spectrum_base import spectral_moment
    from ..studies.sushchenko2010 import get_table2, spectrum_from_wave_height

    if plot is not None:  # checked before any work
        output_file("--plot", plot, "figure")
        check_figure_suffix("--plot", plot)
    _table_height(h3, extrapolate)
    params = sea_state_parameters(h3, table=get_table2(table), extrapolate=extrapolate)
    with warnings.catch_warnings():  # an extrapolated table has been warned of once above
        warnings.simplefilter("ignore")
        spec = spectrum_from_wave_height(model, h3, table=table, extrapolate=extrapolate)
    m0 = spectral_moment(spec, 0)
    result: dict[str, Any] = {
        "model": model,
        "h3": params.h3,
        "grade": params.grade,
        "table": table,
        "D_r": params.variance,
        "mu": params.decay_rate,
        "lambda": params.resonance_frequency,
        "m0": m0,
        "m0_closed_form": float(spec.variance),  # type: ignore[attr-defined]
        "peak_frequency": float(spec.peak_frequency),
        "convention": "one-sided S1(omega), K(tau) = int_0^inf S1 cos(omega tau) d omega",
    }
    if plot is not None:
        _save_spectrum_plot(spec, plot, h3)
        result["plot"] = str(plot)
    if json_out:
        print_json(result)
        return
    for k, v in result.items():
        console.print(f"{k:>16}: {v:.6g}" if isinstance(v, float) else f"{k:>16}: {v}", highlight=False, markup=False)


def _save_spectrum_plot(spec: Any, path: Path, h3: float) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from ..plotting.save import save_figure
    from ..plotting.waves import plot_spectrum

    fig = plt.figure()
    try:
        ax = plot_spectrum(spec, ax=fig.add_subplot())
        ax.set_title(f"{spec.name}, h3% = {h3:g} m")
    except BaseException:
        plt.close(fig)
        raise
    save_figure(fig, path, dpi=100)


@app.command("sample")
@handle_errors
def sample_cmd(
    h3: _H3,
    duration: Annotated[float, typer.Option("--duration", help="Length of each run [s].")],
    dt: Annotated[float, typer.Option("--dt", help="Sample interval Δt [s].")],
    seed: Annotated[int, typer.Option("--seed", min=0, help=(
        "Seed (>= 0); run i uses SeedSequence(seed).spawn(runs)[i]."))],
    runs: Annotated[int, typer.Option("--runs", help="Number of realisations.")] = 1,
    out: Annotated[Path | None, typer.Option("--out", help="Write a NetCDF file (h5netcdf).")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    model: Annotated[RationalSpectrumName, typer.Option(
        "--model", metavar="NAME",
        help=f"Spectrum with a shaping filter (Rakhmanin–Firsov): {_names(RationalSpectrumName)}.")
    ] = "rakhmanin-firsov-2",
    table: _Table = "corrected",
    extrapolate: _Extrapolate = False,
) -> None:
    """Seeded wave ordinate (and slope) realisations, discretised exactly."""
    from ..environment.shaping import shaping_filter
    from ..errors import ParameterError
    from ..studies.sushchenko2010 import spectrum_from_wave_height

    if runs < 1:
        raise ParameterError(f"`runs` must be >= 1, got {runs}")
    if out is not None:
        output_file("--out", out, "netcdf")
    _table_height(h3, extrapolate)
    spec = spectrum_from_wave_height(model, h3, table=table, extrapolate=extrapolate)
    filt = shaping_filter(spec, ("ordinate",))
    slope = shaping_filter(spec, ("ordinate", "slope"))
    if np.all(slope.D == 0.0):
        filt = slope
    if not (math.isfinite(dt) and dt > 0):
        raise ParameterError(f"`dt` must be > 0 [s], got {dt!r}")
    if not (math.isfinite(duration) and duration > 0):
        raise ParameterError(f"`duration` must be > 0 [s], got {duration!r}")
    ratio = duration / dt
    if ratio < 1.0 or abs(ratio - round(ratio)) > 1e-9 * max(ratio, 1.0):
        raise ParameterError(f"`--duration` must be a whole multiple (>= 1) of `--dt` [s]: "
                             f"duration={duration!r}, dt={dt!r}")
    steps = int(round(ratio)) + 1
    if steps * runs > MAX_SAMPLES:
        raise ParameterError(
            f"runs × steps = {steps * runs} exceeds {MAX_SAMPLES}; shorten --duration or --runs"
        )
    res = filt.sample(n_steps=steps, dt=dt, seed=seed, runs=runs)
    ordinate = res["ordinate"]
    result: dict[str, Any] = {
        "model": spec.name,
        "h3": float(h3),
        "seed": seed,
        "runs": runs,
        "steps": steps,
        "dt": res.dt,
        "samples": int(ordinate.size),
        "variance_expected": float(res.variance_expected[0]),
        "variance_sample": float(np.mean(ordinate**2)),
    }
    if "slope" in res.labels:
        result["slope_variance_expected"] = float(res.variance_expected[1])
        result["slope_variance_sample"] = float(np.mean(res["slope"] ** 2))
    if out is not None:
        ds = res.to_xarray()
        ds.attrs.update({"model": spec.name, "h3": float(h3), "table": table, "seed": seed,
                         WRITTEN_BY_ATTR: command_path() or "seahelm waves sample"})
        write_netcdf(ds, out)
        result["out"] = str(out)
    if json_out:
        print_json(result)
        return
    for k, v in result.items():
        console.print(f"{k:>24}: {v:.6g}" if isinstance(v, float) else f"{k:>24}: {v}", highlight=False, markup=False)


@app.command("figure")
@handle_errors
def figure_cmd(
    out: Annotated[Path, typer.Option("--out", help="PNG file to write.")] = Path("waves.png"),
    seed: Annotated[int, typer.Option("--seed", min=0,
                                      help="Seed (>= 0) of the sample realisations.")] = 0,
    duration: Annotated[float, typer.Option("--duration", help="Realisation length [s].")] = 200.0,
    force: ForceFlag = False,
) -> None:
    """The paper's figure: spectra for sea states 3, 6, 9, slope spectra, realisations."""
    import matplotlib

    matplotlib.use("Agg")
    from ..plotting.save import save_figure
    from ..studies.sushchenko2010 import plot_paper_figure

    if not (math.isfinite(duration) and 0 < duration <= MAX_FIGURE_DURATION):
        raise ParameterError(f"`--duration` must be in (0, {MAX_FIGURE_DURATION:g}] [s], got "
                             f"{duration!r}")
    output_file("--out", out, "figure")
    check_figure_suffix("--out", out)
    save_figure(plot_paper_figure(seed=seed, duration=duration), out, dpi=100)
    console.print(f"wrote {escape(str(out))}")
