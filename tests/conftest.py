"""Shared fixtures and helpers, the order of a parallel run and the unit tier.

- a non-interactive matplotlib backend; the catalog ships the suite uses most, once per session;
- the result files of the HTML report's tests, once per session;
- under xdist (``make test``: ``-n 2 --dist worksteal``) the modules known to take longest go
  first, a share at the head of each worker's queue (:func:`order_for_workers`), so that no long
  test starts last and serialises the end of the run;
- the ``slow`` marker on every test outside the unit tier (:data:`UNIT_MODULES`):
  ``make test-fast`` runs ``-m "not slow"``.
"""

from __future__ import annotations

import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")
#: One OpenBLAS thread in the xdist workers and in every subprocess (benchmarks, ``seahelm``
#: commands), which inherit this environment: two workers on 2 cores, each with OpenBLAS's
#: default of a thread per core, oversubscribe the machine and its threads spin-wait, so that a
#: small SVD (1800 x 16) took 0.024 s of CPU instead of 0.0006 s and
#: tests/test_analysis_nomoto_fit.py 57 s of CPU instead of 10 s (no compile in either; its
#: 58 s in the fresh-clone census). (This process's OpenBLAS is loaded already, by plugins:
#: a run with -n 0 keeps the default unless the variable is set outside.)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


@pytest.fixture
def mariner2():
    from seahelm.ships import get_ship

    return get_ship("mariner-nomoto2").params


@pytest.fixture
def mariner1():
    from seahelm.ships import get_ship

    return get_ship("mariner-nomoto1").params


@pytest.fixture(scope="session")
def kvlcc2_l7():
    """The model-scale KVLCC2 (L = 7 m) of the catalog, MMG standard model (a frozen Ship)."""
    from seahelm.ships import get_ship

    return get_ship("kvlcc2-l7")


@pytest.fixture(scope="session")
def kvlcc2_full():
    """The full-scale KVLCC2 (L = 320 m) of the catalog (a frozen Ship)."""
    from seahelm.ships import get_ship

    return get_ship("kvlcc2-full")


@pytest.fixture(scope="session")
def mariner_linear():
    """``linearize("mariner-nonlinear", actuator=False)``: the Mariner's straight run."""
    from seahelm.analysis.equilibria.linearisation import linearize

    return linearize("mariner-nonlinear", actuator=False)


@pytest.fixture(scope="session")
def kvlcc2_l7_linear():
    """``linearize("kvlcc2-l7", actuator=False)``: the KVLCC2's straight run (a kink)."""
    from seahelm.analysis.equilibria.linearisation import linearize

    return linearize("kvlcc2-l7", actuator=False)


@pytest.fixture(scope="session")
def kvlcc2_l7_imo():
    """``imo_check("kvlcc2-l7")``: the IMO MSC.137(76) check of the model-scale KVLCC2
    (turning circles, zig-zags, stopping), run once for the suite: its tests read it
    (tests/test_analysis_imo.py, the figures of tests/test_plotting_labels.py)."""
    from seahelm.analysis.imo import imo_check

    return imo_check("kvlcc2-l7")


def pytest_report_header(config):
    from seahelm.versions import version_report

    return f"seahelm tested with: {version_report()}"


def pytest_configure(config):
    """With SEAHELM_REQUIRE_EMPTY_CACHE=1 (set by .ci/run), refuse to start on a warm cache.

    A test that passes only because a kernel compiled by other code is still on disk is how a
    fresh-machine failure hid before; CI must start from nothing. Checked once, in the
    controlling process (not in xdist workers, which start after it).

    Registers the order of a parallel run (:class:`_OrderForWorkers`) and, with
    ``SEAHELM_TEST_COMPILE_TIMES`` set, the compile log of every test (:class:`CompileTimes`);
    with ``SEAHELM_TEST_KERNEL_CENSUS`` set, the census of the kernels (:class:`KernelCensus`).
    """
    config.pluginmanager.register(_OrderForWorkers(), "seahelm-order-for-workers")
    if os.environ.get("SEAHELM_TEST_KERNEL_CENSUS"):
        config.pluginmanager.register(KernelCensus(os.environ["SEAHELM_TEST_KERNEL_CENSUS"]),
                                      "seahelm-kernel-census")
    if os.environ.get("SEAHELM_TEST_COMPILE_TIMES"):  # (xdist's controller runs no test)
        from numba.core import event

        times = CompileTimes(os.environ["SEAHELM_TEST_COMPILE_TIMES"])
        event.register("numba:compile", times.listener())
        config.pluginmanager.register(times, "seahelm-compile-times")
    if not os.environ.get("SEAHELM_REQUIRE_EMPTY_CACHE") or hasattr(config, "workerinput"):
        return
    from pathlib import Path

    kernels = os.environ.get("SEAHELM_CACHE_DIR")
    if not kernels:
        pytest.exit("SEAHELM_REQUIRE_EMPTY_CACHE is set but SEAHELM_CACHE_DIR is not", returncode=3)
    # numba makes empty per-package folders when cache=True functions are decorated: count files
    warm = [str(p) for p in (Path(kernels), Path(os.environ.get("NUMBA_CACHE_DIR", "")))
            if str(p) not in ("", ".") and p.is_dir() and any(f.is_file() for f in p.rglob("*"))]
    if warm:
        pytest.exit(f"the kernel cache is not empty at the start of the run: {warm}", returncode=3)


# ------------------------------------------------------------------------------------------
# result files of the HTML report's tests (tests/test_report*.py), made once per session on
# component combinations the suite compiles anyway (the demo's; the KVLCC2 MMG of
# `seahelm imo`)
# ------------------------------------------------------------------------------------------
#: A 2-point grid × 5 Monte-Carlo samples on the demo's components (tests/test_cli_inspect.py
#: runs the same combination): kp = 4 leaves the yaw-rate bounds in every sample (diverged,
#: "state out of bounds"), kp = 1 never does.
REPORT_BATCH_SCENARIO = """
title = "report test batch"
[vessel]
catalog = "mariner-nomoto2"
[actuator]
model = "rudder-servo"
[controller]
model = "pid-heading"
dt = 0.5
[controller.params]
kp = 3.0
kd = 60.0
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = 120.0
dt = 0.1
record_every = 5
bounds = { yaw_rate = [-0.006, 0.006] }
[batch.grid]
"controller.params.kp" = [1.0, 4.0]
[batch.monte_carlo]
runs = 5
seed = 3
[batch.monte_carlo.draws]
"vessel.params.gain" = {distribution = "normal", mean = 0.185, std = 0.04}
"""


#: The demo's ship (Nomoto, 2nd order) under the PID heading autopilot, a seeded Monte-Carlo
#: batch over ``t1``: the CLI's reliability tests (tests/test_cli_silent_wrong.py,
#: tests/test_cli_stop_signals.py). Fill in with :func:`nomoto_monte_carlo`.
NOMOTO_MONTE_CARLO = """[vessel]
catalog = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 20.0
[simulation]
t_final = {t_final}
dt = 0.1
record_every = {record_every}
[batch.monte_carlo]
runs = {runs}
seed = 1
[batch.monte_carlo.draws]
"vessel.params.t1" = {{ distribution = "uniform", low = 90.0, high = 150.0 }}
"""


def nomoto_monte_carlo(t_final: float, runs: int = 1, record_every: int = 10) -> str:
    """:data:`NOMOTO_MONTE_CARLO` for ``t_final`` [s] (dt 0.1 s), ``runs`` runs, recorded every
    ``record_every`` steps."""
    return NOMOTO_MONTE_CARLO.format(t_final=t_final, runs=runs, record_every=record_every)


def one_error(args: list[str]) -> str:
    """Run ``seahelm ARGS``; assert exit 2 with one ``error:`` line on stderr and nothing on
    stdout; return that line."""
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert res.stdout == "", res.stdout
    return lines[0]


def _invoke(args, exit_code=0):
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    res = CliRunner().invoke(app, args)
    assert res.exit_code == exit_code, (res.stdout, res.stderr)
    return res


@pytest.fixture(scope="session")
def report_demo_dir(tmp_path_factory):
    """`seahelm demo --out DIR`: result.nc, overview.png and report.html."""
    out = tmp_path_factory.mktemp("report-demo")
    _invoke(["demo", "--out", str(out)])
    return out


@pytest.fixture(scope="session")
def report_batch_dir(tmp_path_factory):
    """`seahelm run --report` of :data:`REPORT_BATCH_SCENARIO`: a grid × Monte-Carlo batch
    with diverged runs (result.nc and report.html)."""
    where = tmp_path_factory.mktemp("report-batch")
    scenario = where / "batch.toml"
    scenario.write_text(REPORT_BATCH_SCENARIO)
    # exit code 3: all written, some runs diverged
    _invoke(["run", str(scenario), "--out", str(where / "out"), "--no-plot", "--report"],
            exit_code=3)
    return where / "out"


@pytest.fixture(scope="session")
def report_imo_dir(tmp_path_factory):
    """`seahelm imo kvlcc2-l7 --out DIR` (turning and zig-zag runs and metrics, the criteria)
    and `seahelm report` of it (report.html)."""
    out = tmp_path_factory.mktemp("report-imo")
    _invoke(["imo", "kvlcc2-l7", "--out", str(out)])
    _invoke(["report", str(out / "turning-circle-runs.nc"), "-o", str(out / "report.html")])
    return out


@pytest.fixture(scope="session")
def report_sweep_dir(tmp_path_factory):
    """`seahelm sweep` of :data:`REPORT_BATCH_SCENARIO` (the demo's components: its kernel is
    compiled once for the suite) in chunks of 4 into a store, and `seahelm report` of it."""
    where = tmp_path_factory.mktemp("report-sweep")
    scenario = where / "batch.toml"
    scenario.write_text(REPORT_BATCH_SCENARIO)
    _invoke(["sweep", str(scenario), "--store", str(where / "sweep.zarr"), "--chunk-size", "4"],
            exit_code=3)  # (some runs diverge)
    _invoke(["report", str(where / "sweep.zarr"), "-o", str(where / "report.html")])
    return where


# ------------------------------------------------------------------------------------------
# the order of a parallel run: the long modules first, a share at the head of each worker
# ------------------------------------------------------------------------------------------
def _docs(group: str) -> str:
    """The node id of a group of docs commands (tests/test_docs_commands.py)."""
    return f"tests/test_docs_commands.py::test_every_command_runs_as_written_in_order[{group}]"


#: Seconds the slowest modules (or test functions, or single tests: see :func:`ordering_key`)
#: take in a fresh clone's `make test` (empty kernel cache, 2 cores; most of it is compiling
#: kernels): CPU seconds per module (the process's and its finished children's, summed over the
#: module's tests) of the fresh-clone run of 2026-12-02 16:31 (/tmp/fresh11, a loaded machine)
#: with ``SEAHELM_TEST_COMPILE_TIMES`` (:class:`CompileTimes`), every module of 12 s or more
#: but those whose cost went since: tests/test_analysis_nomoto_fit.py (58 s then, ~10 s with one
#: OpenBLAS thread, below) and tests/test_environment_first_order.py (20 s then, ~5 s now). In
#: that run the two workers were busy to the end (the tests' seconds summed to 2 × the wall
#: time less the two collections). The docs-command groups (one test per file then:
#: getting-started.rst 142 s, README.md 65 s) are CPU seconds of their commands in an empty
#: cache: ``seahelm imo``'s IMO kernels 63 s, then each command that reuses them 2 to 7 s.
#: Only the order of the run depends on them: a wrong or missing figure costs time, not a test.
LONG_MODULES: dict[str, float] = {
    _docs("README.md:imo-cargo.toml-out-imo"): 70.0,
    _docs("getting-started.rst:maneuver-turning-ship-my.toml-rudder-35"): 30.0,
    _docs("getting-started.rst:run-examples-mariner-monte-carlo.toml"): 20.0,
    _docs("README.md:maneuver-turning-ship-cargo.toml-rudder"): 12.0,
    _docs("getting-started.rst:maneuver-turning-ship-son-nomoto"): 12.0,
    _docs("getting-started.rst:sweep-examples-mariner-monte-carlo.toml"): 10.0,
    _docs("getting-started.rst:run-examples-mariner-route-ilos.toml-out"): 10.0,
    _docs("getting-started.rst:autopilot-tune-mariner-nonlinear"): 10.0,
    "tests/test_benchmarks_quick.py": 208.3,
    "tests/test_simulation_pure_python.py": 200.9,
    "tests/test_scenario.py": 137.6,
    "tests/test_simulation_integrators.py": 117.9,
    "tests/test_cli_stop_signals.py": 63.3,
    "tests/test_first_order_in_loop.py": 47.4,
    "tests/test_encounters_store.py": 28.3,
    "tests/test_output_policy.py": 27.4,
    "tests/test_examples_scripts.py": 26.2,
    "tests/test_control_baselines.py": 25.9,
    "tests/test_control_lq_cross_track.py": 22.1,
    "tests/test_sweep_dask.py": 20.9,
    "tests/test_dp_observer.py": 20.8,
    "tests/test_simulation_wiring.py": 20.8,
    "tests/test_scenario_first_order_in_loop.py": 20.7,
    "tests/test_reversals.py": 20.0,
    "tests/test_kernel_cache.py": 19.3,
    "tests/test_report.py": 19.2,
    "tests/test_simulation_batch.py": 18.2,
    "tests/test_cli_main.py": 16.9,
    "tests/test_control_state_space.py": 16.5,
    "tests/test_replay.py": 16.2,
    "tests/test_analysis_maneuvers_constant_speed.py": 15.8,
    "tests/test_control_autopilot_design.py": 15.8,
    "tests/test_docs_coming_from.py": 15.6,
    "tests/test_control_held_rps.py": 15.6,
    "tests/test_reliability_fuzz.py": 15.3,
    "tests/test_analysis_nomoto_fit_start.py": 15.2,
    "tests/test_control_final_state.py": 15.0,
    "tests/test_studies_lvov2014.py": 13.6,
    "tests/test_control_path_following.py": 12.8,
}

#: Entries run right after a long entry, on its worker, because they need the kernels it
#: compiles: the README's ``seahelm imo cargo.toml`` compiles the MMG's IMO kernels (turning
#: circles, zig-zags, crash stop; an estimated ship's are the KVLCC2's: after it, ``seahelm imo
#: kvlcc2-l7`` compiles nothing) that the page's ``seahelm imo kvlcc2-l7`` (and its Monte-Carlo
#: draws, its single manoeuvres) and ``imo_check("kvlcc2-l7")`` (73 s of setup in a fresh
#: clone) would compile again at the same time on the other worker.
FOLLOWERS: dict[str, tuple[str, ...]] = {
    _docs("README.md:imo-cargo.toml-out-imo"): (
        _docs("getting-started.rst:imo-kvlcc2-l7-out-imo"),
        _docs("getting-started.rst:imo-kvlcc2-l7-monte-carlo-50-seed-1"),
        _docs("getting-started.rst:maneuver-stopping-ship-kvlcc2-l7"),
        _docs("getting-started.rst:maneuver-spiral-ship-kvlcc2-l7"),
        _docs("getting-started.rst:maneuver-pullout-ship-kvlcc2-l7-rudder"),
        _docs("README.md:maneuver-zigzag-ship-cargo.toml-rudder"),
        "tests/test_analysis_imo.py", "tests/test_plotting_labels.py"),
    # the same turning circle in 10 m of water
    _docs("README.md:maneuver-turning-ship-cargo.toml-rudder"): (
        _docs("getting-started.rst:maneuver-turning-ship-cargo.toml-rudder"),),
    # the Esso Osaka with Fujiwara's wind loads from the measured wind (a replay there, an MMG
    # fit here): one kernel, 26 s CPU to compile, that only these two modules use
    "tests/test_reversals.py": ("tests/test_mmg_multi_record.py",),
    # the supply vessel's DP loops in waves: examples/supply_dp_observer_waves.toml's kernel
    # (dp-pid-observer, the sea's mean loads and first-order motions, the sensors) is the one of
    # test_dp_observer's observer runs and test_sensor_stage's stepping test; dp-pid in the same
    # sea (test_dp_observer's raw runs) is test_sensor_stage's, test_sensor_defaults' and
    # test_restart_clock_time_varying's (each ~20-30 s CPU to compile in a fresh clone)
    "tests/test_scenario.py": ("tests/test_dp_observer.py", "tests/test_sensor_stage.py",
                               "tests/test_sensor_defaults.py",
                               "tests/test_restart_clock_time_varying.py"),
}


def worksteal_shares(n_items: int, n_workers: int) -> list[int]:
    """How many of ``n_items`` tests xdist's ``worksteal`` scheduler first sends to each of
    ``n_workers`` idle workers: consecutive slices, worker ``i`` ``remaining // (n - i)``
    (``xdist.scheduler.worksteal.WorkStealingScheduling.check_schedule``). Later it steals
    from the tail of the longest queue, so the head of each slice runs on that worker."""
    shares, remaining = [], n_items
    for i in range(n_workers):
        shares.append(remaining // (n_workers - i))
        remaining -= shares[-1]
    return shares


def ordering_key(nodeid: str, keys) -> str | None:
    """The entry of ``keys`` that names test ``nodeid``, the most specific first: its node id,
    its function (``module::name`` for every parameter), its module; None if none does."""
    for key in (nodeid, nodeid.split("[", 1)[0], nodeid.split("::", 1)[0]):
        if key in keys:
            return key
    return None


def order_for_workers(items: list, n_workers: int, seconds: dict[str, float],
                      followers: dict[str, tuple[str, ...]] | None = None) -> list:
    """``items`` reordered for ``n_workers``: the entries of ``seconds`` (a module's path, a
    test function's ``module::name`` or one test's node id, see :func:`ordering_key`), longest
    first, each to the worker with the fewest seconds so far, at the head of that worker's
    slice (see :func:`worksteal_shares`), each followed by its ``followers`` (entries that
    reuse its kernels); every other test after them in its own order. The tests of an entry
    keep their order and stay together (a module's fixtures are made once)."""
    followers = followers or {}
    keys = set(seconds) | {f for fs in followers.values() for f in fs}
    named = [ordering_key(item.nodeid, keys) for item in items]
    leaders = {k for k in named if k in seconds}
    placed = leaders | {f for k in leaders for f in followers.get(k, ())}
    by_key: dict[str, list] = {}
    rest = []
    for item, key in zip(items, named):
        if key in placed:
            by_key.setdefault(key, []).append(item)
        else:
            rest.append(item)
    heads: list[list] = [[] for _ in range(n_workers)]
    load = [0.0] * n_workers
    for name in sorted((k for k in seconds if k in by_key), key=lambda k: (-seconds[k], k)):
        worker = min(range(n_workers), key=lambda w: (load[w], w))
        for each in (name, *followers.get(name, ())):
            if each in by_key:
                heads[worker].extend(by_key.pop(each))
                load[worker] += seconds.get(each, 0.0)
    ordered, start = [], 0
    for head, share in zip(heads, worksteal_shares(len(items), n_workers)):
        fill = max(0, share - len(head))
        ordered += head + rest[start:start + fill]
        start += fill
    return ordered + rest[start:]


# ------------------------------------------------------------------------------------------
# where a fresh clone's time goes: SEAHELM_TEST_COMPILE_TIMES=FILE
# ------------------------------------------------------------------------------------------
class CompileTimes:
    """Per test, the seconds numba spent compiling in this process and what it compiled.

    With ``SEAHELM_TEST_COMPILE_TIMES=FILE`` (an empty kernel cache and numba cache make it
    tell a fresh clone's story) every test appends one JSON line to FILE: ``test`` (its node
    id), ``seconds`` (wall, setup to teardown), ``cpu`` (this process and its finished
    children), ``compile`` (seconds of the outermost compilations) and ``compiled``
    (``[function, seconds]``; a kernel is ``seahelm_kernel_<hash>.run_slice``, one hash per
    combination of components) and ``kernels`` (the closed-loop kernels this test was the first
    in its process to use, compiled or loaded from the cache). A kernel that one test alone
    compiles and no other uses is a combination only it needs. Subprocesses (``seahelm``
    commands) are not followed: their compilations are in their ``cpu``. xdist workers append
    to the same file.
    """

    def __init__(self, path: str):
        self.path, self.depth, self.start, self.compiled = path, 0, 0.0, []

    def on_start(self, ev) -> None:
        import time

        if self.depth == 0:
            self.start = time.perf_counter()
        self.depth += 1

    def on_end(self, ev) -> None:
        import time

        self.depth -= 1
        if self.depth == 0:
            py = getattr((ev.data or {}).get("dispatcher"), "py_func", None)
            name = f"{getattr(py, '__module__', '?')}.{getattr(py, '__qualname__', '?')}"
            self.compiled.append([name, round(time.perf_counter() - self.start, 3)])

    def listener(self):
        from numba.core import event

        times = self

        class _Listener(event.Listener):  # type: ignore[misc]
            def on_start(self, ev):
                times.on_start(ev)

            def on_end(self, ev):
                times.on_end(ev)

        return _Listener()

    @staticmethod
    def _cpu() -> float:
        import resource

        own, children = (resource.getrusage(w) for w in (resource.RUSAGE_SELF,
                                                          resource.RUSAGE_CHILDREN))
        return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime

    @staticmethod
    def _kernels() -> set[str]:
        import sys

        return {name for name in sys.modules if name.startswith("seahelm_kernel_")}

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(self, item, nextitem):
        import json
        import time

        self.compiled, start, cpu = [], time.perf_counter(), self._cpu()
        before = self._kernels()
        yield
        row = {"test": item.nodeid, "seconds": round(time.perf_counter() - start, 3),
               "cpu": round(self._cpu() - cpu, 3),
               "compile": round(sum(s for _, s in self.compiled), 3), "compiled": self.compiled,
               "kernels": sorted(self._kernels() - before)}
        with open(self.path, "a", encoding="utf-8") as fh:
            fh.write(json.dumps(row) + "\n")


class KernelCensus:
    """Which combination of components each test needs, without compiling any.

    With ``SEAHELM_TEST_KERNEL_CENSUS=FILE`` every test that builds a closed-loop kernel
    appends ``{"test": node id, "kernel": "seahelm_kernel_<hash>"}`` to FILE and stops there
    (skipped: "kernel census"): nothing is compiled for it and it does not pass (a census, not
    a test run). Only a test's first kernel is seen, and not those of ``seahelm`` subprocesses
    (which run and compile as usual). A kernel only one test names is a combination only that
    test needs."""

    def __init__(self, path: str):
        self.path, self.test = path, None

    def pytest_configure(self, config) -> None:
        import seahelm.simulation.closed_loop as closed_loop

        real = closed_loop.import_generated

        def census(name: str, text: str):
            if not name.startswith("seahelm_kernel_"):
                return real(name, text)
            import json

            with open(self.path, "a", encoding="utf-8") as fh:
                fh.write(json.dumps({"test": self.test, "kernel": name}) + "\n")
            pytest.skip("kernel census")

        closed_loop.import_generated = census

    @pytest.hookimpl(tryfirst=True)
    def pytest_runtest_setup(self, item) -> None:
        self.test = item.nodeid


# ------------------------------------------------------------------------------------------
# the unit tier (`make test-fast`: -m "not slow")
# ------------------------------------------------------------------------------------------
#: The modules of the unit tier: none compiles a closed-loop kernel or starts seahelm in a
#: process, and together they take under 3 minutes in a fresh clone (empty kernel and numba
#: caches, `make test-fast` on 2 cores). Every test of every other module is marked ``slow``
#: (as are the tests marked so by hand): ``make test`` runs them all. A new module joins the
#: tier here once it is measured cheap in a fresh clone.
UNIT_MODULES: frozenset[str] = frozenset({
    "tests/test_actuators_servo.py",
    "tests/test_analysis_averaging.py",
    "tests/test_analysis_course_keeping.py",
    "tests/test_analysis_response_statistics.py",
    "tests/test_analysis_seakeeping.py",
    "tests/test_analysis_statistics.py",
    "tests/test_cli_averaging.py",
    "tests/test_cli_compensate.py",
    "tests/test_cli_help.py",
    "tests/test_cli_identify.py",
    "tests/test_cli_seakeeping.py",
    "tests/test_cli_style.py",
    "tests/test_cli_waves.py",
    "tests/test_components_contract.py",
    "tests/test_content_digest.py",
    "tests/test_control_autopilot_design_pvs.py",
    "tests/test_control_compensation.py",
    "tests/test_control_guidance.py",
    "tests/test_docs.py",
    "tests/test_environment_blendermann.py",
    "tests/test_environment_encounter_motion.py",
    "tests/test_environment_rao.py",
    "tests/test_environment_rao_capytaine.py",
    "tests/test_environment_rao_wigley.py",
    "tests/test_environment_sea_state.py",
    "tests/test_environment_shaping.py",
    "tests/test_environment_spectra.py",
    "tests/test_environment_spectra_mss.py",
    "tests/test_environment_wave_forces.py",
    "tests/test_environment_wind_gust.py",
    "tests/test_hydrodynamics_estimates.py",
    "tests/test_hydrodynamics_four_quadrant.py",
    "tests/test_hydrodynamics_low_speed_hull.py",
    "tests/test_hydrodynamics_propeller_series.py",
    "tests/test_hydrodynamics_resistance.py",
    "tests/test_identification_turn_log.py",
    "tests/test_import_graph.py",
    "tests/test_linearize_bad_input.py",
    "tests/test_package.py",
    "tests/test_plotting_save.py",
    "tests/test_plotting_seakeeping.py",
    "tests/test_properties.py",
    "tests/test_resources.py",
    "tests/test_scenario_limits.py",
    "tests/test_scenario_particulars.py",
    "tests/test_shallow_water_bad_input.py",
    "tests/test_ships.py",
    "tests/test_ships_estimate.py",
    "tests/test_ships_estimate_course_unstable.py",
    "tests/test_ships_scaling.py",
    "tests/test_simulation_reference.py",
    "tests/test_studies_platonov.py",
    "tests/test_studies_romanov_chirkova.py",
    "tests/test_studies_shushlyapin2017.py",
    "tests/test_studies_sushchenko2010.py",
    "tests/test_suite_order.py",
    "tests/test_suite_threads.py",
    "tests/test_top_level_api.py",
    "tests/test_vessels_engine_shaft.py",
})


#: The tests of the unit modules that compile a closed-loop kernel all the same (12 to 20 s
#: each in a fresh clone), the other tests of their modules none: ``slow`` too.
SLOW_UNIT_TESTS: frozenset[str] = frozenset({
    "tests/test_ships.py::test_a_new_vessel_model_is_one_module_and_one_registry_line",
    "tests/test_ships_estimate.py::test_cli_estimate_then_imo",
    "tests/test_ships_scaling.py::test_froude_similarity_of_the_turning_circle",
})


def mark_outside_the_unit_tier(items: list, unit: frozenset[str] = UNIT_MODULES,
                               slow: frozenset[str] = SLOW_UNIT_TESTS) -> None:
    """Add the ``slow`` marker to every item whose module is not in ``unit`` and to the
    items named in ``slow`` (node ids without the parameters)."""
    for item in items:
        if item.nodeid.split("::", 1)[0] not in unit or item.nodeid.split("[", 1)[0] in slow:
            item.add_marker(pytest.mark.slow)


@pytest.hookimpl(tryfirst=True)  # (before -m deselects)
def pytest_collection_modifyitems(config, items):
    mark_outside_the_unit_tier(items)


class _OrderForWorkers:
    """Registered by :func:`pytest_configure`: reorders after every deselection (-m, -k), so
    the slices are those of the tests that run."""

    @pytest.hookimpl(trylast=True)
    def pytest_collection_modifyitems(self, config, items):
        workers = getattr(config, "workerinput", {}).get("workercount", 0)
        if workers >= 2:  # (every worker computes the same order: xdist checks they agree)
            items[:] = order_for_workers(items, workers, LONG_MODULES, FOLLOWERS)
