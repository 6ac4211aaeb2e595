"""``seahelm encounter``: ships meeting ships — an encounter scenario (TOML with ``[[vessel]]``
tables), maritime-schema traffic situations (JSON, e.g. from ``trafficgen``), or a Monte-Carlo
of encounter geometry; outcome table by COLREG situation, result file and plots.

Exit codes: 0 success, 2 bad input (one-line reason on stderr), 1 other failure.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Annotated, Any

import typer

from ..errors import ParameterError
from ._common import ForceFlag, JsonFlag, _writable_directory, command_path, console, \
    handle_errors, output_dir, print_json, store_containing

_METHODS = ("none", "rule-based", "velocity-obstacles")
_FILES = ("encounters.nc", "tracks.png", "cpa.png", "rose.png")


#: Memory of one vessel's record in a run, with the simulator's and the result's arrays
#: (measured: 25 kB an encounter of two vessels and 121 records, with a margin of ~2).
_BYTES_PER_VESSEL_RECORD = 50


def _physical_memory() -> int:
    """The memory this process may use [bytes] (0 where the OS does not say): the smallest of
    the machine's, its cgroup's room and its address-space room, the one helper the library
    uses too (:func:`seahelm.resources.memory_limit`)."""
    from ..resources import memory_limit

    limit = memory_limit()
    return 0 if limit is None else int(limit.bytes)


def _encounter_ship(option: str, name: str) -> Any:
    """The catalog ship or ship file ``name`` of ``option`` (``--own-ship``/``--target-ship``).

    An encounter starts each vessel at a speed and scales the track-keeping autopilot's
    derivative time by L/U_0, so a ship without a test speed U_0 (the Otter, REMUS 100, the
    DP vessels; none of them steers by rudder either) is refused here, naming the option.
    """
    from ..ships import get_ship, ship_names

    try:
        ship = get_ship(name)
    except ParameterError:
        raise
    except ValueError as exc:
        raise ParameterError(f": {exc}", field=option, value=name) from None
    if ship.test_speed is None:
        with_speed = [n for n in ship_names() if get_ship(n).test_speed is not None]
        raise ParameterError(f": ship {name!r} has no test speed [m/s] (an encounter steers "
                             "each ship by rudder about its test speed); give a ship with "
                             f"one, e.g. {', '.join(with_speed)}",
                             field=option, unit="m/s", value=name)
    return ship


def _build(files: list[Path], monte_carlo: int | None, avoidance: str | None, own_ship: str,
           target_ship: str, t_final: float | None, seed: int, detection: float,
           targets_avoid: bool = False, overtaking: float = 0.0) -> Any:
    from ..encounters import Encounter
    from ..encounters.files import (is_encounter_scenario, parse_encounter_scenario,
                                    read_traffic_situations)
    from ..encounters.monte_carlo import monte_carlo_vessels

    method = None if avoidance in (None, "none") else avoidance
    # situations and --monte-carlo without --avoidance: velocity obstacles (the help's
    # default); --avoidance none: none
    chosen = "velocity-obstacles" if avoidance is None else method
    if monte_carlo is not None or (files and all(f.suffix.lower() == ".json" for f in files)):
        own_ship = _encounter_ship("--own-ship", own_ship)
        target_ship = _encounter_ship("--target-ship", target_ship)
    if monte_carlo is not None:
        if files:
            raise ParameterError(": give files or --monte-carlo, not both",
                                 field="--monte-carlo", value=monte_carlo)
        if monte_carlo < 1:
            raise ParameterError(f"must be >= 1 [encounters], got {monte_carlo}",
                                 field="--monte-carlo", value=monte_carlo)
        if not (math.isfinite(overtaking) and 0.0 <= overtaking <= 1.0):
            raise ParameterError(f"must be a share in 0 ... 1 [-], got {overtaking!r}",
                                 field="--overtaking", unit="-", value=overtaking)
        tf = 1200.0 if t_final is None else t_final
        if not (math.isfinite(detection) and detection > 926.0 / 0.75):
            raise ParameterError(f"must be > {926.0 / 0.75:.0f} [m] (the CPA is drawn within "
                                 f"±926 m at 0.75 × it), got {detection!r}",
                                 field="--detection", unit="m", value=detection)
        if seed < 0:
            raise ParameterError(f"must be an integer >= 0, got {seed}", field="--seed",
                                 value=seed)
        need = monte_carlo * _BYTES_PER_VESSEL_RECORD * 2 * (tf / 10.0 + 1)
        memory = _physical_memory()
        if memory and need > memory:
            raise ParameterError(f"needs about {need / 1e9:.3g} GB for its tracks ({tf:g} s), "
                                 f"more than the {memory / 1e9:.3g} GB this process may use: draw "
                                 f"fewer, or several batches with different --seed",
                                 field="--monte-carlo", value=monte_carlo)
        # overtaking closes at a few m/s: closer, within what the horizon lets close
        hi = max(min(0.35 * detection, 1.8 * tf), 1400.0)
        lo = max(1000.0, min(0.15 * detection, 0.75 * hi))
        try:
            vessels, _ = monte_carlo_vessels(
                monte_carlo, own_ship=own_ship, target_ship=target_ship, seed=seed,
                detection_range=(0.75 * detection, detection), tcpa=(0.1 * tf, 0.6 * tf),
                target_speed=(3.0, 8.0), targets_avoid=targets_avoid, overtaking=overtaking,
                overtaking_range=(lo, hi))
        except ParameterError as exc:
            if exc.field == "target_speed":
                raise ParameterError(f": no target detected at {detection:g} m reaches its "
                                     f"CPA within 0.1-0.6 x {tf:g} s at 3-8 m/s; give a longer "
                                     "--t-final or a shorter --detection", field="--t-final",
                                     unit="s", value=tf) from None
            if exc.field != "overtaking_range":
                raise
            raise ParameterError(f": {exc.reason.lstrip(': ')}; give a longer --t-final or "
                                 f"--overtaking 0", field="--overtaking", value=overtaking
                                 ) from None
        return lambda m: Encounter(vessels, t_final=tf, avoidance=m, record_every=10), chosen
    if not files:
        raise ParameterError(": give an encounter scenario (TOML), traffic situations (JSON) "
                             "or --monte-carlo N", field="FILES")
    if all(f.suffix.lower() == ".json" for f in files):
        tf = 1200.0 if t_final is None else t_final
        return (lambda m: read_traffic_situations(files, own_ship=own_ship,
                                                  target_ship=target_ship, t_final=tf,
                                                  avoidance=m, targets_avoid=targets_avoid),
                chosen)
    if len(files) != 1 or files[0].suffix.lower() != ".toml":
        raise ParameterError(f": one scenario (.toml) or traffic situations (.json), got "
                             f"{', '.join(f.name for f in files)}", field="FILES")
    if not files[0].is_file():
        raise ParameterError(": no such file", field=str(files[0]))
    data = tomllib.loads(files[0].read_text())
    if not is_encounter_scenario(data):
        raise ParameterError(": not an encounter scenario (no [[vessel]] array of tables); "
                             "run a single-vessel scenario with `seahelm run`",
                             field=str(files[0]))
    base = files[0].parent
    if t_final is not None:
        data = {**data, "encounter": {**data.get("encounter", {}), "t_final": t_final}}
    if targets_avoid and isinstance(data.get("vessel"), list):
        data = {**data, "vessel": [{**v, "avoid": True} if isinstance(v, dict) else v
                                   for v in data["vessel"]]}

    def make(m: Any) -> Any:
        d = data if m == "scenario" else {**data, "encounter": {
            **{k: v for k, v in data.get("encounter", {}).items() if k != "avoidance"},
            **({} if m is None else {"avoidance": m})}}
        return parse_encounter_scenario(d, base=base)
    return make, ("scenario" if avoidance is None else method)


def _name(method: Any) -> str:
    from ..encounters.avoidance import AVOIDANCE

    if method is None:
        return "none"
    return next((k for k, v in AVOIDANCE.items() if type(method) is v), type(method).__name__)


def _rows(result: Any) -> list[dict[str, Any]]:
    return result.summary()


def _print(label: str, rows: list[dict[str, Any]]) -> None:
    """The outcome table by situation, as a rich table (the CLI's consoles fit it to the
    terminal, or a pipe's 80 columns). A near miss is the target inside the own ship's domain
    without a collision."""
    from rich.markup import escape
    from rich.table import Table

    def pct(v: Any) -> str:
        return "-" if v is None else f"{100 * v:.1f} %"

    def ci(c: Any) -> str:
        return f"{100 * c[0]:.1f}-{100 * c[1]:.1f} %"

    table = Table(title=escape(label), title_justify="left")
    for name in ("situation", "n", "collision", "95% CI", "near miss", "95% CI",
                 "give-way acted", "substantial", "stand-on kept",
                 "stand-on to port (17c)", "median least range [m]"):
        table.add_column(escape(name), justify="left" if name == "situation" else "right")
    for r in rows:
        table.add_row(r["situation"], str(r["encounters"]), pct(r["collision"]),
                      ci(r["collision_ci"]), pct(r["near_miss"]), ci(r["near_miss_ci"]),
                      pct(r["own_acted"]), pct(r["own_substantial"]),
                      pct(r["own_kept_course"]), pct(r.get("own_altered_to_port")),
                      f"{r['min_range_median']:.0f}")
    console.print(table)


def _write(result: Any, out: Path, force: bool, label: str) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    from ..plotting.encounters import plot_cpa, plot_encounter_tracks, plot_outcome_rose
    from ..plotting.save import save_figure
    from ..results import write_netcdf

    ds = result.to_xarray()
    ds.attrs["seahelm_command"] = command_path() or "seahelm encounter"
    ds.attrs["avoidance"] = label
    write_netcdf(ds, out / "encounters.nc", force=force)
    if result.lengths.size > 1:
        worst = int(result.min_range[:, 0].argmin())
        save_figure(plot_encounter_tracks(result, worst), out / "tracks.png", force=force)
        save_figure(plot_cpa(result), out / "cpa.png", force=force)
        save_figure(plot_outcome_rose(result), out / "rose.png", force=force)


@handle_errors
def encounter(
    files: Annotated[list[Path] | None, typer.Argument(
        help="An encounter scenario (TOML, [[vessel]] tables) or maritime-schema traffic "
             "situations (JSON, one encounter each).")] = None,
    monte_carlo: Annotated[int | None, typer.Option(
        "--monte-carlo", help="Draw N two-ship encounters (bearing all round, CPA within "
                              "±0.5 nmi at detection; a share --overtaking of them "
                              "overtaking) instead of reading files.")] = None,
    avoidance: Annotated[str | None, typer.Option(
        help=f"Own ship's avoidance: {', '.join(_METHODS)} (default: the scenario's; "
             "velocity-obstacles for situations and --monte-carlo).")] = None,
    compare: Annotated[bool, typer.Option(
        "--compare", help="Run every method (none, rule-based, velocity-obstacles) side "
                          "by side.")] = False,
    own_ship: Annotated[str, typer.Option(help="Own ship of situations / --monte-carlo.")
                        ] = "kvlcc2-full",
    target_ship: Annotated[str, typer.Option(help="Target ship of situations / "
                                                  "--monte-carlo.")] = "kvlcc2-full",
    t_final: Annotated[float | None, typer.Option(
        "--t-final", help="Duration [s] (default the scenario's; 1200).")] = None,
    detection: Annotated[float, typer.Option(
        help="--monte-carlo: range at detection [m] (drawn in 0.75 ... 1 times it).")
    ] = 9000.0,
    seed: Annotated[int, typer.Option(help="--monte-carlo seed.")] = 0,
    overtaking: Annotated[float, typer.Option(
        help="--monte-carlo: share of the encounters drawn as overtaking (half with the own "
             "ship overtaking a slower target ahead, half overtaken, at half speed, by one "
             "from astern), at 0.15 ... 0.35 times --detection.")] = 0.2,
    workers: Annotated[int | None, typer.Option(
        "--workers", help="Run the encounters in chunks on a local dask cluster of N "
                          "processes (as `seahelm sweep --workers`); the same result.")] = None,
    chunk_size: Annotated[int | None, typer.Option(
        "--chunk-size", help="Encounters per chunk (in this process without --workers; "
                             "default: the encounters over 4 per worker).")] = None,
    targets_avoid: Annotated[bool, typer.Option(
        "--targets-avoid", help="The targets use the same avoidance method as the own ship "
                                "(default: they keep their course or route; in a scenario, "
                                "`avoid = true` in a [[vessel]] table).")] = False,
    out: Annotated[Path | None, typer.Option(
        help=f"Write {', '.join(_FILES)} here (the last method's with --compare).")] = None,
    store: Annotated[Path | None, typer.Option(
        "--store", help="Zarr store directory (e.g. study.zarr): each chunk written as it "
                        "finishes, one study per avoidance method; an interrupted study "
                        "is resumed by the same command (the chunks written are "
                        "skipped).")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Ships meeting ships: run encounters, print outcomes by COLREG situation (collisions,
    ship-domain intrusions with 95 % intervals, Rule 8/16/17 verdicts)."""
    if avoidance is not None and avoidance not in _METHODS:
        raise ParameterError(f"must be one of {', '.join(_METHODS)}, got {avoidance!r}",
                             field="--avoidance", value=avoidance)
    if t_final is not None and not (math.isfinite(t_final) and t_final > 0):
        raise ParameterError(f"must be > 0 [s], got {t_final!r}", field="--t-final", unit="s",
                             value=t_final)
    for name, value in (("--workers", workers), ("--chunk-size", chunk_size)):
        if value is not None and value < 1:
            raise ParameterError(f"must be >= 1, got {value}", field=name, value=value)
    if out is not None:
        output_dir("--out", out, _FILES, reads=tuple(files or ()), force=force)
    if store is not None:
        if any(Path(f).resolve() == store.resolve() for f in files or ()):
            raise ParameterError(f"`--store` {store} is a file this command reads: writing "
                                 "the store there would destroy it; choose another path")
        outer = store_containing(store.parent)
        if outer is not None:
            raise ParameterError(f"`--store` {store} is inside the store {outer}: writing "
                                 "there would corrupt it; choose a path outside it")
    make, method = _build(list(files or []), monte_carlo, avoidance, own_ship, target_ship,
                          t_final, seed, detection, targets_avoid, overtaking)
    methods = ([None, "rule-based", "velocity-obstacles"] if compare else [method])
    encounters = [make(m) for m in methods]  # (all validated before any runs)
    if encounters[0].n_vessels < 2:
        raise ParameterError(": an encounter needs the own ship and at least one target, got "
                             f"{encounters[0].n_vessels} vessel", field="vessel",
                             value=encounters[0].n_vessels)
    payload: dict[str, Any] = {"seahelm_command": command_path() or "seahelm encounter",
                               "methods": {}}
    labels = [m if m not in (None, "scenario") else _name(enc.avoidance)
              for m, enc in zip(methods, encounters)]
    sizes: list[int | None] = [chunk_size] * len(encounters)
    if store is not None:
        from ..sweep.encounter_store import check_study_store, stored_chunk_size

        for i, (name, enc) in enumerate(zip(labels, encounters)):
            held = stored_chunk_size(store, name) if chunk_size is None else None
            sizes[i] = held or chunk_size or max(1, math.ceil(enc.n_encounters
                                                               / (4 * (workers or 1))))
        check_study_store(store, {name: (enc, c) for name, enc, c
                                  in zip(labels, encounters, sizes)}, force=force)
        _writable_directory("--store", store.parent)
        payload["store"] = str(store)
    result, label = None, ""
    for m, enc, label, size in zip(methods, encounters, labels, sizes):
        if store is not None:
            from ..sweep.encounter_store import run_study

            counts: list[int] = []
            result = run_study(enc, store, label, chunk_size=size, workers=workers,
                               force=force, on_chunk=lambda d, n: counts.append(d) or None)
            if not json_out:
                console.print(f"store {store}, study {label}: {counts[0]} of "
                              f"{math.ceil(enc.n_encounters / size)} chunk(s) there before, "
                              f"{counts[-1] - counts[0]} run now", highlight=False,
                              soft_wrap=True)
        elif workers is None and chunk_size is None:
            result = enc.run()
        else:
            from ..encounters.chunked import run_chunked

            result = run_chunked(enc, chunk_size=chunk_size, workers=workers)
        rows = _rows(result)
        payload["methods"][label] = rows
        if not json_out:
            _print(f"{enc.n_encounters} encounter(s) of {enc.n_vessels} vessels, "
                   f"{enc.t_final:g} s — own ship's avoidance: {label}", rows)
    if out is not None and result is not None:
        _write(result, out, force, label)
    if json_out:
        print_json(payload)
