"""The one output policy (issue 43, item 1): every command that writes a file goes by
:mod:`seahelm.output_files`, and a command that writes cannot be added without a row here.

- an output is never a file the command reads (also through a symbolic or hard link, or
  named with a trailing slash): exit 2, the input unchanged byte for byte and in its mtime;
- an existing file that is not the command's own earlier output (a user's file, a file of
  another kind) is replaced only with ``--force``: exit 2 and unchanged without it; a TOML
  file (a ship file, a scenario: made to be edited) always needs ``--force``;
- with ``--force`` it is replaced atomically (no temporary file left) and keeps its mode; a new
  file gets the umask's mode (ship files were written 0600).
"""

from __future__ import annotations

import errno
import os
import stat
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
import typer.main
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.output_files import (
    OutputExistsError,
    atomic_write,
    check_output,
    write_output,
    written_by_line,
)
from seahelm.ships import get_ship, write_ship

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

#: The options through which a command writes files (or a store).
OUTPUT_OPTIONS = {"--out", "-o", "--plot", "--save-posterior", "--store"}


def _writing_commands() -> dict[tuple[str, ...], set[str]]:
    """Every command of the CLI with an output option, from the typer app itself."""
    found: dict[tuple[str, ...], set[str]] = {}

    def walk(cmd, path):
        if hasattr(cmd, "commands"):
            for name in cmd.list_commands(None):
                walk(cmd.get_command(None, name), path + (name,))
            return
        # (a flag such as `run --plot/--no-plot` names no file)
        params = [p for p in cmd.params if set(p.opts) & OUTPUT_OPTIONS
                  and not getattr(p, "is_flag", False)]
        if params:
            found[path] = {next(o for o in p.opts if o.startswith("--")) for p in params}
    walk(typer.main.get_command(app), ())
    return found


@dataclass
class Files:
    """Inputs the invocations read (copies in the test's directory)."""

    root: Path
    kv: Path        # an MMG ship file (kvlcc2-l7)
    mar: Path       # a Mariner ship file
    result: Path    # a small seahelm result (NetCDF)
    records: Path   # a Nomoto record (CSV, degrees, with a comment line)
    scenario: Path  # a scenario file
    particulars: Path


@dataclass
class Case:
    """One writing command: its arguments without the output, the output option, whether
    the output is a directory (the files at the command's own names are then checked), the
    input that can be given as the output, and whether a full run is cheap enough for the
    ``--force`` case here."""

    args: Callable[[Files], list[str]]
    option: str
    directory: tuple[str, ...] = ()
    own_input: Callable[[Files], Path] | None = None
    cheap: bool = False
    kind: str = "file"


def _estimate(f: Files) -> list[str]:
    return ["ship", "estimate", "--length", "320", "--beam", "58", "--draft", "20.8",
            "--cb", "0.81", "--speed", "7.97"]


def _replay_record(f: Files) -> Path:
    """A 60 s turn of the KVLCC2 L7 model in the FRT-DS-ESSO header (tests/test_replay.py)."""
    path = f.root / "turn.csv"
    if not path.exists():
        from test_replay import _simulated_turn, _write

        _write(path, *_simulated_turn(t_final=60.0))
    return path


#: Every writing command and output option (test_every_writing_command_is_listed keeps it
#: complete).
CASES: dict[tuple[tuple[str, ...], str], Case] = {
    (("ship", "scale"), "--out"): Case(
        lambda f: ["ship", "scale", str(f.kv), "--length", "320"], "--out",
        own_input=lambda f: f.kv, cheap=True),
    (("ship", "estimate"), "--out"): Case(
        lambda f: ["ship", "estimate", str(f.particulars)], "--out",
        own_input=lambda f: f.particulars, cheap=True),
    (("autopilot", "tune"), "--out"): Case(
        lambda f: ["autopilot", "tune", str(f.mar)], "--out", own_input=lambda f: f.mar,
        cheap=True),
    (("identify", "nomoto"), "--out"): Case(
        lambda f: ["identify", "nomoto", str(f.records), "--speed", "7.7", "--length", "160"],
        "--out", own_input=lambda f: f.records, cheap=True),
    (("identify", "nomoto"), "--plot"): Case(
        lambda f: ["identify", "nomoto", str(f.records)], "--plot",
        own_input=lambda f: f.records, kind="png"),
    (("identify", "mmg"), "--out"): Case(
        lambda f: ["identify", "mmg", str(f.result), "--ship", str(f.kv), "--regression-only"],
        "--out", own_input=lambda f: f.kv),
    (("identify", "mmg"), "--save-posterior"): Case(
        lambda f: ["identify", "mmg", str(f.result), "--ship", str(f.kv), "--regression-only",
                   "--samples", "4"], "--save-posterior", kind="csv"),
    (("report",), "--out"): Case(
        lambda f: ["report", str(f.result)], "--out", own_input=lambda f: f.result,
        cheap=True, kind="html"),
    (("plot",), "--out"): Case(
        lambda f: ["plot", str(f.result)], "--out", own_input=lambda f: f.result, cheap=True,
        kind="png"),
    (("waves", "sample"), "--out"): Case(
        lambda f: ["waves", "sample", "--h3", "3", "--duration", "10", "--dt", "0.5",
                   "--seed", "1"], "--out", cheap=True, kind="nc"),
    (("waves", "figure"), "--out"): Case(
        lambda f: ["waves", "figure", "--duration", "20"], "--out", cheap=True, kind="png"),
    (("waves", "spectrum"), "--plot"): Case(
        lambda f: ["waves", "spectrum", "--h3", "3"], "--plot", cheap=True, kind="png"),
    (("dp", "tune"), "--out"): Case(lambda f: ["dp", "tune", "supply"], "--out", cheap=True),
    (("dp", "capability"), "--out"): Case(
        lambda f: ["dp", "capability", "shushlyapin2017-dp", "--headings", "4"], "--out", cheap=True,
        kind="nc"),
    (("dp", "capability"), "--plot"): Case(
        lambda f: ["dp", "capability", "shushlyapin2017-dp", "--headings", "4"], "--plot", cheap=True,
        kind="png"),
    (("averaging", "cpp"), "--plot"): Case(
        lambda f: ["averaging", "cpp", "--grid", "8"], "--plot", cheap=True, kind="png"),
    (("seakeeping",), "--out"): Case(
        lambda f: ["seakeeping", "kvlcc2-l7", "--hs", "2", "--tp", "8", "--dof", "heave"],
        "--out",
        directory=("seakeeping.nc",), cheap=True),
    (("run",), "--out"): Case(
        lambda f: ["run", str(f.scenario)], "--out", directory=("result.nc",),
        own_input=lambda f: f.scenario),
    (("demo",), "--out"): Case(lambda f: ["demo"], "--out", directory=("result.nc",)),
    (("encounter",), "--out"): Case(
        lambda f: ["encounter", "--monte-carlo", "1", "--t-final", "300", "--detection", "2500",
                   "--avoidance", "none"], "--out",
        directory=("encounters.nc", "tracks.png", "cpa.png", "rose.png")),
    (("encounter",), "--store"): Case(
        lambda f: ["encounter", "--monte-carlo", "1", "--t-final", "300", "--detection", "2500",
                   "--avoidance", "none"], "--store", kind="store"),
    (("imo",), "--out"): Case(
        lambda f: ["imo", str(f.kv)], "--out", directory=("imo-report.json",),
        own_input=lambda f: f.kv),
    (("replay",), "--out"): Case(
        lambda f: ["replay", str(_replay_record(f)), "--ship", "kvlcc2-l7", "--kind", "none"],
        "--out", directory=("replay.nc", "replay.png"), own_input=_replay_record, cheap=True),
    (("fmu",), "--out"): Case(
        lambda f: ["fmu", str(f.kv)], "--out", own_input=lambda f: f.kv, cheap=True,
        kind="fmu"),
    (("sweep",), "--store"): Case(
        lambda f: ["sweep", str(f.scenario)], "--store", own_input=lambda f: f.scenario,
        kind="store"),
    **{(("maneuver", m), "--out"): Case(
        (lambda m: lambda f: ["maneuver", m, "--ship", str(f.kv)])(m), "--out",
        directory=(names,), own_input=lambda f: f.kv)
       for m, names in (("turning", "turning-circle-runs.nc"), ("zigzag", "zigzag-runs.nc"),
                        ("pullout", "pull-out-runs.nc"), ("spiral", "direct-spiral-runs.nc"),
                        ("stopping", "stopping-runs.nc"))},
}


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Files:
    from seahelm.simulation.engine import simulate
    from seahelm.ships import ship_to_toml
    from seahelm.vessels.nomoto import NOMOTO2

    root = tmp_path_factory.mktemp("inputs")
    kv = root / "kv.toml"
    kv.write_text(ship_to_toml(get_ship("kvlcc2-l7")))
    mar = root / "mar.toml"
    mar.write_text(ship_to_toml(get_ship("mariner-nonlinear")))
    result = simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros((2, 5)),
                      t_final=5.0, dt=0.1, reference=[0.1]).to_netcdf(root / "r.nc")
    t = np.arange(0.0, 300.0, 0.5)
    rudder = 10.0 * np.sign(np.sin(2 * np.pi * t / 150.0) + 1e-9)
    r = np.zeros_like(t)
    for i in range(1, t.size):  # Nomoto K = 0.1 1/s, T = 30 s, Euler at 0.5 s
        r[i] = r[i - 1] + 0.5 * (0.1 * np.radians(rudder[i - 1]) - r[i - 1]) / 30.0
    heading = np.degrees(np.concatenate([[0.0], np.cumsum(0.5 * r[:-1])]))
    records = root / "nomoto.csv"
    records.write_text("# units: time s, rudder_angle deg, heading deg\n"
                       "time,rudder_angle,heading\n"
                       + "".join(f"{a},{b},{c}\n" for a, b, c in zip(t, rudder, heading)))
    scenario = EXAMPLES / "mariner_pid_sweep.toml"
    own_scenario = root / "scenario.toml"
    own_scenario.write_text(scenario.read_text())
    particulars = root / "particulars.toml"
    particulars.write_text("length = 320.0\nbeam = 58.0\ndraft = 20.8\nblock_coefficient = 0.81\n"
                           "speed = 7.97\n")
    return Files(root, kv, mar, result, records, own_scenario, particulars)


def _state(path: Path) -> tuple[bytes, int, int]:
    st = path.stat()
    return path.read_bytes(), st.st_mtime_ns, stat.S_IMODE(st.st_mode)


def _refused(args: list[str], keep: list[Path]) -> str:
    before = {p: _state(p) for p in keep}
    res = runner.invoke(app, args)
    assert res.exit_code == 2, (args, res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    assert {p: _state(p) for p in keep} == before  # byte for byte, mtime and mode
    return lines[0]


def test_every_writing_command_is_listed_and_has_force():
    found = _writing_commands()
    listed = {(cmd, opt) for cmd, opt in CASES}
    expected = {(cmd, opt) for cmd, opts in found.items() for opt in opts}
    assert expected - listed == set(), "a command that writes has no row in CASES"
    assert listed - expected == set(), "CASES lists an output option that is gone"
    cli = typer.main.get_command(app)
    for cmd in found:
        node = cli
        for name in cmd:
            node = node.get_command(None, name)
        opts = {o for p in node.params for o in p.opts}
        assert "--force" in opts or "--overwrite" in opts, cmd


@pytest.mark.parametrize("key", [k for k, c in CASES.items() if c.own_input is not None],
                         ids=lambda k: " ".join(k[0]) + " " + k[1])
def test_the_output_is_never_an_input(files, key):
    case = CASES[key]
    target = case.own_input(files)
    line = _refused(case.args(files) + [case.option, str(target), "--force"]
                    if key[1] != "--store" else
                    case.args(files) + [case.option, str(target), "--overwrite"], [target])
    assert str(target) in line


def _unrelated(tmp_path: Path, case: Case) -> tuple[Path, Path]:
    """The output path to give and the unrelated file that is there (for a directory
    output: a user's file at one of the command's own names)."""
    if case.kind == "store":
        store = tmp_path / "mine.zarr"
        store.write_text("a user's file\n")
        return store, store
    if case.directory:
        out = tmp_path / "out"
        out.mkdir()
        (out / case.directory[0]).write_text("a user's file\n")
        return out, out / case.directory[0]
    suffix = {"file": ".toml", "png": ".png", "csv": ".csv", "html": ".html",
              "nc": ".nc", "fmu": ".fmu"}[case.kind]
    target = tmp_path / f"mine{suffix}"
    target.write_text("a user's file\n")
    return target, target


@pytest.mark.parametrize("key", list(CASES), ids=lambda k: " ".join(k[0]) + " " + k[1])
def test_an_unrelated_existing_file_needs_force(files, tmp_path, key):
    case = CASES[key]
    out, mine = _unrelated(tmp_path, case)
    os.chmod(mine, 0o640)
    _refused(case.args(files) + [case.option, str(out)], [mine])


@pytest.mark.parametrize("key", [k for k, c in CASES.items() if c.cheap],
                         ids=lambda k: " ".join(k[0]) + " " + k[1])
def test_force_replaces_atomically_and_keeps_the_mode(files, tmp_path, key):
    case = CASES[key]
    out, mine = _unrelated(tmp_path, case)
    os.chmod(mine, 0o640)
    res = runner.invoke(app, case.args(files) + [case.option, str(out), "--force"])
    assert res.exit_code == 0, (res.stdout, res.stderr)
    assert mine.read_bytes() != b"a user's file\n"
    assert stat.S_IMODE(mine.stat().st_mode) == 0o640
    assert not [p for p in mine.parent.iterdir() if p.name.endswith(".tmp")]
    # and again without --force: the command's own output of an earlier run is replaced,
    # unless it is a ship file or scenario (TOML), which may have been edited since
    before = mine.read_bytes()
    res = runner.invoke(app, case.args(files) + [case.option, str(out)])
    if case.kind == "file" and not case.directory:  # (a TOML file)
        assert res.exit_code == 2 and "perhaps edited since" in res.stderr, res.stderr
        assert mine.read_bytes() == before
    else:
        assert res.exit_code == 0, (res.stdout, res.stderr)


# -- the cases of the issue, as they were reported ------------------------------------------
def test_the_reported_cases(files, tmp_path):
    kv = tmp_path / "kv.toml"
    kv.write_bytes(files.kv.read_bytes())
    mar = tmp_path / "mar.toml"
    mar.write_bytes(files.mar.read_bytes())
    r = tmp_path / "r.nc"
    r.write_bytes(files.result.read_bytes())
    mine = tmp_path / "mine.toml"
    mine.write_text("mine\n")
    pid = tmp_path / "pid.toml"
    pid.write_text("mine\n")
    # identify mmg -o its own base ship; autopilot tune --out its input ship
    assert "is a file this command reads" in _refused(
        ["identify", "mmg", str(r), "--ship", str(kv), "--regression-only", "-o", str(kv)], [kv])
    assert "is a file this command reads" in _refused(
        ["autopilot", "tune", str(mar), "--out", str(mar)], [mar])
    # a TOML over a NetCDF result
    for args in (["ship", "scale", "kvlcc2-l7", "--length", "320"],
                 ["identify", "nomoto", str(files.records), "--speed", "7.7", "--length", "160"],
                 ["autopilot", "tune", "mariner-nonlinear"]):
        assert "exists (a seahelm NetCDF file" in _refused(args + ["--out", str(r)], [r])
    # an unrelated existing file (a user's, or a ship file another command wrote)
    assert "a file seahelm did not write" in _refused(
        ["ship", "scale", "kvlcc2-l7", "--length", "320", "--out", str(mine)], [mine])
    assert "a file seahelm did not write" in _refused(
        ["autopilot", "tune", "mariner-nonlinear", "--out", str(pid)], [pid])
    assert "exists (a seahelm ship file, perhaps edited since)" in _refused(
        ["identify", "nomoto", str(files.records), "--speed", "7.7", "--length", "160", "-o",
         str(mar)], [mar])
    assert "this writes an HTML report there: pass --force" in _refused(
        ["report", str(r), "-o", str(kv)], [kv])
    # a trailing slash names a directory, never the file
    assert "ends with '/'" in _refused(_estimate(files) + ["-o", f"{kv}/", "--force"], [kv])


def test_links_to_an_input_are_the_input(files, tmp_path):
    kv = tmp_path / "kv.toml"
    kv.write_bytes(files.kv.read_bytes())
    hard = tmp_path / "hard.toml"
    os.link(kv, hard)
    soft = tmp_path / "soft.toml"
    soft.symlink_to(kv)
    for target in (hard, soft):
        _refused(["ship", "scale", str(kv), "--length", "320", "--out", str(target),
                  "--force"], [kv])


def test_concurrent_writers_to_one_file(files, tmp_path, monkeypatch):
    """Two `ship estimate -o c.toml` at once: the second finds the first's ship file when it
    writes (after its check found none) and says so as it would had it run second -- exit 2
    naming the path and --force, the first's file whole (it said only "error:
    FileExistsError" before). A user's file appearing meanwhile is not replaced either."""
    import seahelm.ships.estimate as estimate

    target = tmp_path / "c.toml"
    real = estimate.estimate_ship

    def meanwhile(design, **kwargs):  # the other process writes while this one computes
        other = subprocess.run([sys.executable, "-m", "seahelm", *_estimate(files), "-o",
                                str(target)], capture_output=True, text=True, timeout=300)
        assert other.returncode == 0, other.stderr
        return real(design, **kwargs)

    monkeypatch.setattr(estimate, "estimate_ship", meanwhile)
    res = runner.invoke(app, _estimate(files) + ["-o", str(target), "--name", "second"])
    assert res.exit_code == 2, res.stderr
    assert f"`--out` {target} exists" in res.stderr and "pass --force" in res.stderr
    assert 'name = "estimated-ship"' in target.read_text()

    def user_meanwhile(design, **kwargs):
        target.write_text("a user's file\n")
        return real(design, **kwargs)

    target.unlink()
    monkeypatch.setattr(estimate, "estimate_ship", user_meanwhile)
    res = runner.invoke(app, _estimate(files) + ["-o", str(target)])
    assert res.exit_code == 2 and str(target) in res.stderr and "--force" in res.stderr
    assert target.read_text() == "a user's file\n"


# -- the library's policy -----------------------------------------------------------------
def _text(s: str):
    return lambda tmp: Path(tmp).write_text(s)


def test_library_refuses_inputs_links_and_slashes(tmp_path):
    src = tmp_path / "in.toml"
    src.write_text("# seahelm ship file\n")
    with pytest.raises(ParameterError, match="is a file this command reads"):
        check_output(src, "toml", reads=[src], force=True)
    hard = tmp_path / "hard.toml"
    os.link(src, hard)
    with pytest.raises(ParameterError, match="is a file this command reads"):
        check_output(hard, "toml", reads=[src], force=True)
    with pytest.raises(ParameterError, match="ends with '/'"):
        check_output(f"{src}/", "toml", force=True)
    with pytest.raises(ParameterError, match="must be one of"):
        check_output(tmp_path / "x", "docx")


def test_library_savers_keep_the_rule(tmp_path):
    from seahelm.plotting.save import save_figure

    mine = tmp_path / "mine.nc"
    mine.write_text("a user's file\n")
    result = get_ship("mariner-nomoto2")  # (any ship: its file is TOML)
    with pytest.raises(OutputExistsError, match="pass force=True"):
        write_output(mine, _text("x"), "netcdf")
    assert mine.read_text() == "a user's file\n"
    with pytest.raises(FileExistsError, match="exists; pass overwrite=True"):
        write_ship(result, mine)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    png = tmp_path / "f.png"
    png.write_text("a user's file\n")
    with pytest.raises(OutputExistsError):
        save_figure(plt.figure(), png)
    save_figure(plt.figure(), png, force=True)
    save_figure(plt.figure(), png)  # its own figure now: replaced without force


def test_new_files_get_the_umask_and_replaced_ones_keep_their_mode(tmp_path):
    old = os.umask(0o027)
    try:
        path = write_ship(get_ship("kvlcc2-l7"), tmp_path / "s.toml")
        assert stat.S_IMODE(path.stat().st_mode) == 0o640  # (was 0600 whatever the umask)
        os.chmod(path, 0o604)
        write_ship(get_ship("kvlcc2-l7"), path, overwrite=True)
        assert stat.S_IMODE(path.stat().st_mode) == 0o604
    finally:
        os.umask(old)


def test_a_failed_write_names_the_path_and_leaves_the_old_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text("old")

    def full(tmp):
        raise OSError(errno.ENOSPC, "No space left on device", tmp)

    with pytest.raises(OSError) as info:
        write_output(path, full, "toml", force=True)
    assert info.value.filename == str(path) and info.value.errno == errno.ENOSPC
    assert path.read_text() == "old" and sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_own_output_is_the_same_commands(tmp_path):
    import xarray as xr

    from seahelm.output_files import WRITTEN_BY_ATTR
    from seahelm.results import write_netcdf

    nc = write_netcdf(xr.Dataset({"a": ("x", [1.0])},
                                 attrs={WRITTEN_BY_ATTR: "seahelm waves sample"}),
                      tmp_path / "w.nc")
    assert check_output(nc, "netcdf", command="seahelm waves sample") == nc
    assert check_output(nc, "netcdf") == nc  # (the library: any seahelm NetCDF file)
    with pytest.raises(OutputExistsError, match="not written by `seahelm plot`"):
        check_output(nc, "netcdf", command="seahelm plot")
    path = tmp_path / "s.toml"  # a ship file its own command wrote: edited since, perhaps
    path.write_text("# seahelm ship file\n" + written_by_line("seahelm ship scale"))
    with pytest.raises(OutputExistsError, match="perhaps edited since"):
        check_output(path, "toml", command="seahelm ship scale")
    atomic_write(path, _text("x"))  # (the bare atomic write checks nothing)
    assert path.read_text() == "x"
