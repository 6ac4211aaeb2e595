"""How good is a ship estimated from its main particulars? KVLCC2 and Mariner against their tests.

``seahelm ship estimate`` builds a complete MMG model from L, B, T, C_b and the speed by
published regressions (Kijima et al. 1990, Yoshimura & Masumoto 2012, Motora's added masses,
Holtrop & Mennen, the Wageningen B-series, Fujii's rudder). This script estimates two ships whose
captive-test models seahelm has (the KVLCC2 of Yasukawa & Yoshimura 2015 and the Mariner of
Chislett & Strøm-Tejsen 1965), puts the estimated coefficients beside the measured ones, and runs
the 35° turning circle and the 10/10 and 20/20 zig-zags on both models; then the KVLCC2 in
shallow water (h/T = 2.0, 1.5, 1.2) and a figure of its turning circles.

    python examples/own_ship_validation.py [OUTDIR]

Prints the tables the docs quote (docs/guide/own-ship.rst) and writes
``OUTDIR/own_ship_validation.png`` (default: the working directory).
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np

from seahelm.analysis.maneuvers import turning_circle, zigzag
from seahelm.ships import get_ship
from seahelm.ships.estimate import Design, estimate_ship, nomoto_of

KNOT = 1852.0 / 3600.0

#: The KVLCC2's particulars (Yasukawa & Yoshimura 2015; lcb 3.48 % L, P/D 0.721 and
#: A_E/A_0 0.431 of the SIMMAN 2008 KVLCC2), full scale; the steering gear of the catalog ship.
KVLCC2 = Design(name="kvlcc2-estimated", length=320.0, beam=58.0, draft=20.8,
                block_coefficient=0.8098, displacement=312_600.0, x_G=11.2, speed=15.5 * KNOT,
                propeller_diameter=9.86, pitch_ratio=0.721, area_ratio=0.431, blades=4,
                rudder_area=112.5, rudder_span=15.8, max_rudder=math.radians(35.0),
                rudder_rate=math.radians(2.34), lcb=3.48)

#: The same at the scale of the L7 model the captive tests were made with (fresh water).
KVLCC2_L7 = Design(name="kvlcc2-l7-estimated", length=7.0, beam=1.27, draft=0.46,
                   block_coefficient=0.8098, displacement=3.27, x_G=0.25, speed=1.179,
                   propeller_diameter=0.216, pitch_ratio=0.721, area_ratio=0.431, blades=4,
                   rudder_area=0.0539, rudder_span=0.345, max_rudder=math.radians(35.0),
                   rudder_rate=math.radians(15.8), rho=1000.0, lcb=3.48)

#: The Mariner (Chislett & Strøm-Tejsen 1965 as in Fossen's mariner.m): L, B, T; C_b from the
#: model's mass m' = 798e-5; x_G = −0.023 L; rudder ±40°, 5°/s (the catalog ship's gear);
#: propeller and rudder sizes are not in the model: seahelm's defaults.
MARINER = Design(name="mariner-estimated", length=160.93, beam=23.17, draft=8.23,
                 block_coefficient=0.542, x_G=-0.023 * 160.93, speed=7.7175,
                 max_rudder=math.radians(40.0), rudder_rate=math.radians(5.0))

COMPARED = ("m_x", "m_y", "J_z", "R_0", "X_vv", "X_vr", "X_rr", "X_vvvv", "Y_v", "Y_r",
            "Y_vvv", "Y_vvr", "Y_vrr", "Y_rrr", "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr",
            "w_P0", "t_P", "k_0", "k_1", "k_2", "t_R", "a_H", "x_H", "epsilon", "kappa",
            "gamma_R_minus", "gamma_R_plus", "l_R", "f_alpha")


def mariner_in_mmg_terms() -> dict[str, float]:
    """The Mariner's PMM derivatives in the MMG convention (forces ÷ ½ρ L d U², the MMG
    equations' (m + m_x) u r and x_G m u r moved out of Y'_r and N'_r)."""
    p = get_ship("mariner-nonlinear").params
    f = 160.93 / 8.23  # prime system on L² -> on L·d
    return {"m_x": -p.X_udot * f, "m_y": -p.Y_vdot * f, "J_z": -p.N_rdot * f,
            "Y_v": p.Y_v * f, "Y_r": (p.Y_r + p.mass - p.X_udot) * f, "N_v": p.N_v * f,
            "N_r": (p.N_r + p.mass * p.x_G) * f, "Y_vvv": p.Y_vvv * f, "Y_vvr": p.Y_vvr * f,
            "N_vvv": p.N_vvv * f, "N_vvr": p.N_vvr * f}


def coefficient_table(title: str, estimated: object, measured: dict[str, float]) -> None:
    print(f"\n{title}\n{'coefficient':>14} {'estimated':>10} {'measured':>10} {'diff':>7}")
    for name in COMPARED:
        if name not in measured:
            continue
        e, m = getattr(estimated, name), measured[name]
        diff = f"{100 * (e - m) / abs(m):+.0f}%" if m else "-"
        print(f"{name:>14} {e:10.4f} {m:10.4f} {diff:>7}")


def manoeuvres(ship: object) -> dict[str, float]:
    """35° turning (starboard) and 10/10, 20/20 first overshoots (starboard first)."""
    turn = turning_circle(ship, math.radians(35.0), sides=1).metrics
    zz = zigzag(ship, np.radians([10.0, 20.0]), np.radians([10.0, 20.0]), sides=1).metrics
    length = ship.length
    return {"advance [L]": float(turn["advance"]) / length,
            "tactical diameter [L]": float(turn["tactical_diameter"]) / length,
            "speed loss [%]": 100 * (1 - float(turn["steady_speed"])
                                     / float(turn["approach_speed_value"])),
            "10/10 first overshoot [deg]": math.degrees(float(
                zz["overshoot"].isel(pair=0).sel(n=1))),
            "20/20 first overshoot [deg]": math.degrees(float(
                zz["overshoot"].isel(pair=1).sel(n=1)))}


def manoeuvre_table(title: str, estimated: object, reference: object) -> dict[str, tuple]:
    a, b = manoeuvres(estimated), manoeuvres(reference)
    print(f"\n{title}\n{'':>28} {'estimated':>10} {'captive':>10} {'diff':>7}")
    for key in a:
        print(f"{key:>28} {a[key]:10.3f} {b[key]:10.3f} {100 * (a[key] - b[key]) / b[key]:+6.0f}%")
    return {k: (a[k], b[k]) for k in a}


def shallow_table(ship: object, estimated: object) -> list[tuple[float, float, float]]:
    print("\nKVLCC2 full scale, 35° turning to starboard in shallow water "
          "(tactical diameter / advance [L])")
    print(f"{'h/T':>6} {'captive + corrections':>24} {'estimated':>18}")
    rows = []
    for ratio in (math.inf, 2.0, 1.5, 1.2):
        pair = []
        for s in (ship, estimated):
            s = s if math.isinf(ratio) else s.at_depth(ratio * 20.8)
            m = turning_circle(s, math.radians(35.0), sides=1).metrics
            pair.append((float(m["tactical_diameter"]) / 320.0, float(m["advance"]) / 320.0))
        rows.append((ratio, pair[0][0], pair[1][0]))
        label = "deep" if math.isinf(ratio) else f"{ratio:g}"
        print(f"{label:>6} {pair[0][0]:12.2f} / {pair[0][1]:4.2f} {pair[1][0]:11.2f} / "
              f"{pair[1][1]:4.2f}")
    return rows


def figure(ship: object, outdir: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 5.6), layout="constrained")
    for ratio in (math.inf, 2.0, 1.5, 1.2):
        s = ship if math.isinf(ratio) else ship.at_depth(ratio * 20.8)
        runs = turning_circle(s, math.radians(35.0), sides=1).runs
        label = "deep water" if math.isinf(ratio) else f"h/T = {ratio:g}"
        ax.plot(runs["east"] / 320.0, runs["north"] / 320.0, label=label)
    ax.set_xlabel("transfer y/L (east)")
    ax.set_ylabel("advance x/L (north)")
    ax.set_title("KVLCC2, 35° rudder to starboard: shallow water widens the turn")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.legend()
    path = outdir / "own_ship_validation.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def dominant_terms(estimated: object, reference: object, top: int = 8) -> None:
    """Which estimated coefficients move the turning circle most: each one alone set to its
    captive value (one batch of ships)."""
    names = [n for n in COMPARED if getattr(estimated.params, n) != getattr(reference.params, n)]
    ships = [estimated] + [estimated.replace(params={n: getattr(reference.params, n)}, name=n)
                           for n in names]
    m = turning_circle(ships, math.radians(35.0), sides=1, t_final=120.0).metrics
    length = estimated.length
    adv, td = m["advance"].values / length, m["tactical_diameter"].values / length
    print(f"\nKVLCC2 L7: the estimate's 35° turning ({adv[0]:.2f} L advance, {td[0]:.2f} L "
          "tactical diameter) with one coefficient at its captive value")
    print(f"{'coefficient':>14} {'advance':>9} {'tactical':>9}")
    order = sorted(range(len(names)), key=lambda i: -abs(td[i + 1] - td[0]))
    for i in order[:top]:
        print(f"{names[i]:>14} {adv[i + 1] - adv[0]:+9.2f} {td[i + 1] - td[0]:+9.2f}")


def main(outdir: Path) -> None:
    warnings.simplefilter("ignore")  # (every ship here is inside the regressions' data)
    l7 = get_ship("kvlcc2-l7")
    est_l7 = estimate_ship(KVLCC2_L7)
    coefficient_table("KVLCC2 L7 model scale: estimated vs captive (Yasukawa & Yoshimura 2015)",
                      est_l7.params, {n: getattr(l7.params, n) for n in COMPARED})
    manoeuvre_table("KVLCC2 L7 at 1.179 m/s: estimated model vs captive-test model", est_l7, l7)
    dominant_terms(est_l7, l7)
    kvlcc2 = get_ship("kvlcc2-full")
    est = estimate_ship(KVLCC2)
    print(f"\nKVLCC2 full scale: Holtrop's R'_0 {est.params.R_0:.4f} and w_P0 "
          f"{est.params.w_P0:.3f} (the captive set keeps the model's {kvlcc2.params.R_0:.3f}, "
          f"{kvlcc2.params.w_P0:.2f})")
    manoeuvre_table("KVLCC2 full scale at 15.5 kn: estimated model vs captive-test model",
                    est, kvlcc2)
    mariner = get_ship("mariner-nonlinear")
    est_m = estimate_ship(MARINER)
    coefficient_table("Mariner: estimated vs PMM (Chislett & Strøm-Tejsen 1965), MMG terms",
                      est_m.params, mariner_in_mmg_terms())
    manoeuvre_table("Mariner at 15 kn: estimated MMG model vs the PMM model", est_m, mariner)
    nomoto, _ = nomoto_of(MARINER)
    print(f"\nMariner Nomoto (Clarke et al. 1983 + estimated rudder): K {nomoto.gain:.4f} 1/s, "
          f"T1 {nomoto.t1:.1f} s, T2 {nomoto.t2:.2f} s, T3 {nomoto.t3:.2f} s "
          "(from the PMM model, Fossen 2021 Table 7.1: K 0.185, T1 118, T2 7.8, T3 18.5)")
    shallow_table(kvlcc2, est)
    print(f"\nwrote {figure(kvlcc2, outdir)}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
