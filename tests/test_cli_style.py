"""One CLI style across the command groups: options declared with ``Annotated`` (no
``typer.Option`` defaults), one ``--json`` flag, declared once (``_common.JsonFlag``), options
with a fixed set of values typed as choices that ``--help`` lists, and bad input found by the
command-line parser reported as the commands report theirs: one ``error: `` line on stderr,
exit code 2."""

from __future__ import annotations

import importlib
import inspect
import json
import os
import pkgutil
import subprocess
import sys
import typing

import pytest
import typer
from typer.models import ParameterInfo
from typer.testing import CliRunner

import seahelm.cli
from seahelm.cli._common import JsonFlag, OneLineErrors
from seahelm.cli.main import app as main_app

MODULES = [importlib.import_module(f"seahelm.cli.{m.name}")
           for m in pkgutil.iter_modules(seahelm.cli.__path__)]
COMMANDS = [(mod.__name__, name, obj) for mod in MODULES
            for name, obj in vars(mod).items()
            if inspect.isfunction(obj) and obj.__module__ == mod.__name__
            and any(True for _ in inspect.signature(obj).parameters)]


def _parameter_infos(func):
    hints = typing.get_type_hints(func, include_extras=True)
    for name, param in inspect.signature(func).parameters.items():
        meta = getattr(hints.get(name), "__metadata__", ())
        yield name, param, [m for m in meta if isinstance(m, ParameterInfo)]


@pytest.mark.parametrize(("module", "name", "func"), COMMANDS,
                         ids=[f"{m}.{n}" for m, n, _ in COMMANDS])
def test_options_are_annotated_not_defaults(module, name, func):
    for pname, param, _ in _parameter_infos(func):
        assert not isinstance(param.default, ParameterInfo), (
            f"{module}.{name}({pname}): typer.Option as a default; use Annotated")


@pytest.mark.parametrize(("module", "name", "func"), COMMANDS,
                         ids=[f"{m}.{n}" for m, n, _ in COMMANDS])
def test_json_flag_is_the_shared_one(module, name, func):
    shared = typing.get_args(JsonFlag)[1]
    for pname, _param, infos in _parameter_infos(func):
        if any(getattr(i, "param_decls", None) and "--json" in i.param_decls for i in infos):
            assert pname == "json_out" and infos == [shared], f"{module}.{name}({pname})"


def test_the_check_sees_commands():
    names = {(m.rsplit(".", 1)[1], n) for m, n, _ in COMMANDS}
    assert {("main", "demo"), ("compensate", "compensate"), ("averaging", "cpp")} <= names


# ------------------------------------------------------------------------------------------
# bad input found by the command-line parser: one `error: ` line, exit code 2
# ------------------------------------------------------------------------------------------

_runner = CliRunner()

#: (arguments, what the one line must say): bad choices, bad numbers, unknown options and
#: commands, missing arguments and options, in the main command and each group.
PARSER_ERRORS = [
    (["maneuver", "turning", "--side", "left"],
     "Invalid value for '--side': 'left' is not one of 'both', 'starboard', 'port'"),
    (["maneuver", "zigzag", "--catalog", "kvlcc9"],
     "unknown ship 'kvlcc9'; catalog ships with a steering gear: esso-osaka-3m, kvlcc2-full, kvlcc2-l7, "
     "kvlcc2-l7-wp0-0.35, kvlcc2-l7-xp-0.5, mariner-nonlinear, son-nomoto-container (or the "
     "path of a ship file"),
    (["maneuver", "zigzag", "--ship", "kvlcc9"], "unknown ship 'kvlcc9'; catalog ships with"),
    (["imo", "kvlcc9"], "unknown ship 'kvlcc9'; catalog ships with a steering gear: esso-osaka-3m, kvlcc2-full"),
    (["imo", "missing.toml"], "missing.toml: no such ship file"),
    (["identify", "steady-turn", "x.csv", "--method", "ols"],
     "Invalid value for '--method': 'ols' is not one of 'lsq', 'robust', 'brute'"),
    (["identify", "steady-turn", "x.csv", "--form", "odd"],
     "Invalid value for '--form': 'odd' is not one of 'paper', 'exact', 'paper-odd', "
     "'exact-odd'"),
    (["identify", "steady-turn", "x.csv", "--angles", "grad"],
     "Invalid value for '--angles': 'grad' is not one of 'deg', 'rad'"),
    (["waves", "spectrum", "--h3", "3", "--model", "nope"],
     "Invalid value for '--model': 'nope' is not one of 'rakhmanin-firsov-1',"),
    (["waves", "table", "--table", "misprinted"],
     "Invalid value for '--table': 'misprinted' is not one of 'corrected', 'printed'"),
    (["waves", "spectrum", "--h3", "abc"],
     "Invalid value for '--h3': Input should be a valid number, unable to parse string as a "
     "number, got 'abc'"),
    (["waves", "sample", "--h3", "3", "--duration", "10", "--dt", "0.1", "--seed", "1.5"],
     "Invalid value for '--seed': Input should be a valid integer, unable to parse string as "
     "an integer, got '1.5'"),
    (["compensate", "--length", "long"], "Invalid value for '--length':"),
    (["averaging", "cpp", "--grid", "many"], "Invalid value for '--grid':"),
    (["maneuver", "turning", "--rudder", "hard"], "Invalid value for '--rudder':"),
    (["plot", "r.nc", "--run", "first"], "Invalid value for '--run':"),
    (["--badflag"], "No such option: --badflag"),
    (["maneuver", "turning", "--sides", "port"], "No such option: --sides"),
    (["run"], "Missing argument 'SCENARIO'"),
    (["waves", "spectrum"], "Missing option '--h3'"),
    (["waves", "spectrum", "--h3"], "Option '--h3' requires an argument"),
    (["run", "a.toml", "b.toml"], "Got unexpected extra argument(s) (b.toml)"),
    (["wave"], "No such command 'wave'. Did you mean 'waves'?"),
    (["maneuver", "turnin"], "No such command 'turnin'. Did you mean 'turning'?"),
]


@pytest.mark.parametrize(("args", "text"), PARSER_ERRORS, ids=[" ".join(a) for a, _ in PARSER_ERRORS])
def test_parser_errors_are_one_line_exit_2(args, text):
    res = _runner.invoke(main_app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    assert res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert text in lines[0]


def test_parser_errors_point_to_the_help():
    res = _runner.invoke(main_app, ["waves", "spectrum", "--h3", "abc"])
    assert res.stderr.strip().endswith("(see 'seahelm waves spectrum --help')")


@pytest.mark.parametrize("args", [
    ["--badflag"], ["maneuver", "turning", "--side", "left"], ["run"],
    ["waves", "spectrum", "--h3", "abc"]])
def test_the_console_script_prints_one_line(args):
    """The installed entry point (its own ``sys.exit``, not CliRunner's) behaves the same."""
    proc = subprocess.run([sys.executable, "-c", "from seahelm.cli.main import main; main()",
                           *args], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr


def test_python_dash_m_seahelm_is_the_same_command():
    ok = subprocess.run([sys.executable, "-m", "seahelm", "--version"], capture_output=True,
                        text=True, timeout=120)
    assert ok.returncode == 0 and "seahelm" in ok.stdout, ok.stderr
    bad = subprocess.run([sys.executable, "-m", "seahelm", "waves", "spectrum", "--h3", "abc"],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and bad.stdout == ""
    lines = bad.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), bad.stderr


def test_sub_apps_alone_print_one_line_too():
    from seahelm.cli.waves import app as waves_app

    res = _runner.invoke(waves_app, ["spectrum", "--h3", "abc"])
    assert res.exit_code == 2 and res.stdout == ""
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: Invalid value for '--h3':")


def test_no_arguments_still_show_the_help():
    res = _runner.invoke(main_app, [])
    assert res.exit_code == 2 and "Usage" in res.stdout and "error" not in res.stderr


def test_every_app_reports_parser_errors_in_one_line():
    apps = [(m.__name__, m.app) for m in MODULES if isinstance(getattr(m, "app", None), typer.Typer)]
    assert len(apps) >= 6
    for name, app in apps:
        assert app.info.cls is OneLineErrors, name


# ------------------------------------------------------------------------------------------
# choices: typed (Literal), listed by --help, the same as the library's registries
# ------------------------------------------------------------------------------------------
def test_choices_agree_with_the_library():
    from seahelm.cli import identify, maneuver, waves
    from seahelm.ships import CATALOG, with_steering_gear
    from seahelm.environment.rational_spectra import RationalSpectrum
    from seahelm.studies.sushchenko2010 import SPECTRA, TABLE2_VERSIONS
    from seahelm.identification.reduced.fitting import FIT_METHODS
    from seahelm.identification.reduced.forms import REDUCED_FORMS

    args = typing.get_args
    # ships are a catalog name or a file: the help lists the catalog's, from the catalog
    assert with_steering_gear() == tuple(n for n, s in CATALOG.items()
                                         if s.steering_gear is not None)
    assert ", ".join(with_steering_gear()) in maneuver.SHIP_HELP
    assert args(maneuver.SideName) == tuple(maneuver._SIDES)
    assert args(identify.FitMethod) == tuple(FIT_METHODS)
    assert args(identify.FormName) == tuple(REDUCED_FORMS)
    assert args(waves.SpectrumName) == tuple(SPECTRA)
    assert args(waves.RationalSpectrumName) == tuple(
        n for n, cls in SPECTRA.items() if issubclass(cls, RationalSpectrum))
    assert args(waves.TableVersion) == tuple(TABLE2_VERSIONS)


@pytest.mark.parametrize(("args", "choices"), [
    (["maneuver", "turning"], ["both|starboard|port", "osaka-3m, kvlcc2-full, "
                               "kvlcc2-l7, kvlcc2-l7-wp0-0.35, kvlcc2-l7-xp-0.5,"]),
    (["maneuver", "zigzag"], ["both|starboard|port"]),
    (["identify", "steady-turn"], ["deg|rad", "lsq|robust|brute"]),
    (["waves", "spectrum"], ["corrected|printed", "pierson-moskowitz, jonswap, bretschneider"]),
    (["waves", "sample"], ["rakhmanin-firsov-3, rakhmanin-firsov-3-printed."]),
])
def test_help_lists_the_choices(args, choices):
    res = _runner.invoke(main_app, [*args, "--help"])
    assert res.exit_code == 0
    text = " ".join(res.stdout.replace("│", " ").split())  # lines of the help box, joined
    for choice in choices:
        assert choice in text, (choice, text)


def test_the_console_script_exits_at_once_with_its_output_flushed():
    """main() ends with os._exit after flushing (no interpreter shutdown): the output of a
    command is complete through a pipe, the status is the command's, atexit hooks do not run."""
    proc = subprocess.run([sys.executable, "-m", "seahelm", "models", "--json"],
                          capture_output=True, text=True, timeout=120,
                          env={k: v for k, v in os.environ.items()
                               if k != "SEAHELM_ORDINARY_EXIT"})
    assert proc.returncode == 0, proc.stderr
    assert "vessel_models" in json.loads(proc.stdout)  # 100 kB, all of it
    code = ("import atexit, sys; from seahelm.cli.main import exit_now; "
            "atexit.register(lambda: print('atexit ran')); print('out', end=''); "
            "sys.stderr.write('partial'); exit_now({arg})")
    env = {k: v for k, v in os.environ.items() if k != "SEAHELM_ORDINARY_EXIT"}
    for arg, status in (("None", 0), ("3", 3), ("'bye'", 1)):
        p = subprocess.run([sys.executable, "-c", code.format(arg=arg)], capture_output=True,
                           text=True, timeout=120, env=env)
        assert p.returncode == status and p.stdout == "out", (arg, p.stdout, p.stderr)
        assert p.stderr.startswith("partial")
        assert ("bye" in p.stderr) == (arg == "'bye'")
    # the ordinary shutdown on request: SystemExit, so atexit hooks run
    p = subprocess.run([sys.executable, "-c", code.format(arg="3")], capture_output=True,
                       text=True, timeout=120, env={**env, "SEAHELM_ORDINARY_EXIT": "1"})
    assert p.returncode == 3 and p.stdout == "outatexit ran\n", p.stdout


def test_a_tool_running_seahelm_inside_itself_gets_the_ordinary_exit(tmp_path):
    """A wrapper that runs seahelm as __main__ through runpy (as pyinstrument or pdb do) and
    works after it: no os._exit, its code after the run and its atexit hooks run."""
    wrapper = tmp_path / "wrap.py"
    wrapper.write_text(
        "import atexit, runpy, sys\n"
        "atexit.register(lambda: print('atexit ran'))\n"
        "sys.argv = ['seahelm', '--version']\n"
        "try:\n"
        "    runpy.run_module('seahelm', run_name='__main__', alter_sys=True)\n"
        "except SystemExit as exc:\n"
        "    print('wrapper: exit', exc.code)\n"
        "print('wrapper: after')\n")
    env = {k: v for k, v in os.environ.items() if k != "SEAHELM_ORDINARY_EXIT"}
    p = subprocess.run([sys.executable, str(wrapper)], capture_output=True, text=True,
                       timeout=120, env=env)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines()[-3:] == ["wrapper: exit 0", "wrapper: after", "atexit ran"]
    # and "0" does not ask for the ordinary exit
    code = "from seahelm.cli.main import exit_now; import atexit; " \
           "atexit.register(lambda: print('atexit ran')); exit_now(0)"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120, env={**env, "SEAHELM_ORDINARY_EXIT": "0"})
    assert p.returncode == 0 and p.stdout == ""


def test_exit_now_leaves_coverage_its_shutdown(monkeypatch):
    import types

    from seahelm.cli.main import exit_now

    monkeypatch.setitem(sys.modules, "coverage", types.ModuleType("coverage"))
    with pytest.raises(SystemExit) as exc:
        exit_now(2)
    assert exc.value.code == 2
