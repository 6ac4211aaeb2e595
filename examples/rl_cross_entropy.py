"""A linear heading-keeping autopilot for the KVLCC2 (L7 model) learnt by the cross-entropy
method on seahelm's vector environment, in wind and waves.

The policy is δ_c = δ_max · clip(θ · f, -1, 1) with the features
f = (ψ̃, r L/U_0, (u - U_0)/U_0, v/U_0, δ_c,previous/δ_max, 1) of the observation (heading
error, yaw rate, surge and sway speed, last rudder command). Each iteration draws a population of
θ from a Gaussian, runs every candidate for a few episodes at once (one sub-environment of the
:class:`seahelm.gym.ShipVectorEnv` per candidate and episode: one compiled batch), keeps the
best fifth and refits the Gaussian to them (Rubinstein & Kroese 2004, "The cross-entropy
method", ch. 4). Wind 3 m/s and waves h = 0.066 m (20 m/s and 3 m at full scale) from the
north-east; every episode draws its own target heading, so the weather comes from all sides.

Prints the mean return of each iteration and of the initial and final mean policy on held-out
episodes, and writes ``rl_cross_entropy.png`` (the learning curve) into the directory given.

    python examples/rl_cross_entropy.py [OUT_DIR] [--iterations N] [--population P]
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from seahelm.gym import ShipVectorEnv


def features(obs: np.ndarray, env: ShipVectorEnv) -> np.ndarray:
    """The policy's features (envs, 6) from the observations (envs, 5)."""
    p = env.plant
    heading_error, yaw_rate, surge, sway, rudder = obs.T.astype(float)
    return np.stack([heading_error, yaw_rate * p.length / p.speed, (surge - p.speed) / p.speed,
                     sway / p.speed, rudder / p.max_rudder, np.ones_like(heading_error)],
                    axis=1)


def returns(env: ShipVectorEnv, theta: np.ndarray, seed: int) -> np.ndarray:
    """Return of one episode per sub-environment; ``theta`` (envs, 6) one policy each."""
    obs, _ = env.reset(seed=seed)
    total = np.zeros(env.num_envs)
    going = np.ones(env.num_envs, dtype=bool)
    max_rudder = env.plant.max_rudder
    while going.any():
        action = max_rudder * np.clip((theta * features(obs, env)).sum(axis=1), -1.0, 1.0)
        obs, reward, terminated, truncated, _ = env.step(action[:, None])
        total += np.where(going, reward, 0.0)
        going &= ~(terminated | truncated)  # (the next step restarts it: not counted)
    return total


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", default=".", type=Path)
    parser.add_argument("--iterations", type=int, default=15)
    parser.add_argument("--population", type=int, default=48)
    parser.add_argument("--episodes", type=int, default=4, help="episodes per candidate")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    P, E = args.population, args.episodes
    weather = dict(wind_speed=3.0, wind_direction=math.radians(45.0), wave_height=0.066,
                   wave_length=2.6, wave_direction=math.radians(45.0))
    env = ShipVectorEnv(P * E, task="HeadingKeeping", ship="kvlcc2-l7", **weather)
    rng = np.random.default_rng(args.seed)
    mean, std = np.zeros(6), np.full(6, 1.0)
    n_elite = max(2, P // 5)
    held_out = 10_000  # seeds of the evaluation episodes, apart from the training ones

    def evaluate(theta: np.ndarray) -> float:
        return float(returns(env, np.repeat(theta[None], P * E, axis=0), held_out).mean())

    start = evaluate(mean)
    curve, t0 = [], time.perf_counter()
    print(f"{'iteration':>9s} {'mean return':>12s} {'elite':>8s} {'best':>8s}")
    for it in range(args.iterations):
        candidates = mean + std * rng.standard_normal((P, 6))
        r = returns(env, np.repeat(candidates, E, axis=0), seed=args.seed * 1000 + it)
        score = r.reshape(P, E).mean(axis=1)
        elite = candidates[np.argsort(score)[-n_elite:]]
        mean, std = elite.mean(axis=0), elite.std(axis=0) + 0.02
        curve.append((float(score.mean()), float(np.sort(score)[-n_elite:].mean()),
                      float(score.max())))
        print(f"{it:9d} {curve[-1][0]:12.2f} {curve[-1][1]:8.2f} {curve[-1][2]:8.2f}")
    end = evaluate(mean)
    steps = args.iterations * P * E * env.episode_seconds
    print(f"held-out episodes, mean return: initial policy {start:.2f}, learnt {end:.2f} "
          f"(of {env.episode_seconds:.0f} at most); θ = {np.round(mean, 3).tolist()}; "
          f"{time.perf_counter() - t0:.1f} s, ~{steps:.0f} env-steps")
    env.close()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = np.array(curve)
    fig, ax = plt.subplots(figsize=(6.4, 3.8), layout="constrained")
    it = np.arange(1, len(c) + 1)
    ax.plot(it, c[:, 0], "o-", label="population mean")
    ax.plot(it, c[:, 1], "s-", label="elite mean")
    ax.axhline(start, color="0.5", ls=":", label=f"rudder amidships ({start:.1f})")
    ax.axhline(end, color="C2", ls="--", label=f"learnt policy, held-out ({end:.1f})")
    ax.set_xlabel("cross-entropy iteration")
    ax.set_ylabel("episode return (120 s, max 120)")
    ax.set_title("KVLCC2 L7 heading keeping in wind and waves: a linear policy")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    args.out.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out / "rl_cross_entropy.png", dpi=110)


if __name__ == "__main__":
    main()
