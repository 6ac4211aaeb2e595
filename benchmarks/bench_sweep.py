"""Sweeps: runs/s in-process vs 2 local dask workers, and the chunking overhead.

The KVLCC2 L7 35° starboard turning circle (80 s, the default RK4 step 0.05 s) over
``--runs`` Monte-Carlo samples of its linear derivatives (Y'_v, Y'_r, N'_v, N'_r, 10 % standard
deviation): one run per sample, each with its own steady approach (self-propulsion rps and
trim), simulated and measured (advance, transfer, tactical diameter, ...). Timed, end to end:

* ``monolithic``: the manoeuvre of all samples as one batch (the library, no store):
  ``ManeuverJob.run_ships(job.ships())``;
* ``in-process``: ``run_sweep`` with nothing configured (automatic chunks, the compiled
  parallel engine, results streamed to a fresh Zarr store, summary statistics);
* ``2 workers``: ``run_sweep`` on a local dask cluster of 2 worker processes (1 thread each),
  started and warmed up (imports, kernel loaded from the cache) before the timing; its start-up
  is printed apart.

The engine's share of the monolithic run bounds what local workers can gain: the engine
already runs on a thread per core in-process, so 2 workers on 2 cores parallelise only the rest
(at most 1 / (e + (1 − e)/2) for a share e; printed with the figures).

Medians of ``--repeats`` runs; the chunking overhead is in-process / monolithic − 1 (the
issue's bound: ≤ 10 %). On a machine shared with other jobs the figures move by tens of per
cent from one run to the next; the ratios are taken within one repeat.

    python benchmarks/bench_sweep.py [--runs 10000] [--repeats 3] [--no-dask] [--quick]

``--quick`` (the test suite's smoke run): 20 runs, 1 repeat, no dask.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from seahelm.scenario import parse_scenario
from seahelm.sweep import run_sweep
from seahelm.ships import get_ship

DERIVATIVES = ("Y_v", "Y_r", "N_v", "N_r")


def scenario(runs: int, seed: int = 1) -> str:
    params = get_ship("kvlcc2-l7").params
    draws = "\n".join(
        f'"vessel.params.{n}" = {{ distribution = "normal", mean = {getattr(params, n)!r}, '
        f'std = {abs(0.1 * getattr(params, n))!r} }}' for n in DERIVATIVES)
    return ('title = "bench: KVLCC2 L7 35 deg turning, uncertain linear derivatives"\n'
            '[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\nrudder_deg = 35\n'
            'sides = "starboard"\nt_final = 80.0\n'
            f"[batch.monte_carlo]\nruns = {runs}\nseed = {seed}\n"
            f"[batch.monte_carlo.draws]\n{draws}\n")


def _clear() -> None:
    from seahelm.analysis.maneuvers.ships import clear_approaches

    clear_approaches()


def _forget_approaches(client) -> None:
    """Clear the memo of steady approaches (here and on the workers): every timing computes
    each sample's approach, as a first sweep does."""
    _clear()
    if client is not None:
        client.run(_clear)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10_000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-dask", action="store_true", help="skip the 2-worker timing")
    ap.add_argument("--quick", action="store_true",
                    help="smoke run (the test suite's): 20 runs, 1 repeat, no dask")
    args = ap.parse_args()
    if args.quick:
        args.runs, args.repeats, args.no_dask = 20, 1, True

    work = Path(tempfile.mkdtemp(prefix="seahelm-bench-sweep-"))
    text = scenario(args.runs)
    path = work / "bench.toml"
    path.write_text(text)
    job = parse_scenario(text, source=str(path))
    job.run_ships(job.ships(0, 2))  # compile / load the kernel, outside the timings
    run_sweep(work / "warm.toml", work / "warm.zarr", text=scenario(4, seed=99))

    client = cluster = None
    if not args.no_dask:
        from seahelm.sweep.executors import executor

        t0 = time.perf_counter()
        pool = executor(workers=2)
        pool.__enter__()
        client, cluster = pool.client, pool
        started = time.perf_counter() - t0
        t0 = time.perf_counter()
        run_sweep(work / "warm2.toml", work / "warm2.zarr", text=scenario(8, seed=99), chunk_size=4,
                  client=client)
        warm = time.perf_counter() - t0
        print(f"local cluster of 2 workers: started in {started:.1f} s, warmed up (imports, "
              f"kernel from the cache) in {warm:.1f} s")

    times: dict[str, list[float]] = {"monolithic": [], "in-process": [], "2 workers": []}
    engine: list[float] = []  # the monolithic run's time in the engine's batch
    chunk = {}
    for rep in range(args.repeats):
        _forget_approaches(client)
        t0 = time.perf_counter()
        result = job.run_ships(job.ships())
        times["monolithic"].append(time.perf_counter() - t0)
        engine.append(float(result.simulation.metadata["wall_time_s"]))
        store = work / f"here-{rep}.zarr"
        _forget_approaches(client)
        t0 = time.perf_counter()
        report = run_sweep(path, store, text=text)
        times["in-process"].append(time.perf_counter() - t0)
        chunk["in-process"] = (report.chunk_size, report.n_chunks)
        shutil.rmtree(store)
        if client is not None:
            store = work / f"there-{rep}.zarr"
            _forget_approaches(client)
            t0 = time.perf_counter()
            report = run_sweep(path, store, text=text, client=client)
            times["2 workers"].append(time.perf_counter() - t0)
            chunk["2 workers"] = (report.chunk_size, report.n_chunks)
            shutil.rmtree(store)
        print(f"repeat {rep + 1}: " + ", ".join(f"{k} {v[-1]:.2f} s" for k, v in times.items()
                                                 if v), flush=True)
    if cluster is not None:
        cluster.__exit__(None, None, None)
    shutil.rmtree(work, ignore_errors=True)

    print(f"\nKVLCC2 L7 35 deg turning, {args.runs} runs (Monte-Carlo samples), "
          f"{os.cpu_count()} cores, medians of {args.repeats}")
    med = {k: statistics.median(v) for k, v in times.items() if v}
    for name, t in med.items():
        extra = ""
        if name in chunk:
            extra = f"  ({chunk[name][1]} chunks of {chunk[name][0]})"
        print(f"  {name:12s} {t:8.2f} s  {args.runs / t:8.0f} runs/s{extra}")
    overhead = [s / m - 1 for s, m in zip(times["in-process"], times["monolithic"])]
    print(f"  chunking overhead (in-process sweep / monolithic - 1): "
          f"{100 * statistics.median(overhead):+.1f} % (per repeat: "
          f"{', '.join(f'{100 * o:+.1f} %' for o in overhead)})")
    # the engine runs on a thread per core in-process already: workers parallelise only the
    # rest (Amdahl), so on this machine they gain at most 1 / (e + (1 - e) / cores)
    share = statistics.median(e / m for e, m in zip(engine, times["monolithic"]))
    cores = os.cpu_count() or 1
    print(f"  engine share of the monolithic run: {100 * share:.0f} % (threaded in-process), "
          f"so local workers gain at most {1 / (share + (1 - share) / cores):.2f} x on "
          f"{cores} cores")
    if times["2 workers"]:
        ratio = [h / w for h, w in zip(times["in-process"], times["2 workers"])]
        print(f"  2 workers vs in-process: {statistics.median(ratio):.2f} x the runs/s")


if __name__ == "__main__":
    main()
