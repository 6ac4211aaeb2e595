"""Top-level commands of ``seahelm``: demo, run, models, plot, --version."""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer

from .. import __version__, stop_request
from ..errors import ParameterError
from ._common import (
    ForceFlag,
    JsonFlag,
    OneLineErrors,
    ProgressBar,
    check_figure_suffix,
    exit_if_diverged,
    fail_bad_input,
    console,
    handle_errors,
    input_file,
    output_dir,
    output_file,
    print_json,
)
from ._outputs import REPORT_NAME  # (run --report, demo: the name seahelm report gives too)
from ._runs import (
    batch_columns,
    diverged_runs,
    diverged_table,
    monte_carlo_statistics,
    run_units,
    statistics_tables,
    status_counts,
    summary_table,
)

app = typer.Typer(
    cls=OneLineErrors,
    name="seahelm",
    help="Batched, validated ship motion simulation and control.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

# Subcommand groups of the paper modules: (name, module, help).
_GROUPS = (
    ("waves", "seahelm.cli.waves", "Sea-wave spectra, sea-state tables and disturbance signals."),
    ("identify", "seahelm.cli.identify", "Identify steering-model coefficients from turns."),
    ("averaging", "seahelm.cli.averaging", "Full averaging of the CPP ship in waves."),
    ("compensate", "seahelm.cli.compensate", "Wave/wind forces and compensating rudder angle."),
    ("maneuver", "seahelm.cli.maneuver",
     "Standard manoeuvres: turning circle, zig-zag, spiral, pull-out, stopping."),
    ("ship", "seahelm.cli.ship", "Ships: the catalog, and ship files (TOML)."),
    ("autopilot", "seahelm.cli.autopilot", "Autopilot design: PID and LQ gains from the ship."),
    ("dp", "seahelm.cli.dp", "Dynamic positioning: thrust allocation, capability (level 1)."),
)
for _name, _module, _help in _GROUPS:
    try:
        _sub = importlib.import_module(_module)
    except ModuleNotFoundError as _exc:  # a group not built yet
        if _exc.name != _module:
            raise
        continue
    app.add_typer(_sub.app, name=_name, help=_help)
# Commands that add themselves to a group's app, in modules of their own: `maneuver stopping`.
for _module in ("seahelm.cli.stopping",):
    importlib.import_module(_module)

# Single commands of their own modules: (name, module, function).
_COMMANDS = (("imo", "seahelm.cli.imo", "imo"), ("inspect", "seahelm.cli.inspect", "inspect"),
             ("report", "seahelm.cli.report", "report"), ("sweep", "seahelm.cli.sweep", "sweep"),
             ("linearize", "seahelm.cli.linearize", "linearize"),
             ("seakeeping", "seahelm.cli.seakeeping", "seakeeping"),
             ("replay", "seahelm.cli.replay", "replay"), ("models", "seahelm.cli.models", "models"),
             ("encounter", "seahelm.cli.encounter", "encounter"),
             ("fmu", "seahelm.cli.fmu", "fmu"))
for _name, _module, _attr in _COMMANDS:
    try:
        _sub = importlib.import_module(_module)
    except ModuleNotFoundError as _exc:  # a command not built yet
        if _exc.name != _module:
            raise
        continue
    app.command(_name)(getattr(_sub, _attr))
    if _name == "inspect":
        app.command("summary", help="Same as `seahelm inspect`: what a result file holds.")(
            _sub.inspect)


def _version(value: bool) -> None:
    if value:
        from ..versions import version_report

        console.print(f"seahelm {__version__}", highlight=False)
        console.print(version_report(), highlight=False, soft_wrap=True)
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[bool, typer.Option(
        "--version", callback=_version, is_eager=True,
        help="Print the versions of seahelm, Python and its core dependencies, and exit.")
    ] = False,
) -> None:
    """Batched, validated ship motion simulation and control."""


def _execute(batch: Any, out: Path | None, *, as_json: bool, plot: bool, csv: bool,
             label: str, report: bool = False, reads: tuple[Path, ...] = ()
             ) -> dict[str, Any] | None:
    from ..analysis.maneuvers import summarize
    from ..scenario import ManeuverJob, run_scenario

    if report and out is None:
        raise ParameterError(f"`--report` writes {REPORT_NAME} beside the result files; give "
                             "`--out DIR`")
    if isinstance(batch, ManeuverJob):  # a [maneuver] scenario: as `seahelm maneuver` shows it
        from .maneuver import OUT_FILES
        from .maneuver_job import present_job

        if csv:
            raise ParameterError("`--csv` writes the time series of a [simulation] scenario; "
                                 f"a [maneuver] scenario ({batch.kind}) writes NetCDF only")
        if report and out is not None:
            output_dir("--out", out, (REPORT_NAME,), reads=reads)
        present_job(batch, out, as_json, plot=plot, reads=reads)
        if report and out is not None:  # from the manoeuvre's files (it reads their pair)
            source = next(n for n in OUT_FILES[batch.kind] if n.endswith(".nc"))
            if batch.kind == "imo" and batch.monte_carlo is not None:
                from ..analysis.imo.ensemble import ENSEMBLE_FILE as source
            _write_report(out / source, out / REPORT_NAME, quiet=as_json)
        return None

    if out is not None:  # every target checked before anything runs
        output_dir("--out", out, ("result.nc",) + (("result.csv",) if csv else ())
                   + (("overview.png",) if plot else ()) + ((REPORT_NAME,) if report else ()),
                   reads=reads)
    bar = ProgressBar(f"simulating {batch.n_runs} run(s)")
    try:
        result = run_scenario(batch, progress=bar)
    finally:
        bar.close()
    summary = summarize(result)
    units = run_units(result, summary)
    batch_keys = batch_columns(result, summary)
    stats = monte_carlo_statistics(result, summary)
    files: dict[str, str] = {}
    if out is not None:
        from ..results import write_together

        out.mkdir(parents=True, exist_ok=True)
        with write_together():  # result.nc, csv, figure and report together, or none
            _write_files(result, out, files, csv=csv, plot=plot, report=report)
    payload: dict[str, Any] = {
        "scenario": batch.metadata.get("title") or batch.metadata.get("scenario_source", ""),
        "n_runs": result.n_runs,
        "dims": dict(zip(result.dims, result.shape)),
        **{k: v for k, v in status_counts(result.status).items() if k != "n_runs"},
        "wall_time_s": result.metadata["wall_time_s"],
        "files": files,
    }
    if result.n_runs == 1:
        payload.update({k: v for k, v in summary[0].items() if k != "run"})
    payload["runs"] = summary
    payload["units"] = units
    if stats:
        payload["statistics"] = stats
    if as_json:
        print_json(payload)
    else:
        console.print(summary_table(summary, label, batch_keys, units=units))
        for table in statistics_tables(stats, units=units):
            console.print(table)
        if payload["n_diverged"]:
            console.print(diverged_table(diverged_runs(result)))
        console.print(
            f"{result.n_runs} run(s), {payload['n_ok']} ok, {payload['n_diverged']} diverged, "
            f"{result.metadata['wall_time_s']:.3g} s"
        )
        for kind, path in files.items():
            console.print(f"  {kind}: {path}")
    exit_if_diverged(payload["n_diverged"])
    return payload


def _write_files(result: Any, out: Path, files: dict[str, str], *, csv: bool, plot: bool,
                 report: bool) -> None:
    """Write a simulation's files into ``out`` (inside a :func:`write_together` block)."""
    files["netcdf"] = str(result.to_netcdf(out / "result.nc"))
    if csv:
        files["csv"] = str(result.to_csv(out / "result.csv"))
    if plot:
        import matplotlib

        matplotlib.use("Agg")
        from ..plotting.save import save_figure

        files["plot"] = str(save_figure(result.plot(), out / "overview.png"))
    if report:  # from the result in memory (reading the file back costs more)
        from ..report import report_data_from_dataset

        data = report_data_from_dataset(result.to_xarray(), sources=(files["netcdf"],))
        files["report"] = str(_write_report(data, out / REPORT_NAME, quiet=True))


def _write_report(source: Any, target: Path, *, quiet: bool) -> Path:
    """The HTML report (:func:`seahelm.report.write_report`) of a result file or of report
    data, beside the result files."""
    from ..report import write_report

    summary = write_report(source, target, option="--out", force_word="--force")
    if not quiet:
        console.print(f"  report: {summary.path}", highlight=False)
    return summary.path


@app.command()
@handle_errors
def demo(
    out: Annotated[Path, typer.Option(help="Output directory.")] = Path("seahelm-out"),
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Run the embedded default scenario (Mariner, 20° course change, PID): plot and report."""
    from ..scenario import default_scenario_text, parse_scenario

    batch = parse_scenario(default_scenario_text(), source="<embedded default scenario>")
    _execute(batch, out, as_json=json_out, plot=True, csv=False, label=batch.metadata["title"],
             report=True)


@app.command()
@handle_errors
def run(
    scenario: Annotated[Path, typer.Argument(help="Scenario TOML file.")],
    out: Annotated[Path | None, typer.Option(help=(
        "Write result.nc (and overview.png) here; a [maneuver] scenario writes "
        "<kind>-metrics.nc, <kind>-runs.nc and <kind>.png."))] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
    csv: Annotated[bool, typer.Option(help="Also write result.csv.")] = False,
    plot: Annotated[bool, typer.Option(help="Write the figure with --out.")] = True,
    report: Annotated[bool, typer.Option(
        "--report", help=f"Also write {REPORT_NAME}, an HTML report, with --out.")] = False,
) -> None:
    """Validate and run a scenario file: a simulation or a standard manoeuvre."""
    from ..scenario import load_scenario

    if scenario.suffix.lower() == ".toml" and scenario.is_file():
        import tomllib

        from ..encounters.files import is_encounter_scenario
        try:
            several = is_encounter_scenario(tomllib.loads(scenario.read_text()))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError):
            several = False  # (load_scenario says what is wrong)
        if several:  # a [[vessel]] array of tables: ships meeting ships
            from .encounter import encounter

            return encounter([scenario], out=out, force=force, json_out=json_out)
    batch = load_scenario(scenario)
    _execute(batch, out, as_json=json_out, plot=plot, csv=csv,
             label=batch.metadata["title"] or str(scenario), report=report, reads=(scenario,))


@app.command()
@handle_errors
def plot(
    result: Annotated[Path, typer.Argument(help="Result file written by seahelm (NetCDF).")],
    out: Annotated[Path | None, typer.Option(
        help="PNG file (default: next to the result).")] = None,
    runs: Annotated[list[int] | None, typer.Option(
        "--run", help="Run(s) to draw: flat run index, C order over the batch dims.")] = None,
    force: ForceFlag = False,
) -> None:
    """Plot a result file: heading, actuator angle, yaw rate and track."""
    import matplotlib

    matplotlib.use("Agg")
    from ..plotting.save import save_figure
    from ..plotting.timeseries import plot_result
    from ..results import flatten_runs, load_result

    input_file("RESULT", result)
    target = output_file("--out", out or result.with_suffix(".png"), "figure", reads=(result,))
    check_figure_suffix("--out", target)
    ds = flatten_runs(load_result(result))
    if runs:
        bad = [r for r in runs if r not in set(np.asarray(ds["run"].values).tolist())]
        if bad:
            raise ValueError(f"--run {bad} not in the file (runs 0..{ds.sizes['run'] - 1})")
    path = save_figure(plot_result(ds, runs=runs), target)
    console.print(f"wrote {path}")


@app.command()
@handle_errors
def cache(
    clear: Annotated[bool, typer.Option("--clear", help="Delete the compiled kernels.")] = False,
    json_out: JsonFlag = False,
) -> None:
    """Show (or clear) the on-disk cache of compiled closed-loop kernels.

    Only seahelm's own files are counted and deleted (``seahelm_kernel_*``, ``seahelm_guided_*``
    and their compiled caches); anything else in the directory is left alone and reported.
    """
    from ..simulation.engine import kernel_cache_dir

    where = kernel_cache_dir()
    # Another process may be clearing (or compiling into) the cache at the same time: a file
    # or directory that vanishes between the listing and its use is simply not counted.
    sizes = _cache_files(where)
    ours = [p for p in sizes
            if p.name.startswith(("seahelm_kernel_", "seahelm_guided_", ".seahelm_"))]
    others = [p for p in sizes if p not in set(ours)]
    size = sum(sizes[p] for p in ours)
    kernels = sum(1 for p in ours if p.parent == where and p.name.startswith("seahelm_kernel_")
                  and p.suffix == ".py")
    if clear:
        for path in ours:
            path.unlink(missing_ok=True)
    payload = {"path": str(where), "kernels": kernels, "files": len(ours), "bytes": size,
               "cleared": clear, "other_files": len(others)}
    if json_out:
        print_json(payload)
    else:
        verb = "cleared" if clear else "holds"
        console.print(f"{where} {verb} {kernels} kernel(s), {len(ours)} file(s), "
                      f"{size / 1e6:.1f} MB", highlight=False)
        if others:
            console.print(f"  {len(others)} other file(s) there are not seahelm's and were "
                          "left alone", highlight=False)


def _cache_files(where: Path) -> dict[Path, int]:
    """The regular files under ``where`` with their sizes [bytes]; files and directories that
    vanish while they are listed (another ``seahelm cache --clear``) are left out."""
    import os
    import stat

    found: dict[Path, int] = {}
    for root, _dirs, names in os.walk(where):  # (os.walk skips a directory that vanishes)
        for name in names:
            path = Path(root) / name
            try:
                st = path.stat()
            except FileNotFoundError:
                continue
            if stat.S_ISREG(st.st_mode):
                found[path] = st.st_size
    return found


def _value_options() -> set[str]:
    """The names of every option, in every command, that takes a value (not a flag)."""
    from typer.main import get_command

    names: set[str] = set()
    stack = [get_command(app)]
    while stack:
        cmd = stack.pop()
        for param in cmd.params:
            if param.param_type_name == "option" and not getattr(param, "is_flag", False):
                names.update(param.opts)
        stack.extend(getattr(cmd, "commands", {}).values())
    return names


def _refuse_empty_values(argv: list[str]) -> None:
    """An empty option value (``--out ''``, ``--out=``) is an error: the parser turns an empty
    path into ``.``, the current directory, and would write there without a word; no option
    of seahelm means anything by an empty value."""
    if "" not in argv and not any(a.startswith("-") and a.endswith("=") for a in argv):
        return
    names = _value_options()
    for k, arg in enumerate(argv):
        name = arg[:-1] if arg.endswith("=") else (argv[k - 1] if arg == "" and k else None)
        if name in names:
            fail_bad_input(f"`{name}` must not be empty")


def main() -> None:
    """Entry point of the ``seahelm`` console script (and of ``python -m seahelm``).

    Run as the process's program (the ``seahelm`` script, ``python -m seahelm``), the process
    ends at once when the command has finished (its files written and closed) with its exit
    code (:func:`exit_now`): the interpreter's own shutdown, which finalises every module and
    numba's compiled code, took 0.45–0.6 s after a ``seahelm demo`` of 1.8 s (measured), time
    the user waits for nothing. Called from other Python code (a test, a notebook) it raises
    ``SystemExit`` as any click command does.
    """
    import sys

    # SIGTERM and Ctrl-C as exceptions, so a killed write cleans up its temporary file (Python's
    # default for SIGTERM ends the process at once), recorded so a swallowed one is raised again
    stop_request.install()
    _show_compiling()
    try:
        _refuse_empty_values(sys.argv[1:])
        app()
    except typer.Exit as exc:
        code: object = exc.exit_code
    except SystemExit as exc:
        code = exc.code
        stop_request.clear()  # (a SIGTERM's, handled: not raised again in this process)
    else:  # pragma: no cover - click's standalone mode always ends with SystemExit
        code = 0
    if _is_the_program():
        exit_now(code)
    raise SystemExit(code)


def _show_compiling() -> None:
    """One status line on a terminal when this command compiles a kernel: the first use of a
    combination on this machine (a minute or two for a whole IMO check) looks like a hang
    otherwise. Later runs load the kernels from the cache and print nothing.
    ``SEAHELM_COMPILE_LOG`` names a file that gets one line per compiled function."""
    import sys

    from .._codegen import watch_compiles

    def say() -> None:
        print("compiling the simulation kernels for this command (first use on this machine; "
              "later runs load them from the cache) ...", file=sys.stderr, flush=True)

    watch_compiles(on_first=say if sys.stderr.isatty() else None)


def _is_the_program() -> bool:
    """True when seahelm is the process's program and nothing else runs around it: ``python -m
    seahelm`` or the console script (a ``__main__`` file named ``seahelm``, or the
    ``__main__.py`` inside a Windows ``seahelm.exe`` launcher), called straight from that
    ``__main__`` (only runpy's frames and the ``__main__`` module's own above ``main()``), with
    no tracer or profiler set. A tool that runs seahelm inside itself (pdb, pyinstrument,
    ``runpy`` in a script of one's own) does work after the command returns, so it gets the
    ordinary ``SystemExit``.
    """
    import sys
    from pathlib import Path

    if sys.gettrace() is not None or sys.getprofile() is not None:
        return False
    program = sys.modules.get("__main__")
    spec = getattr(program, "__spec__", None)
    path = Path(getattr(program, "__file__", None) or "")
    if not ((spec is not None and spec.name == "seahelm.__main__") or path.stem == "seahelm"
            or (path.name == "__main__.py" and path.parent.stem == "seahelm")):
        return False
    main_globals = vars(program)
    frame = sys._getframe(2)  # (1 is main())
    while frame is not None:
        if frame.f_globals is not main_globals and frame.f_globals.get("__name__") != "runpy":
            return False
        frame = frame.f_back
    return True


def exit_now(code: object) -> None:
    """End the process with ``code`` (as ``SystemExit`` takes it) without the interpreter's
    shutdown: flush stdout and stderr and the logging handlers, then ``os._exit``.

    Under coverage measurement (``coverage`` imported, which writes its data at exit) it raises
    ``SystemExit`` instead, as does any process that wants the ordinary shutdown and sets
    ``SEAHELM_ORDINARY_EXIT`` (to anything but empty, ``0``, ``false`` or ``no``).
    """
    import os
    import sys

    if code is None:
        status = 0
    elif isinstance(code, int):
        status = code
    else:  # SystemExit("text"): the text on stderr, status 1
        print(code, file=sys.stderr)
        status = 1
    ordinary = os.environ.get("SEAHELM_ORDINARY_EXIT", "").strip().lower()
    if "coverage" in sys.modules or ordinary not in ("", "0", "false", "no"):
        raise SystemExit(status)
    if "logging" in sys.modules:
        import logging

        logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:  # (None under pythonw)
                stream.flush()
        except (OSError, ValueError):  # a closed pipe (`seahelm ... | head`) or stream
            if stream is sys.stdout and status == 0:
                status = 120  # what Python's own shutdown returns when it cannot flush stdout
    os._exit(status)
