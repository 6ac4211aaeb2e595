"""``seahelm seakeeping SHIP --hs HS --tp TP``: seakeeping statistics over speed × heading.

The closed-form RAOs of the ship's particulars (:func:`seahelm.environment.rao.closed_form_rao`,
re-evaluated at every speed) — or, with ``--rao FILE``, the RAOs of a file at its speed — in a
wave spectrum, optionally short-crested (``--spreading``): the response's spectral moments
(:mod:`seahelm.analysis.seakeeping`), its RMS, significant amplitude (2√m0), mean zero
up-crossing period and, with ``--exceed``, the probability of exceeding that level at least
once in ``--duration`` (:mod:`seahelm.analysis.seakeeping.response_statistics`). Prints a table (a
summary per speed for grids of more than 40 cells); ``--out DIR`` writes ``seakeeping.nc``
(all dofs, SI units) and the polar diagram ``seakeeping-<dof>.png``, together or not at all.
Roll and pitch are shown in degrees, heave in metres; ``--limit`` and ``--exceed`` are in
those units. Exit codes: 0, 2 bad input (one ``error:`` line naming the option and its unit; a
ship without particulars or, for roll, without a metacentric height), 1 other failure.
``--sweep STORE`` draws a time-domain sweep's polar diagram instead
(:mod:`seahelm.cli.seakeeping_sweep`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ..environment.directional_spreading import MAX_DIRECTIONS, MAX_S
from ..environment.spectra import sea_spectrum_names
from ..errors import ParameterError
from ._common import ForceFlag, JsonFlag, console, handle_errors, input_file, output_dir, print_json

__all__ = ["seakeeping"]

#: The result files ``--out`` writes (the figure's name carries the dof).
NETCDF_NAME = "seakeeping.nc"
#: Largest grid printed cell by cell; above it, one summary row per speed.
MAX_TABLE_CELLS = 40
#: Largest speeds × headings grid computed.
MAX_CELLS = 100_000
#: Numerical bounds of the grids (beyond them the RAOs overflow: speeds of 1e300 gave NaN
#: moments; those of the sea state are :data:`seahelm.environment.spectra.SEA_BOUNDS`); every
#: value inside computes finite moments (measured at each end). The closed form's own
#: validity range (Fn <= 0.4) warns well inside them.
#: Above this significant wave height [m] a warning: the highest measured is 19.0 m (a North
#: Atlantic buoy, 4 February 2013; WMO 2016).
HS_HIGHEST = 20.0
#: ``--spreading-s``'s default.
DEFAULT_SPREADING_S = 10.0
SPEED_MAX = 100.0
HEADING_MAX = 360.0

#: The spectra of a sea by Hs (and Tp, γ): those of the registry that take a significant
#: height (:func:`seahelm.environment.spectra.sea_spectrum`), from the registry.
SpectrumName = Literal[sea_spectrum_names()]  # type: ignore[valid-type]
SpreadingName = Literal["none", "cos2", "cos-2s"]
Dof = Literal["roll", "pitch", "heave"]
Statistic = Literal["rms", "significant"]
RollExcitation = Literal["averaged", "slope"]


def parse_grid(option: str, text: str, unit: str) -> np.ndarray:
    """``START:STOP:N`` (N values, both ends included) or a comma-separated list.

    Parameters
    ----------
    option : str
        The option, for the error message.
    text : str
        The grid as typed.
    unit : str
        The unit of its values, for the error message.

    Returns
    -------
    numpy.ndarray
        The values, strictly increasing.

    Raises
    ------
    ParameterError
        Empty, malformed, non-finite or not increasing.
    """
    def bad(why: str) -> ParameterError:
        return ParameterError(f"{why} [{unit}], got {text!r}", field=option.lstrip("-"),
                              unit=unit, value=text)

    parts = [p.strip() for p in text.split(":")] if ":" in text else None
    if parts is not None and len(parts) != 3:
        raise bad("must be START:STOP:N or a comma-separated list")
    try:  # (a ParameterError is a ValueError: the checks come after)
        if parts is not None:
            start, stop, n = float(parts[0]), float(parts[1]), int(parts[2])
        else:
            values = np.array([float(p) for p in text.split(",") if p.strip()])
    except ValueError:
        raise bad("must be START:STOP:N or a comma-separated list of numbers") from None
    if parts is not None:
        if n < 1 or (n == 1 and start != stop):  # (this message was the generic one before)
            raise bad("needs N >= 1 (N = 1 only with START = STOP)")
        if n > MAX_CELLS:  # (np.linspace of 10^11 values was a MemoryError)
            raise bad(f"needs N <= {MAX_CELLS}")
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise bad("must be finite")  # (np.linspace warned before the error)
        values = np.linspace(start, stop, n)
    if values.size == 0:
        raise bad("must hold at least one value")
    if not np.all(np.isfinite(values)):
        raise bad("must be finite")
    if values.size > 1 and not np.all(np.diff(values) > 0):
        raise bad("must be strictly increasing")
    return values


def _positive(option: str, value: float | None, unit: str) -> None:
    if value is not None and not (math.isfinite(value) and value > 0):
        raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=option, unit=unit,
                             value=value)


def _within(option: str, value: float, unit: str, low: float, high: float,
            low_open: bool = False) -> None:
    if not (math.isfinite(value) and (value > low if low_open else value >= low)
            and value <= high):
        raise ParameterError(f"must be in {'(' if low_open else '['}{low:g}, {high:g}] "
                             f"[{unit}], got {value!r}", field=option, unit=unit, value=value)


#: The library's spectrum parameter -> this command's option.
_SEA_OPTIONS = {"significant_height": "hs", "peak_period": "tp", "gamma": "gamma"}


def _spectrum(name: str, hs: float, tp: float | None, gamma: float | None) -> Any:
    """:func:`seahelm.environment.spectra.sea_spectrum` (which parameters each spectrum
    takes, their bounds), its errors naming the options; Hs above the highest measured warns."""
    from ..environment.spectra import sea_spectrum

    try:
        spec = sea_spectrum(name, significant_height=hs, peak_period=tp, gamma=gamma)
    except ParameterError as exc:
        raise ParameterError(exc.reason, field=_SEA_OPTIONS.get(exc.field or "", exc.field),
                             unit=exc.unit, value=exc.value) from None
    if hs > HS_HIGHEST:
        from ..errors import warn_validity

        warn_validity(f"`--hs` = {hs:g} m is above {HS_HIGHEST:g} m, more than the highest "
                      "significant wave height ever measured (19 m, WMO 2016): a unit or a "
                      "typing mistake?")
    return spec


def _display(dof: str) -> tuple[float, str]:
    """Factor from SI to the shown unit, and that unit."""
    return (1.0, "m") if dof == "heave" else (180.0 / math.pi, "deg")


@handle_errors
def seakeeping(
    ship: Annotated[str | None, typer.Argument(
        metavar="[SHIP]", help="A catalog ship (`seahelm ship list`) or a ship file; its "
                               "particulars give the closed-form RAOs.")] = None,
    hs: Annotated[float | None, typer.Option("--hs", help="Significant wave height Hs [m].")
                  ] = None,
    tp: Annotated[float | None, typer.Option(
        "--tp", help="Peak period Tp [s] (not for pierson-moskowitz).")] = None,
    spectrum: Annotated[SpectrumName, typer.Option(
        "--spectrum", help="Wave spectrum: jonswap, bretschneider (= ittc), "
                           "pierson-moskowitz.")] = "jonswap",
    gamma: Annotated[float | None, typer.Option(
        "--gamma", help="JONSWAP peak enhancement γ [-] (jonswap only).", show_default="3.3")
    ] = None,
    speeds: Annotated[str | None, typer.Option(
        "--speeds", help="Ship speeds [m/s]: START:STOP:N or a list (default 0 to the ship's "
                         "test speed, 5 values).")] = None,
    headings: Annotated[str, typer.Option(
        "--headings", help="Mean wave headings relative to the ship [deg] (0 following, 180 "
                           "head, 90 waves from port): START:STOP:N or a list.")
    ] = "0:360:37",
    dof: Annotated[Dof, typer.Option(
        "--dof", help="Response shown in the table and the figure (the NetCDF has all).")
    ] = "roll",
    stat: Annotated[Statistic, typer.Option(
        "--stat", help="Statistic of the figure and --limit: rms or significant (2√m0).")
    ] = "rms",
    limit: Annotated[float | None, typer.Option(
        "--limit", help="Criterion on --stat, drawn and counted [deg for roll and pitch, m for "
                        "heave].")] = None,
    exceed: Annotated[float | None, typer.Option(
        "--exceed", help="Level whose exceedance probability in --duration is given [deg for "
                         "roll and pitch, m for heave].")] = None,
    duration: Annotated[float, typer.Option(
        "--duration", help="Exposure time of --exceed and of the most probable maximum "
                           "(--json) [s].")] = 3600.0,
    both_sides: Annotated[bool, typer.Option(
        "--both-sides", help="--exceed counts |x| > level (both sides), not x > level.")
    ] = False,
    spreading: Annotated[SpreadingName, typer.Option(
        "--spreading", help="Directional spreading: none (long-crested), cos2, cos-2s.")
    ] = "none",
    spreading_s: Annotated[float | None, typer.Option(
        "--spreading-s", show_default="10", help="The s of cos-2s [-] (with --spreading "
        "cos-2s).")] = None,
    directions: Annotated[int, typer.Option(
        "--directions", help="Directions of the spreading's quadrature [-].")] = 36,
    gm: Annotated[float | None, typer.Option(
        "--gm", help="Metacentric height GM [m] for roll (default: the ship's, if its model "
                     "has one).")] = None,
    roll_period: Annotated[float | None, typer.Option(
        "--roll-period", help="Natural roll period [s] (default the IMO estimate from GM).")
    ] = None,
    roll_damping: Annotated[float, typer.Option(
        "--roll-damping", help="Roll damping ratio ζ [-].")] = 0.1,
    roll_excitation: Annotated[RollExcitation, typer.Option(
        "--roll-excitation", help="The closed-form roll's excitation: the wave slope averaged "
                                  "over the hull (short waves reduced) or the full slope.")
    ] = "averaged",
    rao: Annotated[Path | None, typer.Option(
        "--rao", help="An RAO file (CSV table, seahelm or capytaine NetCDF) instead of the "
                      "closed form; its speed is the only speed.")] = None,
    out: Annotated[Path | None, typer.Option(
        "--out", help=f"Directory for {NETCDF_NAME} and the polar diagram.")] = None,
    sweep: Annotated[Path | None, typer.Option(
        "--sweep", help="A sweep store of first-order wave motions over wave heading x speed "
                        "(`seahelm sweep`): its time-domain polar diagram, each cell with its "
                        "standard error and the frequency domain beside it (the sea, ship and "
                        "speeds are the sweep's).")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Seakeeping in a sea state: RMS, significant amplitude, exceedance, polar diagram."""
    from ..analysis.seakeeping.frequency_domain import closed_form_moments, response_moments

    if sweep is not None:
        given = _given_besides(("dof", "limit", "out", "sweep", "json_out"))
        if given:
            raise ParameterError(f"`--sweep` takes the sea, the ship and the speeds from the "
                                 f"sweep's scenario; give no {', '.join(given)} with it (it "
                                 "takes --dof, --limit, --out and --json; the statistic is the "
                                 "RMS)")
        factor, unit = _display(dof)
        _positive("limit", limit, unit)
        from .seakeeping_sweep import sweep_command

        sweep_command(sweep, dof=dof, limit=limit, out=out, json_out=json_out)
        return
    if (ship is None) == (rao is None):
        raise ParameterError("give a SHIP or `--rao FILE` (one of them)")
    if hs is None:
        raise ParameterError("is required [m]", field="hs", unit="m")
    spec = _spectrum(spectrum, hs, tp, gamma)
    factor, unit = _display(dof)
    for option, value in (("limit", limit), ("exceed", exceed)):
        _positive(option, value, unit)
    _positive("duration", duration, "s")
    if spreading_s is not None and spreading != "cos-2s":
        raise ParameterError(f"= {spreading_s!r} is the s of `--spreading cos-2s`, not of "
                             f"`--spreading {spreading}`: drop it or give `--spreading cos-2s`",
                             field="spreading_s", value=spreading_s)
    spreading_s = DEFAULT_SPREADING_S if spreading_s is None else spreading_s
    _within("spreading_s", spreading_s, "-", 0.0, MAX_S, low_open=True)
    if not 1 <= directions <= MAX_DIRECTIONS:
        raise ParameterError(f"must be in [1, {MAX_DIRECTIONS}] [-], got {directions}",
                             field="directions", unit="-", value=directions)
    for option, value, u in (("gm", gm, "m"), ("roll_period", roll_period, "s")):
        _positive(option, value, u)
    if not (math.isfinite(roll_damping) and 0 < roll_damping <= 1):
        raise ParameterError(f"must be in (0, 1] [-], got {roll_damping!r}",
                             field="roll_damping", unit="-", value=roll_damping)
    eps = parse_grid("--headings", headings, "deg")
    if np.any(np.abs(eps) > HEADING_MAX):
        raise ParameterError(f"must be within ±{HEADING_MAX:g} [deg], got {headings!r}",
                             field="headings", unit="deg", value=headings)
    eps = np.radians(eps)
    spread: Any = None
    if spreading != "none":
        from ..environment.directional_spreading import get_spreading

        spread = get_spreading(spreading, **({"s": spreading_s} if spreading == "cos-2s"
                                             else {}))
    reads: tuple[Path, ...] = ()
    if rao is not None:
        if speeds is not None:
            raise ParameterError("cannot be given with `--rao` (the file's RAOs hold at its "
                                 "speed)", field="speeds")
        input_file("--rao", rao)
        reads = (rao,)
    names = (NETCDF_NAME, f"seakeeping-{dof}.png")
    if out is not None:
        output_dir("--out", out, names, reads=reads)
    if rao is not None:
        from ..environment.rao_io import read_rao

        table = read_rao(rao)
        if dof not in table.dofs:
            raise ParameterError(f"is not in {rao} (it has {', '.join(table.dofs)})",
                                 field="dof", value=dof)
        name = rao.name
        U = np.array([table.speed])
        _check_cells(U, eps)
        moments = response_moments(table, spec, eps, spreading=spread,
                                   n_directions=directions)
    else:
        from ..ships import get_ship

        the_ship = get_ship(ship)
        name = the_ship.name
        if the_ship.particulars is None:
            raise ParameterError(f"ship {name} has no [particulars] (length, beam, draft, "
                                 "block_coefficient): the closed-form RAOs need them; add "
                                 "them to its ship file")
        if gm is None:  # the particulars' GM, else the model's (the 4-DOF container's)
            gm = the_ship.particulars.metacentric_height
        if gm is None:
            gm = getattr(the_ship.params, "metacentric_height", None)
        if dof == "roll" and gm is None and roll_period is None:
            raise ParameterError(f"is not known for ship {name} [m]: roll needs the "
                                 "metacentric height GM (or `--roll-period` [s]; or choose "
                                 "`--dof heave` or `--dof pitch`)", field="gm", unit="m")
        if speeds is None:
            if the_ship.test_speed is None:
                raise ParameterError("is required: the ship has no test speed [m/s]",
                                     field="speeds", unit="m/s")
            speeds = f"0:{the_ship.test_speed:.6g}:5"
        U = parse_grid("--speeds", speeds, "m/s")
        if np.any(U < 0) or np.any(U > SPEED_MAX):
            raise ParameterError(f"must be in [0, {SPEED_MAX:g}] [m/s], got {speeds!r}",
                                 field="speeds", unit="m/s", value=speeds)
        _check_cells(U, eps)
        moments = closed_form_moments(the_ship, spec, U, eps, spreading=spread,
                                      n_directions=directions, metacentric_height=gm,
                                      roll_period=roll_period, roll_damping=roll_damping,
                                      roll_excitation=roll_excitation)
    payload = _payload(name, moments, spec, dof, stat, factor, unit, limit, exceed, duration,
                       both_sides)
    if out is not None:
        _write(out, names, moments, payload, dof, stat, factor, unit, limit, name, spec)
        payload["files"] = [str(out / n) for n in names]
    if json_out:
        print_json(payload)
        return
    _print(payload, unit)


def _given_besides(used: tuple[str, ...]) -> list[str]:
    """The command's parameters given on the command line other than ``used`` (as SHIP or
    their first option name): a ``--stat significant`` or ``--exceed`` that ``--sweep`` would
    ignore without a word."""
    import importlib

    # the click typer runs on: click itself (typer < 0.26) or typer's vendored copy
    core = importlib.import_module(next(
        c.__module__ for c in typer.Context.__mro__ if c.__name__ == "Context"
        and c.__module__.endswith(".core")))
    ctx = importlib.import_module(core.__name__[:-len("core")] + "globals"
                                  ).get_current_context(silent=True)
    if ctx is None:
        return []
    given = (core.ParameterSource.COMMANDLINE, core.ParameterSource.ENVIRONMENT)
    return [p.opts[0] if p.opts[0].startswith("-") else "SHIP" for p in ctx.command.params
            if p.name not in used and ctx.get_parameter_source(p.name) in given]


def _check_cells(U: np.ndarray, eps: np.ndarray) -> None:
    if U.size * eps.size > MAX_CELLS:
        raise ParameterError(f"speeds × headings = {U.size * eps.size} cells exceed "
                             f"{MAX_CELLS}; use coarser `--speeds` or `--headings`")


def _payload(name: str, moments: Any, spec: Any, dof: str, stat: str, factor: float,
             unit: str, limit: float | None, exceed: float | None, duration: float,
             both_sides: bool) -> dict[str, Any]:
    rms = moments.rms(dof) * factor
    sig = moments.significant_amplitude(dof) * factor
    tz = moments.zero_crossing_period(dof)
    shown = rms if stat == "rms" else sig
    mpm = moments.most_probable_maximum(dof, duration) * factor
    cells = []
    prob = None
    if exceed is not None:
        prob = moments.exceedance_probability(dof, exceed / factor, duration,
                                              both_sides=both_sides)
    for i, U in enumerate(moments.speed):
        for j, e in enumerate(moments.heading):
            cell = {"speed_mps": float(U), "heading_deg": math.degrees(float(e)),
                    f"rms_{unit}": float(rms[i, j]), f"significant_amplitude_{unit}":
                    float(sig[i, j]),
                    "zero_crossing_period_s": None if not np.isfinite(tz[i, j])
                    else float(tz[i, j])}
            cell[f"most_probable_maximum_{unit}"] = (None if not np.isfinite(mpm[i, j])
                                                     else float(mpm[i, j]))
            if prob is not None:
                cell["exceedance_probability"] = float(prob[i, j])
            cells.append(cell)
    payload: dict[str, Any] = {
        "ship": name, "dof": dof, "unit": unit, "statistic": stat,
        "sea": {"spectrum": type(spec).__name__, "description": repr(spec)},
        "spreading": moments.description.get("spreading"),
        "raos": moments.description.get("raos"),
        "conventions": "heading 0 following, 180 head, 90 waves travelling to starboard "
                       "(from port); significant amplitude = 2 sqrt(m0); periods in encounter; "
                       "most probable maximum sqrt(2 m0 ln N) of N = duration/T_z amplitudes",
        "duration_s": duration,
        "cells": cells,
    }
    if limit is not None:
        payload["limit"] = {"value": limit, "unit": unit, "statistic": stat,
                            "cells_above": int(np.sum(shown > limit)), "cells": int(shown.size)}
    if exceed is not None:
        payload["exceedance"] = {"level": exceed, "unit": unit, "duration_s": duration,
                                 "both_sides": both_sides}
    return payload


def _write(out: Path, names: tuple[str, ...], moments: Any, payload: dict[str, Any], dof: str,
           stat: str, factor: float, unit: str, limit: float | None, name: str,
           spec: Any) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    from ..plotting.save import save_figure
    from ..plotting.seakeeping import plot_polar_diagram
    from ..results import write_netcdf, write_together

    ds = moments.to_xarray()
    ds.attrs.update({"ship": name, "title": f"seakeeping of {name}"})
    values = (moments.rms(dof) if stat == "rms" else moments.significant_amplitude(dof)) * factor
    label = f"{'RMS' if stat == 'rms' else 'significant'} {dof}"
    ax = plot_polar_diagram(moments.speed, moments.heading, values, label=label, unit=unit,
                            limit=limit, title=f"{name}: {label} [{unit}] in "
                            f"{type(spec).__name__} Hs {spec.significant_height:g} m"
                            + (f", Tp {spec.peak_period:g} s"
                               if hasattr(spec, "peak_period") else ""))
    with write_together():
        write_netcdf(ds, out / names[0])
        save_figure(ax.figure, out / names[1], dpi=100)


def _print(payload: dict[str, Any], unit: str) -> None:
    cells = payload["cells"]
    dof = payload["dof"]
    console.print(escape(f"{payload['ship']}: {dof} in {payload['sea']['description']}; "
                         f"spreading {payload['spreading']}"), highlight=False)
    prob_col = "exceedance" in payload
    table = Table(title_justify="left")
    rms_key, sig_key = f"rms_{unit}", f"significant_amplitude_{unit}"
    if len(cells) <= MAX_TABLE_CELLS:
        table.title = escape(f"{dof} per cell (significant amplitude = 2 sqrt(m0))")
        cols = ["U [m/s]", "heading [deg]", f"RMS [{unit}]", f"signif. ampl. [{unit}]",
                "Tz [s]"]
        if prob_col:
            e = payload["exceedance"]
            cols.append(f"P(>{e['level']:g} {unit} in {e['duration_s']:g} s)")
        for c in cols:
            table.add_column(escape(c), justify="right")
        tiny = 1e-9 * max(c[rms_key] for c in cells)  # round-off (sin π = 1.2e-16): shown 0

        def shown(v: float) -> str:
            return "0" if abs(v) <= tiny else f"{v:.4g}"

        for c in cells:
            row = [f"{c['speed_mps']:.3g}", f"{c['heading_deg']:.4g}", shown(c[rms_key]),
                   shown(c[sig_key]), "-" if c["zero_crossing_period_s"] is None
                   else f"{c['zero_crossing_period_s']:.4g}"]
            if prob_col:
                row.append(f"{c['exceedance_probability']:.3g}")
            table.add_row(*row)
    else:
        table.title = escape(f"{dof} per speed over {len(cells)} cells (largest over the "
                             "headings)")
        cols = ["U [m/s]", f"max RMS [{unit}]", "at heading [deg]",
                f"max signif. ampl. [{unit}]"]
        if prob_col:
            cols.append("max P(exceed)")
        for c in cols:
            table.add_column(escape(c), justify="right")
        by_speed: dict[float, list[dict[str, Any]]] = {}
        for c in cells:
            by_speed.setdefault(c["speed_mps"], []).append(c)
        for U, group in by_speed.items():
            top = max(group, key=lambda c: c[rms_key])
            row = [f"{U:.3g}", f"{top[rms_key]:.4g}", f"{top['heading_deg']:.4g}",
                   f"{max(c[sig_key] for c in group):.4g}"]
            if prob_col:
                row.append(f"{max(c['exceedance_probability'] for c in group):.3g}")
            table.add_row(*row)
    console.print(table)
    if "limit" in payload:
        lim = payload["limit"]
        console.print(escape(f"{lim['statistic']} {dof} above {lim['value']:g} {unit}: "
                             f"{lim['cells_above']} of {lim['cells']} cells"), highlight=False)
    for f in payload.get("files", []):
        console.print(f"wrote {escape(f)}", highlight=False)
