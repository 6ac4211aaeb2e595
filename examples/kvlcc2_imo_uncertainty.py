"""KVLCC2 (L7) IMO compliance under uncertain hull coefficients: a Monte-Carlo sweep.

The linear manoeuvring derivatives Y'_v, Y'_r, N'_v and N'_r of the KVLCC2 L7 model are drawn
independently from normal distributions with a 10 % standard deviation (``--std``) around the
published values; for every sample the ship runs the IMO MSC.137(76) manoeuvres -- 35° turning
circles and 10° initial turning to both sides, 10°/10° and 20°/20° zig-zags to both sides -- as
two sweeps with the same seed (so sample i is the same ship in both). Printed: the distribution
of advance/L, tactical diameter/L, initial-turning distance/L and the zig-zag overshoots, and the
probability that a sample passes each criterion and all of them; written: the two Zarr stores,
``summary.json`` and ``kvlcc2_imo_uncertainty.png``.

    python examples/kvlcc2_imo_uncertainty.py                      # 10,000 samples, in-process
    python examples/kvlcc2_imo_uncertainty.py --workers 2          # a local dask cluster
    python examples/kvlcc2_imo_uncertainty.py --samples 200 --out /tmp/imo

Interrupted, the same command resumes both sweeps where they stopped. The probabilities alone
(stopping included) are one command: ``seahelm run examples/kvlcc2_imo_monte_carlo.toml`` or
``seahelm sweep`` of it.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from seahelm.analysis.imo.check import (
    ADVANCE_LIMIT,
    INITIAL_TURNING_LIMIT,
    TACTICAL_DIAMETER_LIMIT,
    ZIGZAG_20_FIRST_OVERSHOOT_LIMIT,
    imo_overshoot_limits,
)
from seahelm.sweep import open_sweep, run_sweep
from seahelm.ships import get_ship

DERIVATIVES = ("Y_v", "Y_r", "N_v", "N_r")


def scenarios(samples: int, seed: int, std: float) -> dict[str, str]:
    """The turning and zig-zag scenarios with the same draws (TOML text)."""
    params = get_ship("kvlcc2-l7").params
    draws = "\n".join(
        f'"vessel.params.{name}" = {{ distribution = "normal", mean = {getattr(params, name)!r},'
        f' std = {abs(std * getattr(params, name))!r} }}' for name in DERIVATIVES)
    mc = f"[batch.monte_carlo]\nruns = {samples}\nseed = {seed}\n[batch.monte_carlo.draws]\n{draws}\n"
    head = ('title = "KVLCC2 L7 IMO {what}, {pct:g} % std on the linear derivatives"\n'
            '[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\n')
    turning = head.format(what="turning", pct=100 * std) + (
        'kind = "turning"\nrudder_deg = [35.0, 10.0]\nsides = "both"\n') + mc
    zigzag = head.format(what="zig-zags", pct=100 * std) + (
        'kind = "zigzag"\nrudder_deg = [10.0, 20.0]\nheading_deg = [10.0, 20.0]\n'
        'sides = "both"\n') + mc
    return {"turning": turning, "zigzag": zigzag}


def criteria(turning, zigzag, length: float, speed: float) -> dict[str, tuple]:
    """Per criterion and side: (values per sample, limit, unit) -- as ``imo_check`` applies
    them (distances over L, angles in degrees)."""
    limits = imo_overshoot_limits(length / speed)
    out = {}
    for side, name in ((1, "stbd"), (-1, "port")):
        t35 = turning.isel(rudder=0).sel(side=side)
        t10 = turning.isel(rudder=1).sel(side=side)
        z10 = zigzag.isel(pair=0).sel(side=side)
        z20 = zigzag.isel(pair=1).sel(side=side)
        out[f"advance/L {name}"] = (t35["advance"].values / length, ADVANCE_LIMIT, "L")
        out[f"tactical diameter/L {name}"] = (t35["tactical_diameter"].values / length,
                                              TACTICAL_DIAMETER_LIMIT, "L")
        out[f"initial turning/L {name}"] = (t10["distance_10"].values / length,
                                            INITIAL_TURNING_LIMIT, "L")
        out[f"10/10 1st overshoot {name}"] = (np.degrees(z10["overshoot"].sel(n=1).values),
                                              math.degrees(limits.first), "deg")
        out[f"10/10 2nd overshoot {name}"] = (np.degrees(z10["overshoot"].sel(n=2).values),
                                              math.degrees(limits.second), "deg")
        out[f"20/20 1st overshoot {name}"] = (np.degrees(z20["overshoot"].sel(n=1).values),
                                              math.degrees(ZIGZAG_20_FIRST_OVERSHOOT_LIMIT),
                                              "deg")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--std", type=float, default=0.10, help="relative standard deviation")
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--scheduler", default=None)
    ap.add_argument("--chunk-size", type=int, default=None)
    ap.add_argument("--out", type=Path, default=Path("seahelm-out/kvlcc2-imo-uncertainty"))
    args = ap.parse_args()

    args.out.mkdir(parents=True, exist_ok=True)
    stores = {}
    for kind, text in scenarios(args.samples, args.seed, args.std).items():
        path = args.out / f"{kind}.toml"
        path.write_text(text)
        report = run_sweep(path, args.out / f"{kind}.zarr", workers=args.workers,
                           scheduler=args.scheduler, chunk_size=args.chunk_size)
        print(f"{kind}: {report.n_runs} samples in {report.n_chunks} chunk(s), "
              f"{report.computed} computed, {report.wall_time_s:.1f} s")
        stores[kind] = open_sweep(args.out / f"{kind}.zarr").load()
    params = get_ship("kvlcc2-l7").params
    table = criteria(stores["turning"], stores["zigzag"], params.length, params.approach_speed)

    print(f"\nKVLCC2 L7, {args.samples} samples, {100 * args.std:g} % std on "
          f"{', '.join(DERIVATIVES)} (seed {args.seed})")
    print(f"{'criterion':28s} {'mean':>8s} {'q05':>8s} {'q50':>8s} {'q95':>8s} {'limit':>7s}"
          f" {'P(pass)':>8s}")
    summary = {"samples": args.samples, "std": args.std, "seed": args.seed, "criteria": {}}
    passed_all = np.ones(args.samples, dtype=bool)
    for name, (values, limit, unit) in table.items():
        ok = np.isfinite(values) & (values <= limit)  # an event not reached fails
        passed_all &= ok
        q05, q50, q95 = np.nanquantile(values, [0.05, 0.5, 0.95])
        print(f"{name:28s} {np.nanmean(values):8.3f} {q05:8.3f} {q50:8.3f} {q95:8.3f} "
              f"{limit:7.2f} {ok.mean():8.3f}")
        summary["criteria"][name] = {"mean": float(np.nanmean(values)), "q05": float(q05),
                                     "q50": float(q50), "q95": float(q95), "limit": limit,
                                     "unit": unit, "p_pass": float(ok.mean())}
    summary["p_pass_all"] = float(passed_all.mean())
    print(f"{'all criteria':28s} {'':35s} {'':7s} {passed_all.mean():8.3f}")
    (args.out / "summary.json").write_text(json.dumps(summary, indent=2))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shown = ["advance/L stbd", "tactical diameter/L stbd", "10/10 1st overshoot stbd",
             "10/10 2nd overshoot stbd", "20/20 1st overshoot stbd"]
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), layout="constrained")
    for ax, name in zip(axes.flat, shown):
        values, limit, unit = table[name]
        ax.hist(values[np.isfinite(values)], bins=40, color="tab:blue", alpha=0.8)
        ax.axvline(limit, color="tab:red", lw=2, label=f"IMO limit {limit:g} {unit}")
        ax.set_xlabel(f"{name} [{unit}]")
        ax.set_ylabel("samples")
        ax.legend(loc="upper left", fontsize=8)
    ax = axes.flat[-1]
    names = list(table)
    ax.barh(names, [summary["criteria"][n]["p_pass"] for n in names], color="tab:green")
    ax.set_xlim(0, 1)
    ax.set_xlabel("probability of passing")
    ax.tick_params(axis="y", labelsize=7)
    fig.suptitle(f"KVLCC2 L7 under uncertain linear derivatives ({100 * args.std:g} % std, "
                 f"{args.samples} samples): P(all IMO criteria) = {passed_all.mean():.3f}")
    fig.savefig(args.out / "kvlcc2_imo_uncertainty.png", dpi=110)
    print(f"\nwrote {args.out / 'kvlcc2_imo_uncertainty.png'}, {args.out / 'summary.json'}")


if __name__ == "__main__":
    main()
