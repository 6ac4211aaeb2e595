"""Time to first result: `seahelm demo` cold and warm, with the breakdown by phase.

*Cold* runs with an empty kernel cache and numba cache (new temporary directories), as on a
fresh machine or after an upgrade: the demo's component combination compiles. *Warm* is the
same command again with those caches filled. Each phase is timed in a fresh Python process
that does what ``seahelm demo`` does, step by step:

* imports — ``import seahelm.cli.main`` and what the demo pulls in (scenario, engine, xarray);
* compile/load — the engine's zero-step call that compiles the kernel or loads it from the
  cache (``metadata["compile_time_s"]``);
* run — the simulation itself (``metadata["wall_time_s"]``);
* write — ``result.nc`` (NetCDF through xarray/h5netcdf);
* plot — matplotlib import, the overview figure and its PNG;
* report — the HTML report (``report.html``) from the result in memory.

The whole command is timed too (``seahelm demo --json``, a subprocess, wall clock). Prints
medians of several warm repetitions and the cold figures.

Then the first use of other component combinations, each in a fresh process with empty caches:
the example scenarios of every kind of model (Nomoto, the nonlinear Mariner, the KVLCC2 MMG
with and without wind and waves, the catamaran, Voitkunsky's model under the compensated
autopilot), with the kernel's
compile time (``compile_time_s``) and the whole first run (imports excluded).

Python's own bytecode cache is left on (``PYTHONDONTWRITEBYTECODE`` is removed from the
environment), as on a user's machine: with it set, every seahelm module is compiled from
source at each start (about 0.1 s).

    python benchmarks/bench_startup.py [--repeats 5] [--no-combinations] [--quick]

``--quick`` (the test suite's smoke run): the warm phases only, once, with the caches as they
are (no demo command, no cold run, no combinations).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PHASES = r"""
import json, sys, time
t0 = time.perf_counter()
from seahelm.cli import main as cli
from seahelm.scenario import default_scenario_text, parse_scenario, run_scenario
from seahelm.analysis.maneuvers import summarize
t_import = time.perf_counter() - t0
batch = parse_scenario(default_scenario_text(), source="<embedded default scenario>")
result = run_scenario(batch)
summarize(result)
t1 = time.perf_counter()
result.to_netcdf(sys.argv[1] + "/result.nc")
t_write = time.perf_counter() - t1
t2 = time.perf_counter()
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
fig = result.plot()
fig.savefig(sys.argv[1] + "/overview.png", dpi=110, format="png")
plt.close(fig)
t_plot = time.perf_counter() - t2
t3 = time.perf_counter()
from seahelm.report import report_data_from_dataset, write_report
write_report(report_data_from_dataset(result.to_xarray(), sources=(sys.argv[1] + "/result.nc",)),
             sys.argv[1] + "/report.html")
t_report = time.perf_counter() - t3
print(json.dumps({"imports": t_import, "compile/load": result.metadata["compile_time_s"],
                  "run": result.metadata["wall_time_s"], "write": t_write, "plot": t_plot,
                  "report": t_report, "total in process": time.perf_counter() - t0}))
"""


def _env(cache: Path | None) -> dict[str, str]:
    env = dict(os.environ, MPLBACKEND="Agg")
    if cache is not None:  # (None: the caches as they are)
        env.update(SEAHELM_CACHE_DIR=str(cache / "kernels"), NUMBA_CACHE_DIR=str(cache / "numba"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


#: Example scenarios whose component combinations are compiled from empty caches.
COMBINATIONS = {
    "Nomoto-2 + servo + PID (demo)": None,
    "nonlinear Mariner zig-zag": "mariner_zigzag.toml",
    "KVLCC2 MMG turning circles": "kvlcc2_turning_circles.toml",
    "KVLCC2 MMG + wind and waves": "kvlcc2_turning_weather.toml",
    "catamaran + final-state heading": "catamaran_heading_0p8.toml",
    "Voitkunsky + compensated PID + loads": "compensation_storm_compensated.toml",
    "nonlinear Mariner on a LOS route": "mariner_route_los.toml",
}

FIRST_USE = r"""
import json, sys, time
from seahelm.scenario import default_scenario_text, load_scenario, parse_scenario, run_scenario
job = (parse_scenario(default_scenario_text()) if sys.argv[1] == "-"
       else load_scenario(sys.argv[1]))
t0 = time.perf_counter()
result = run_scenario(job)
first = time.perf_counter() - t0
attrs = result.metadata if hasattr(result, "metadata") else result.runs.attrs
print(json.dumps({"compile": attrs["compile_time_s"], "first run": first}))
"""


def first_use(scenario: str | None, cache: Path) -> dict[str, float]:
    path = "-" if scenario is None else str(Path(__file__).parents[1] / "examples" / scenario)
    res = subprocess.run([sys.executable, "-c", FIRST_USE, path], env=_env(cache),
                         capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def phases(cache: Path | None, out: Path) -> dict[str, float]:
    res = subprocess.run([sys.executable, "-c", PHASES, str(out)], env=_env(cache),
                         capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def demo_wall(cache: Path | None, out: Path) -> float:
    exe = Path(sys.executable).with_name("seahelm")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "seahelm"]
    t0 = time.perf_counter()
    subprocess.run([*cmd, "demo", "--out", str(out), "--json"], env=_env(cache),
                   capture_output=True, check=True)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--no-combinations", dest="combinations", action="store_false",
                        help="Skip the first use of the other component combinations.")
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        if args.quick:  # (the demo command itself is the CLI tests')
            print(f"seahelm startup benchmark (--quick: the phases once, warm caches as they "
                  f"are), {os.cpu_count()} cores")
            for key, value in phases(None, root).items():
                print(f"{key:>26}: {value:6.2f} s")
            return
        print(f"seahelm startup benchmark, {os.cpu_count()} cores; warm figures are medians "
              f"of {args.repeats} runs")
        cold_wall = demo_wall(root / "cache-a", root)
        cold = phases(root / "cache-b", root)
        warm_wall = statistics.median(demo_wall(root / "cache-a", root)
                                      for _ in range(args.repeats))
        runs = [phases(root / "cache-b", root) for _ in range(args.repeats)]
        warm = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
        print(f"{'seahelm demo (wall clock)':>26}: cold {cold_wall:7.2f} s   warm {warm_wall:6.2f} s")
        for key in cold:
            print(f"{key:>26}: cold {cold[key]:7.2f} s   warm {warm[key]:6.2f} s")
        if args.combinations:
            print("\nfirst use of a component combination (empty caches, one process each):")
            print(f"{'combination':>38}  {'compile':>8}  {'first run':>9}")
            for i, (label, scenario) in enumerate(COMBINATIONS.items()):
                fig = first_use(scenario, root / f"cache-c{i}")
                print(f"{label:>38}  {fig['compile']:7.2f}s  {fig['first run']:8.2f}s")


if __name__ == "__main__":
    main()
