"""A linear collision-avoidance policy for the KVLCC2 (L7 model) learnt by the cross-entropy
method on seahelm's encounter environment (``seahelm/CollisionAvoidance-v0``), the target seen
through AIS.

Each episode is an encounter of Monte-Carlo geometry: a target ship 12-20 own lengths away on a
collision course (CPA within ±1 L) that keeps its course; the agent's action is the own
ship's course change from its route [rad] (:class:`seahelm.gym.EncounterVectorEnv`). The target
is seen through AIS reports every 2 s, received 1 s later, with noise (0.2 m, 1°, 0.01 m/s).
The policy is Δχ = 45° · clip(θ · f, -1, 1) with the features f = (sin β, cos β, L/ρ, d_CPA/ρ,
t_CPA U_0/(20 L), ψ̃, e/L, 1) of the observation (β the target's relative bearing, ρ its range,
ψ̃ the heading error to the route, e the cross-track error). Each iteration draws a population of
θ from a Gaussian, runs every candidate for a few encounters at once (one sub-environment per
candidate and encounter: one batch), keeps the best fifth and refits the Gaussian to them
(Rubinstein & Kroese 2004, "The cross-entropy method", ch. 4).

Prints the mean return of each iteration and of the initial and final mean policy on held-out
encounters, with their collision counts, and writes ``rl_collision_cross_entropy.png`` (the
learning curve) into the directory given.

    python examples/rl_collision_cross_entropy.py [OUT_DIR] [--iterations N] [--population P]
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from seahelm.encounters import AIS
from seahelm.gym import EncounterVectorEnv

N_FEATURES = 8


def features(obs: np.ndarray, env: EncounterVectorEnv) -> np.ndarray:
    """The policy's features (envs, 8) from the observations (envs, 12)."""
    L, U = env.task.own_length, env.task.own_speed
    o = obs.astype(float)
    bearing, rng, dcpa, tcpa = o[:, 6], np.maximum(o[:, 7], L), o[:, 8], o[:, 9]
    return np.stack([np.sin(bearing), np.cos(bearing), L / rng, dcpa / rng,
                     np.clip(tcpa * U / (20.0 * L), -1.0, 1.0), o[:, 0], o[:, 1] / L,
                     np.ones_like(rng)], axis=1)


def returns(env: EncounterVectorEnv, theta: np.ndarray, seed: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """Return and collision (bool) of one encounter per sub-environment; ``theta`` (envs, 8)
    one policy each."""
    obs, _ = env.reset(seed=seed)
    total = np.zeros(env.num_envs)
    collided = np.zeros(env.num_envs, dtype=bool)
    going = np.ones(env.num_envs, dtype=bool)
    high = float(env.single_action_space.high[0])
    while going.any():
        action = high * np.clip((theta * features(obs, env)).sum(axis=1), -1.0, 1.0)
        obs, reward, terminated, truncated, _ = env.step(action[:, None])
        total += np.where(going, reward, 0.0)
        collided |= going & (reward <= -env.task.weights["collision"])
        going &= ~(terminated | truncated)  # (the next step restarts it: not counted)
    return total, collided


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", default=".", type=Path)
    parser.add_argument("--iterations", type=int, default=12)
    parser.add_argument("--population", type=int, default=40)
    parser.add_argument("--episodes", type=int, default=4, help="encounters per candidate")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    P, E = args.population, args.episodes
    sensor = AIS(update_interval=2.0, delay=1.0, position_noise=0.2,
                 course_noise=math.radians(1.0), heading_noise=math.radians(1.0),
                 speed_noise=0.01, seed=args.seed)
    env = EncounterVectorEnv(P * E, ship="kvlcc2-l7", sensor=sensor)
    rng = np.random.default_rng(args.seed)
    mean, std = np.zeros(N_FEATURES), np.full(N_FEATURES, 1.0)
    n_elite = max(2, P // 5)
    held_out = 10_000  # seeds of the evaluation encounters, apart from the training ones

    def evaluate(theta: np.ndarray) -> tuple[float, int]:
        r, hit = returns(env, np.repeat(theta[None], P * E, axis=0), held_out)
        return float(r.mean()), int(hit.sum())

    (start, start_hits) = evaluate(mean)
    curve, t0 = [], time.perf_counter()
    print(f"{'iteration':>9s} {'mean return':>12s} {'elite':>8s} {'best':>8s}")
    for it in range(args.iterations):
        candidates = mean + std * rng.standard_normal((P, N_FEATURES))
        r, _ = returns(env, np.repeat(candidates, E, axis=0), seed=args.seed * 1000 + it)
        score = r.reshape(P, E).mean(axis=1)
        elite = candidates[np.argsort(score)[-n_elite:]]
        mean, std = elite.mean(axis=0), elite.std(axis=0) + 0.02
        curve.append((float(score.mean()), float(np.sort(score)[-n_elite:].mean()),
                      float(score.max())))
        print(f"{it:9d} {curve[-1][0]:12.2f} {curve[-1][1]:8.2f} {curve[-1][2]:8.2f}")
    end, end_hits = evaluate(mean)
    print(f"held-out encounters ({P * E}), mean return: initial policy (on course) {start:.2f} "
          f"({start_hits} collisions), learnt {end:.2f} ({end_hits} collisions); "
          f"θ = {np.round(mean, 3).tolist()}; {time.perf_counter() - t0:.1f} s")
    env.close()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = np.array(curve)
    fig, ax = plt.subplots(figsize=(6.4, 3.8), layout="constrained")
    it = np.arange(1, len(c) + 1)
    ax.plot(it, c[:, 0], "o-", label="population mean")
    ax.plot(it, c[:, 1], "s-", label="elite mean")
    ax.axhline(start, color="0.5", ls=":",
               label=f"on course, held-out ({start:.1f}; {start_hits} collisions)")
    ax.axhline(end, color="C2", ls="--",
               label=f"learnt policy, held-out ({end:.1f}; {end_hits} collisions)")
    ax.set_xlabel("cross-entropy iteration")
    ax.set_ylabel("episode return")
    ax.set_title("KVLCC2 L7 collision avoidance, target through AIS: a linear policy")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    args.out.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out / "rl_collision_cross_entropy.png", dpi=110)


if __name__ == "__main__":
    main()
