"""Reinforcement-learning environments: env-steps per second of seahelm's gymnasium
environments against a single-ship environment built the usual way (TUD_RL's KVLCC2
environments: the MMG model in Python, one call per step, their Euler/trapezoid integrator).

Three environments of the same problem, side by side in one run: the KVLCC2 L7 model keeping
a heading, dt = 0.1 s, an action (rudder command) every 1 s, episodes of 120 s:

* **baseline**: a ``gymnasium.Env`` whose ``step`` integrates the MMG standard method
  (Yasukawa & Yoshimura 2015, eqs. (4)-(41), written out below from the paper's equations with
  the KVLCC2 L7 coefficients of seahelm's catalog) and a rate-limited rudder servo in Python,
  with TUD_RL's integrator: ten steps of 0.1 s per action, each one evaluation of the forces,
  the velocities (and the rudder) by explicit Euler, the positions and the heading by the
  trapezoid of the old and new velocities (the "ballistic" update of Treiber & Kanagaraj
  2015). TUD_RL (github.com/MarWaltz/TUD_RL, ``tud_rl/envs/_envs/MMG_KVLCC2.py``,
  ``KVLCC2._upd_dynamics``) steps its KVLCC2 that way, one step of ``delta_t`` per call
  (``MMG_Env``: ``delta_t = 3.0`` s, one call per env-step; the ``HHOS_*`` environments call
  it ``n_loops`` times per action); an earlier version of the same file integrated
  ``delta_t`` with ``scipy.integrate.solve_ivp(method="RK45")``. TUD_RL sets the rudder angle
  directly; the baseline keeps the rate-limited servo of seahelm's steering gear, so that
  the three environments simulate the same ship;
* seahelm's :class:`~seahelm.gym.ShipEnv` (one ship, the compiled loop, RK4);
* seahelm's :class:`~seahelm.gym.ShipVectorEnv` with 1,024 sub-environments (one compiled
  batch, the simulator's threads), with RK4 (seahelm's default) and with explicit Euler: the
  row of the ≥ 50 × target, the integrator of the baseline: in calm water no force reads the
  position or the heading, so the ballistic update's velocities are explicit Euler's, step
  for step; only the positions and the heading differ (seahelm's Euler advances them with the
  old velocities, the baseline with the mean of old and new) -- one evaluation of the forces
  per step either way.

Prints the median and quartiles of several repetitions (each repetition runs the rows one
after another: the baseline for ten episodes, then the vector env with Euler, ...) and of the
ratios of each repetition's rows (targets of issue 52: the vector env ≥ 50 × the baseline and
≥ 5 × seahelm's single env), so that a figure is not one lucky draw of a loaded machine.

    python benchmarks/bench_gym.py [--repeats 9] [--envs 1024] [--quick]

And an FMU of the same ship (``seahelm fmu``) run by fmpy: one ``doStep`` of 1 s against the
same interval through the Python stepping API (target of issue 52: ≤ 2 ×).

``--quick`` (the test suite's smoke run): 16 sub-environments, a few steps, one repeat.

The vector env runs the compiled loop (``nogil``) in slices on a pool of threads, one per
core: on an idle 2-core machine its wall rate is about 1.5 x its CPU rate (the slices overlap;
the rest of a step, observation, reward and restarts, is serial Python). On a shared machine
the other core is often someone else's and the wall rate falls to the CPU rate, so the run
prints the load it saw: the cores busy with other processes, from ``/proc/stat`` (Linux).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

import gymnasium
from gymnasium import spaces
from seahelm.gym import ShipEnv, ShipVectorEnv
from seahelm.ships import get_ship

DT, ACTION_PERIOD, EPISODE = 0.1, 1.0, 120.0


class PythonMMGHeadingEnv(gymnasium.Env):
    """The baseline: KVLCC2 heading keeping with the MMG model stepped in Python, the way
    TUD_RL's KVLCC2 environments are built (their integrator: explicit Euler velocities,
    trapezoidal positions; not their code)."""

    metadata = {"render_modes": []}

    def __init__(self) -> None:
        p = get_ship("kvlcc2-l7").params
        self.p = p
        self.L, self.d = p.length, p.draft
        self.m = p.rho * p.displacement
        half = 0.5 * p.rho * self.L ** 2 * self.d
        self.mx, self.my = p.m_x * half, p.m_y * half
        self.Jz = p.J_z * 0.5 * p.rho * self.L ** 4 * self.d
        self.IzG = self.m * (p.gyration_radius * self.L) ** 2
        self.n_prop = 11.85  # self-propulsion rps at 1.179 m/s (seahelm's approach_state)
        self.max_rudder, self.max_rate = math.radians(35.0), math.radians(15.8)
        self.action_space = spaces.Box(-self.max_rudder, self.max_rudder, (1,), np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, (5,), np.float32)

    def _forces(self, u: float, v: float, r: float, delta: float) -> tuple[float, float, float]:
        """Hull, propeller and rudder forces X, Y, N (Yasukawa & Yoshimura 2015)."""
        p, L, d = self.p, self.L, self.d
        U = math.sqrt(u * u + v * v)
        vp, rp = v / U, r * L / U  # v', r'
        q = 0.5 * p.rho * L * d * U * U
        # hull, eqs. (7)-(9)
        X_H = q * (-p.R_0 + p.X_vv * vp * vp + p.X_vr * vp * rp + p.X_rr * rp * rp
                   + p.X_vvvv * vp ** 4)
        Y_H = q * (p.Y_v * vp + p.Y_r * rp + p.Y_vvv * vp ** 3 + p.Y_vvr * vp * vp * rp
                   + p.Y_vrr * vp * rp * rp + p.Y_rrr * rp ** 3)
        N_H = q * L * (p.N_v * vp + p.N_r * rp + p.N_vvv * vp ** 3 + p.N_vvr * vp * vp * rp
                       + p.N_vrr * vp * rp * rp + p.N_rrr * rp ** 3)
        # propeller, eqs. (10)-(16): wake fraction with the drift at the propeller
        beta = math.atan2(-v, u)
        beta_P = beta - p.x_P * rp
        C2 = p.C_2_plus if beta_P > 0 else p.C_2_minus
        one_minus_wP = (1 - p.w_P0) * (1 + (1 - math.exp(-p.C_1 * abs(beta_P))) * (C2 - 1))
        n, D = self.n_prop, p.propeller_diameter
        J = u * one_minus_wP / (n * D)
        K_T = p.k_0 + p.k_1 * J + p.k_2 * J * J
        X_P = (1 - p.t_P) * p.rho * n * n * D ** 4 * K_T
        # rudder, eqs. (17)-(41)
        eta = D / p.rudder_span
        u_P = u * one_minus_wP
        root = math.sqrt(1 + 8 * K_T / (math.pi * J * J))
        u_R = p.epsilon * u_P * math.sqrt(eta * (1 + p.kappa * (root - 1)) ** 2 + 1 - eta)
        beta_R = beta - p.l_R * rp
        gamma = p.gamma_R_minus if beta_R < 0 else p.gamma_R_plus
        v_R = U * gamma * beta_R
        alpha_R = delta - math.atan2(v_R, u_R)
        F_N = 0.5 * p.rho * p.rudder_area * (u_R * u_R + v_R * v_R) * p.f_alpha \
            * math.sin(alpha_R)
        X_R = -(1 - p.t_R) * F_N * math.sin(delta)
        Y_R = -(1 + p.a_H) * F_N * math.cos(delta)
        N_R = -(p.x_R + p.a_H * p.x_H) * L * F_N * math.cos(delta)
        return X_H + X_P + X_R, Y_H + Y_R, N_H + N_R

    def _rhs(self, s: list[float], command: float) -> list[float]:
        """Eq. (4): the surge, sway and yaw equations at midship, solved for the
        accelerations; the kinematics; the rudder servo (rate-limited)."""
        u, v, r, x, y, psi, delta = s
        X, Y, N = self._forces(u, v, r, delta)
        m, xG = self.m, self.p.x_G
        a11, a22, a23 = m + self.mx, m + self.my, xG * m
        a33 = self.IzG + xG * xG * m + self.Jz
        udot = (X + (m + self.my) * v * r + xG * m * r * r) / a11
        b2 = Y - (m + self.mx) * u * r
        b3 = N - xG * m * u * r
        det = a22 * a33 - a23 * a23
        vdot = (b2 * a33 - a23 * b3) / det
        rdot = (a22 * b3 - a23 * b2) / det
        rate = max(-self.max_rate, min(self.max_rate, (command - delta) / 0.1))
        return [udot, vdot, rdot, u * math.cos(psi) - v * math.sin(psi),
                u * math.sin(psi) + v * math.cos(psi), r, rate]

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.target = float(self.np_random.uniform(-math.pi, math.pi))
        self.s = [1.179, 0.0, 0.0, 0.0, 0.0,
                  self.target + float(self.np_random.uniform(-0.35, 0.35)), 0.0]
        self.t = 0.0
        return self._obs(), {}

    def _obs(self) -> np.ndarray:
        u, v, r, _, _, psi, delta = self.s
        err = (psi - self.target + math.pi) % (2 * math.pi) - math.pi
        return np.array([err, r, u, v, delta], dtype=np.float32)

    def step(self, action):
        command = float(np.clip(action[0], -self.max_rudder, self.max_rudder))
        s = self.s
        h = 0.5 * DT
        for _ in range(round(ACTION_PERIOD / DT)):  # TUD_RL's "ballistic" step
            u, v, r, x, y, psi, delta = s
            du, dv, dr, dx, dy, _, ddelta = self._rhs(s, command)
            u1, v1, r1 = u + DT * du, v + DT * dv, r + DT * dr  # velocities: explicit Euler
            c, sn = math.cos(psi), math.sin(psi)  # positions: the old and new velocities'
            s = [u1, v1, r1, x + h * (dx + u1 * c - v1 * sn),  # mean (rotated by the old
                 y + h * (dy + u1 * sn + v1 * c), psi + h * (r + r1),  # heading, as TUD_RL)
                 delta + DT * ddelta]
        self.s, self.t = s, self.t + ACTION_PERIOD
        obs = self._obs()
        reward = math.exp(-(obs[0] / math.radians(10.0)) ** 2) - 0.1 * (s[2] * self.L / 1.179) ** 2
        truncated = self.t >= EPISODE - 1e-9
        return obs, reward, False, truncated, {}


def _single(env: gymnasium.Env, steps: int) -> tuple[float, float]:
    """Env-steps per second of wall time and of this process's CPU time."""
    rng = np.random.default_rng(0)
    actions = rng.uniform(-0.3, 0.3, (steps, 1)).astype(np.float32)
    env.reset(seed=0)
    t0, c0 = time.perf_counter(), time.process_time()
    for k in range(steps):
        _, _, terminated, truncated, _ = env.step(actions[k])
        if terminated or truncated:
            env.reset()
    return steps / (time.perf_counter() - t0), steps / (time.process_time() - c0)


def _busy_jiffies() -> tuple[int, int] | None:
    """Machine-wide busy and total CPU jiffies (``/proc/stat``), or None off Linux."""
    try:
        with open("/proc/stat") as f:
            v = [int(x) for x in f.readline().split()[1:]]
    except (OSError, ValueError):
        return None
    return sum(v) - v[3] - (v[4] if len(v) > 4 else 0), sum(v)


def _vector(envs: ShipVectorEnv, steps: int) -> tuple[float, float]:
    """Env-steps per second of wall time and of this process's CPU time (every thread's)."""
    rng = np.random.default_rng(0)
    actions = rng.uniform(-0.3, 0.3, (steps, envs.num_envs, 1)).astype(np.float32)
    envs.reset(seed=0)
    envs.step(actions[0])  # (the thread pool up)
    t0, c0 = time.perf_counter(), time.process_time()
    for k in range(steps):
        envs.step(actions[k])  # autoreset at the episodes' ends, by gymnasium's rule
    n = steps * envs.num_envs
    return n / (time.perf_counter() - t0), n / (time.process_time() - c0)


def _fmu_step_cost(steps: int) -> tuple[float, float, float]:
    """Seconds per 1 s interval (medians of interleaved chunks): an FMU doStep through fmpy
    (set the two inputs, doStep, get the eight outputs: a master's round), the bare doStep,
    and the same interval through the Python stepping API (:meth:`seahelm.Simulator.step` of
    one 1 s controller interval)."""
    import tempfile
    from pathlib import Path

    import fmpy
    import fmpy.fmi2

    from seahelm import Problem, Simulator
    from seahelm.analysis.equilibria.equilibrium import approach_state
    from seahelm.fmu import build_fmu

    ship = get_ship("kvlcc2-l7")
    start = approach_state(ship, trim=True)
    with tempfile.TemporaryDirectory() as tmp:
        path = build_fmu(ship, Path(tmp) / "kv.fmu")
        md = fmpy.read_model_description(str(path))
        vr = {v.name: v.valueReference for v in md.modelVariables}
        fmu = fmpy.fmi2.FMU2Slave(guid=md.guid, unzipDirectory=fmpy.extract(str(path)),
                                  modelIdentifier=md.coSimulation.modelIdentifier,
                                  instanceName="bench")
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0, stopTime=float(3 * steps + 10))
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        inputs = [vr["rudder_command"], vr["propeller_rps"]]
        outputs = [vr[n] for n in ("north", "east", "heading", "surge_speed", "sway_speed",
                                   "speed", "yaw_rate", "rudder_angle")]
        n0 = start.inputs["propeller_rps"]
        problem = Problem(ship=ship, x0=start.state,
                          actuator_x0=[start.inputs["rudder_angle"]],
                          t_final=float(3 * steps + 10), dt=DT, controller_dt=1.0,
                          record_every=int(round((3 * steps + 10) / DT)))
        sim = Simulator(problem)
        sim.reset()
        cmd = np.array([0.0, n0])
        sim.step(cmd)
        fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1.0)
        t = 1.0
        chunk = max(1, steps // 10)
        rows: list[tuple[float, float, float]] = []
        for _ in range(steps // chunk):  # (chunks interleaved: the load falls on all alike)
            t0 = time.perf_counter()
            for k in range(chunk):
                fmu.setReal(inputs, [0.1 * math.sin(0.1 * k), n0])
                fmu.doStep(currentCommunicationPoint=t, communicationStepSize=1.0)
                fmu.getReal(outputs)
                t += 1.0
            t1 = time.perf_counter()
            for k in range(chunk):
                fmu.doStep(currentCommunicationPoint=t, communicationStepSize=1.0)
                t += 1.0
            t2 = time.perf_counter()
            for k in range(chunk):
                cmd[0] = 0.1 * math.sin(0.1 * k)
                sim.step(cmd).values[0]
            t3 = time.perf_counter()
            rows.append(((t1 - t0) / chunk, (t2 - t1) / chunk, (t3 - t2) / chunk))
        sim.close()
        fmu.terminate()
        fmu.freeInstance()
    round_trip, bare, stepping = (statistics.median(r[i] for r in rows) for i in range(3))
    return round_trip, bare, stepping


def _quartiles(values: list[float]) -> tuple[float, float, float]:
    """Lower quartile, median and upper quartile (linear interpolation; one value: itself)."""
    q1, q2, q3 = np.percentile(np.asarray(values, dtype=float), [25, 50, 75])
    return float(q1), float(q2), float(q3)


def _spread(values: list[float], fmt: str) -> str:
    """``median [q1, q3]`` of ``values`` in ``fmt``."""
    q1, q2, q3 = _quartiles(values)
    return f"{q2:{fmt}} [{q1:{fmt}}, {q3:{fmt}}]"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=9)
    parser.add_argument("--envs", type=int, default=1024)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    n_envs = 16 if args.quick else args.envs
    repeats = 1 if args.quick else args.repeats
    single_steps = 50 if args.quick else 600
    # the baseline's run of a repeat: ten episodes (about 50 ms); a run of a few ms (150
    # steps, as before) measured the scheduler as much as the loop (idle, 19-30 k between runs)
    baseline_steps = 50 if args.quick else 1200
    vector_steps = 10 if args.quick else 130  # past an episode's end: one autoreset of all
    baseline = PythonMMGHeadingEnv()
    env = ShipEnv(task="HeadingKeeping", ship="kvlcc2-l7", dt=DT, action_period=ACTION_PERIOD,
                  episode_seconds=EPISODE)
    envs = ShipVectorEnv(n_envs, task="HeadingKeeping", ship="kvlcc2-l7", dt=DT,
                         action_period=ACTION_PERIOD, episode_seconds=EPISODE)
    euler = ShipVectorEnv(n_envs, task="HeadingKeeping", ship="kvlcc2-l7", dt=DT,
                          action_period=ACTION_PERIOD, episode_seconds=EPISODE,
                          integrator="euler")
    _single(env, 5)  # (warm)
    _single(baseline, 50)
    # interleaved, so that the machine's load falls on every row alike; the ratios of each
    # repeat are of rows measured back to back (a slow drift of the load cancels in them)
    rows: dict[str, list[tuple[float, float]]] = {k: [] for k in
                                                  ("baseline", "single", "vector", "euler")}
    j0, c0, t0 = _busy_jiffies(), time.process_time(), time.perf_counter()
    for _ in range(repeats):
        rows["baseline"].append(_single(baseline, baseline_steps))
        rows["euler"].append(_vector(euler, vector_steps))
        rows["single"].append(_single(env, single_steps))
        rows["vector"].append(_vector(envs, vector_steps))
    j1, c1, t1 = _busy_jiffies(), time.process_time(), time.perf_counter()
    print(f"KVLCC2 L7 heading keeping, dt {DT} s, an action every {ACTION_PERIOD} s "
          f"(median [quartiles] of {repeats} repeats, interleaved; per second of wall time, "
          f"and of the process's CPU time: every thread's, the fair measure on a loaded "
          f"machine)")
    print(f"{'environment':44s} {'env-steps/s (wall)':>27s} {'per CPU-s':>27s}")
    names = {"baseline": "Python MMG, TUD_RL's Euler (baseline)",
             "single": "seahelm ShipEnv (one ship)",
             "vector": f"seahelm ShipVectorEnv ({n_envs}, RK4)",
             "euler": f"seahelm ShipVectorEnv ({n_envs}, Euler)"}
    for key, name in names.items():
        print(f"{name:44s} {_spread([w for w, _ in rows[key]], ',.0f'):>27s} "
              f"{_spread([c for _, c in rows[key]], ',.0f'):>27s}")
    if j0 is not None and j1 is not None and j1[1] > j0[1]:
        cores = os.cpu_count() or 1
        busy = cores * (j1[0] - j0[0]) / (j1[1] - j0[1])  # cores busy, machine-wide
        own = (c1 - c0) / (t1 - t0)  # this process's cores
        print(f"load: {max(0.0, busy - own):.2f} of {cores} cores busy elsewhere during the "
              f"rows (this process {own:.2f})")
    for what, i in (("wall", 0), ("CPU", 1)):
        def ratio(a: str, b: str) -> str:
            return _spread([x[i] / y[i] for x, y in zip(rows[a], rows[b])], ".1f")
        print(f"{what}: vector / baseline (each repeat's pair) {ratio('euler', 'baseline')} x "
              f"Euler (target >= 50 x), {ratio('vector', 'baseline')} x RK4; vector / single "
              f"env {ratio('vector', 'single')} x (target >= 5 x); single env / baseline "
              f"{ratio('single', 'baseline')} x")
    for e in (env, envs, euler):
        e.close()
    round_trip, bare, stepping = _fmu_step_cost(20 if args.quick else 2000)
    print(f"FMU (seahelm fmu kvlcc2-l7, run by fmpy), one 1 s interval (dt {DT} s): "
          f"set inputs + doStep + get outputs {round_trip * 1e6:.0f} us, doStep alone "
          f"{bare * 1e6:.0f} us; Simulator.step of 1 s {stepping * 1e6:.0f} us; "
          f"doStep / stepping: {bare / stepping:.2f} x (target <= 2 x), with the master's "
          f"gets and sets {round_trip / stepping:.2f} x")


if __name__ == "__main__":
    main()
