"""First-order (wave-frequency) motions superposed on a recorded manoeuvre.

The two-time-scale model (Fossen 2011, *Handbook of Marine Craft Hydrodynamics and Motion
Control*, §10.4; Perez 2005, *Ship Motion Control*, ch. 4): the manoeuvring model gives the
low-frequency motion, and the linear wave-frequency motions are added to it,

    η_j(t) = Σ_i a_i |H_j(ω_i, ε_i(t))| cos(θ_i(t) + arg H_j(ω_i, ε_i(t))),
    θ_i(t) = ω_i t − k_i (x(t) cos β_i + y(t) sin β_i) + ϕ_i,      ε_i(t) = β_i − ψ(t),

j = heave, roll, pitch (and yaw, surge, sway where the RAO has them), H_j the RAO
(:class:`~seahelm.environment.rao.RAO`), component i of frequency ω_i, deep-water wave
number k_i = ω_i²/g, direction of travel β_i (clockwise from north) and random phase ϕ_i.

**The phase.** θ_i is the phase of component i at the ship's position (x north, y east): the
exact form, whose rate is the encounter frequency of the current ground velocity,
dθ_i/dt = ω_i − k_i V·(cos β_i, sin β_i) — with the ground velocity along the heading,
ω_i − ω_i² u cos ε_i/g (:func:`~seahelm.environment.encounter.encounter_frequency`), so
θ_i = ∫ ω_e,i dt is time-varying during a manoeuvre without being integrated numerically.
A record without x, y uses the dead-reckoned track x = ∫ u cos ψ dt, y = ∫ u sin ψ dt
(trapezoid rule on the record's time grid: surge along the heading, drift ignored; the phase
error is k_i times the track's trapezoid error, ≤ k u r² T Δt²/12 at a constant yaw rate r).
The waves are those a fixed observer sees (no wave–current interaction).

**The amplitudes.** The n components of each run are drawn from the run's own seed:
frequencies uniform at random within n equal bins of the band [ω_lo, ω_hi] (as
:func:`~seahelm.environment.wind_gust.gust_realisation` draws gust harmonics, so no record
repeats), a_i = √(2 S(ω_i) Δω) with the one-sided spectrum S, phases uniform in [0, 2π), and
with directional spreading (:mod:`.spreading`) one direction per component drawn from D
(single summation), so that for every run and time
E[η_j²] = ∫_{ω_lo}^{ω_hi} ∫ |H_j(ω, β − ψ)|² S(ω) D(β − β̄) dβ dω (long-crested: D = δ).

**Speed.** An RAO holds at one speed. With one RAO, its H_j are used at every speed of the
record (the encounter phase still follows the actual track); with several RAOs at
increasing speeds (e.g. :func:`~seahelm.environment.rao.closed_form_rao` at 0, 4, 8 m/s:
the closed form is cheap), H_j is interpolated linearly in the recorded speed u(t) and held
beyond the ends. H_j is interpolated linearly in ω (:meth:`RAO.__call__`, once per component)
and in heading on a uniform grid of the RAOs' smallest heading step (the same values as
:meth:`RAO.__call__` when the table's headings are uniform).

**What this pass is not.** It runs after the simulation, on the recorded motion: an
autopilot in the loop does not see its first-order yaw. For that, the same components and the
same per-sample code are evaluated inside the closed loop at the live state
(:mod:`seahelm.environment.first_order_in_loop`, ``Problem(first_order=...)``, with
``autopilot_sees_first_order=True``); for a wave-frequency heading disturbance without an RAO
use the shaping filter :data:`~seahelm.environment.wave_yaw.WAVE_YAW`. Parametric roll is
outside any linear RAO.

References
----------
Fossen, T. I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control, §8.2, §10.4.
Faltinsen, O. M. (1990). Sea Loads on Ships and Offshore Structures, ch. 2 (random phases,
a_i = √(2SΔω)).
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import math
import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._validate import as_float_array, check_positive
from ..constants import GRAVITY
from ..errors import ParameterError
from .first_order_kernel import first_order_run
from .rao import DOF_UNITS, RAO
from .directional_spreading import spreading_with_parameter

__all__ = ["WaveComponents", "FirstOrderMotions", "draw_wave_components",
           "first_order_motions", "expected_variance", "OUTPUT_NAMES"]

#: Most components per run (10^11 raised a MemoryError; the pass costs samples × components).
MAX_COMPONENTS = 100_000

#: Dataset names of the first-order parts (heave and pitch are all there is of them).
OUTPUT_NAMES: dict[str, str] = {"heave": "heave", "pitch": "pitch", "roll": "roll_wave",
                                "yaw": "yaw_wave", "surge": "surge_wave", "sway": "sway_wave"}


@dataclasses.dataclass(frozen=True, eq=False)
class WaveComponents:
    """The seeded wave components of each run (module docstring).

    Attributes
    ----------
    frequency, wavenumber, direction, amplitude, phase : numpy.ndarray, shape (runs, n)
        ω_i [rad/s], k_i [rad/m], direction of travel β_i (clockwise from north) [rad],
        a_i [m] and ϕ_i [rad].
    band : tuple of float
        (ω_lo, ω_hi) [rad/s].
    seeds : list
        The SeedSequence of each run.
    """

    frequency: np.ndarray
    wavenumber: np.ndarray
    direction: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    band: tuple[float, float]
    seeds: list[Any]


def _run_seeds(seed: Any, runs: int) -> list[Any]:
    """Run i's stream: child i of SeedSequence(seed) (or seed[i] of a sequence)."""
    if isinstance(seed, (list, tuple)):
        if len(seed) != runs:
            raise ParameterError(f"must hold one seed per run ({runs}), got {len(seed)}",
                                 field="seed")
        return [s if isinstance(s, np.random.SeedSequence) else np.random.SeedSequence(s)
                for s in seed]
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    return ss.spawn(runs)


def draw_wave_components(spectrum: Any, wave_direction: float, *, runs: int = 1,
                         seed: Any = 0, n_components: int = 64,
                         band: tuple[float, float] = (0.2, 2.0),
                         spreading: str | None = None, spreading_parameter: float = 2.0,
                         gravity: float = GRAVITY) -> WaveComponents:
    """Seeded random-phase components of an irregular sea, one set per run.

    Parameters
    ----------
    spectrum : WaveSpectrum
        One-sided sea spectrum (:mod:`seahelm.environment.spectra`).
    wave_direction : float
        Mean direction the waves come **from**, clockwise from north [rad] (as the scenario's
        ``direction_deg``); they travel towards ``wave_direction + π``.
    runs : int, optional
        Number of runs.
    seed : int, SeedSequence or a sequence of one per run, optional
        Run i draws from child i of ``SeedSequence(seed)``; a sequence gives run i ``seed[i]``
        (so run i of a batch equals a run drawn alone with ``seed=[children[i]]``).
    n_components : int, optional
        Components per run (default 64).
    band : (float, float), optional
        (ω_lo, ω_hi) [rad/s] the components cover (default 0.2–2.0 rad/s).
    spreading : {"cos-2s", "cos-n"} or None, optional
        Directional spreading (None: long-crested).
    spreading_parameter : float, optional
        s of cos-2s or n of cos-n [-] (default 2: cos² with ``"cos-n"``).
    gravity : float, optional
        g [m/s²].

    Returns
    -------
    WaveComponents
    """
    if isinstance(n_components, bool) or not isinstance(n_components, (int, np.integer)) \
            or not 1 <= n_components <= MAX_COMPONENTS:
        raise ParameterError(f"must be an integer in [1, {MAX_COMPONENTS}] [-], got "
                             f"{n_components!r}", field="n_components", unit="-",
                             value=n_components)
    if isinstance(runs, bool) or int(runs) != runs or runs < 1:
        raise ParameterError(f"must be an integer >= 1, got {runs!r}", field="runs", value=runs)
    lo, hi = (float(v) for v in as_float_array("band", band, "rad/s"))
    if not 0.0 < lo < hi:
        raise ParameterError(f"must be 0 < low < high [rad/s], got {band!r}", field="band",
                             unit="rad/s", value=band)
    direction = float(as_float_array("wave_direction", wave_direction, "rad"))
    spread = (None if spreading is None
              else spreading_with_parameter(spreading, spreading_parameter))
    n, R = int(n_components), int(runs)
    edges = np.linspace(lo, hi, n + 1)
    width = np.diff(edges)
    shape = (R, n)
    w, ph, dirs = np.empty(shape), np.empty(shape), np.full(shape, direction + math.pi)
    seeds = _run_seeds(seed, R)
    for r, ss in enumerate(seeds):
        rng = np.random.default_rng(ss)
        w[r] = edges[:-1] + rng.random(n) * width
        ph[r] = rng.uniform(0.0, 2.0 * math.pi, n)
        if spread is not None:
            dirs[r] += spread.draw(rng.random(n))
    amp = np.sqrt(2.0 * np.asarray(spectrum.one_sided(w), float) * width)
    return WaveComponents(w, w * w / gravity, np.mod(dirs, 2.0 * math.pi), amp, ph, (lo, hi),
                          seeds)


#: What a record's signals may be called: seahelm's channel names, then the short names.
_ALIASES: dict[str, tuple[tuple[str, ...], str]] = {
    "u": (("surge_speed", "u"), "m/s"), "psi": (("heading", "psi"), "rad"),
    "x": (("north", "x"), "m"), "y": (("east", "y"), "m"), "roll": (("roll_angle",), "rad")}


def _record(motion: Any) -> dict[str, np.ndarray]:
    """time, u, psi (and x, y, the model's roll) from a SimResult, a Dataset or a mapping."""
    out: dict[str, np.ndarray] = {}
    time = getattr(motion, "time", None)
    if time is None or callable(time):
        try:
            time = motion["time"]
        except (KeyError, TypeError):
            raise ParameterError("the record has no `time` [s]", field="motion.time",
                                 unit="s") from None
    out["time"] = as_float_array("motion.time", np.asarray(time), "s")
    for key, (names, unit) in _ALIASES.items():
        for name in names:
            try:
                out[key] = np.asarray(motion[name], dtype=float)
                break
            except (KeyError, ValueError):
                continue
        else:
            if key in ("u", "psi"):
                raise ParameterError(f"the record has no `{names[-1]}` [{unit}] (or "
                                     f"`{names[0]}`): the first-order motions need the speed "
                                     "and the heading", field=f"motion.{names[-1]}",
                                     unit=unit) from None
    if ("x" in out) != ("y" in out):
        raise ParameterError("needs both x and y [m] (or neither: dead reckoning)",
                             field="motion.x")
    return out


def _check_record(rec: dict[str, np.ndarray]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    t = rec["time"]
    if t.ndim != 1 or t.size < 2 or not np.all(np.diff(t) > 0):
        raise ParameterError("must be 1-D and strictly increasing, 2 or more samples [s]",
                             field="motion.time", unit="s")
    shape = None
    series = {}
    for key, unit in (("u", "m/s"), ("psi", "rad"), ("x", "m"), ("y", "m"), ("roll", "rad")):
        if key not in rec:
            continue
        v = rec[key].reshape(-1, rec[key].shape[-1]) if rec[key].ndim else rec[key]
        if v.ndim == 1:
            v = v[None, :]
        if v.shape[-1] != t.size or (shape is not None and v.shape != shape):
            raise ParameterError(f"has shape {rec[key].shape}; it must be (runs, time) with "
                                 f"{t.size} samples, like the other signals"
                                 + (f" {shape}" if shape else ""), field=f"motion.{key}",
                                 unit=unit)
        shape = v.shape
        bad = ~np.isfinite(v)
        if bad.any():
            r, k = (int(i[0]) for i in np.nonzero(bad))
            raise ParameterError(f"is not finite [{unit}] (run {r}, t = {t[k]:g} s): a "
                                 "diverged run has no wave motions", field=f"motion.{key}",
                                 unit=unit, run=r)
        series[key] = np.ascontiguousarray(v)
    return t, series


def _dead_reckoning(t: np.ndarray, u: np.ndarray, psi: np.ndarray) -> tuple[np.ndarray, ...]:
    dt = np.diff(t)
    vx, vy = u * np.cos(psi), u * np.sin(psi)
    x = np.zeros_like(u)
    y = np.zeros_like(u)
    x[:, 1:] = np.cumsum(0.5 * dt * (vx[:, 1:] + vx[:, :-1]), axis=1)
    y[:, 1:] = np.cumsum(0.5 * dt * (vy[:, 1:] + vy[:, :-1]), axis=1)
    return x, y


def _raos(rao: RAO | Sequence[RAO], dofs: Sequence[str] | None) -> tuple[list[RAO], tuple]:
    try:
        raos = [rao] if isinstance(rao, RAO) else [] if isinstance(rao, str) else list(rao)
    except TypeError:  # (None was a bare TypeError)
        raos = []
    if not raos or not all(isinstance(r, RAO) for r in raos):
        raise ParameterError("must be an RAO or a sequence of RAOs at increasing speeds, got "
                             f"{type(rao).__name__}", field="rao")
    speeds = np.array([r.speed for r in raos])
    if np.any(np.diff(speeds) <= 0):
        raise ParameterError(f"RAOs at several speeds must have increasing speeds [m/s], got "
                             f"{speeds.tolist()}", field="rao", unit="m/s")
    if dofs is None:
        dofs = tuple(d for d in ("heave", "roll", "pitch", "yaw") if d in raos[0].dofs)
    if isinstance(dofs, str) or not dofs:  # ('heave' was 'has no 'h''; () an IndexError)
        raise ParameterError(f"must be a non-empty sequence of degrees of freedom, got "
                             f"{dofs!r}", field="dofs", value=dofs)
    for r in raos:
        for d in dofs:
            if d not in r.dofs:
                raise ParameterError(f"has no {d!r} (it has {', '.join(r.dofs)}): the motions "
                                     f"asked for need it", field="rao", value=d)
    return raos, tuple(dofs)


def _heading_grid(raos: list[RAO]) -> tuple[np.ndarray, float]:
    steps = [np.min(np.diff(r.heading)) for r in raos if r.heading.size > 1]
    if not steps:
        raise ParameterError("has one wave heading only; the motions need a heading table",
                             field="rao")
    n = max(int(math.ceil(2.0 * math.pi / min(steps) - 1e-6)), 4)
    step = 2.0 * math.pi / n
    return np.arange(n + 1) * step, step


def _tables(raos: list[RAO], dofs: tuple, comp: WaveComponents, rows: slice, grid: np.ndarray,
            strict: bool | None) -> tuple[np.ndarray, np.ndarray]:
    """a_i H_j per run: (runs, n_speed, n_dof, n_head + 1, m), NaN where a table stops."""
    w = comp.frequency[rows]
    amp = comp.amplitude[rows]
    R, m = w.shape
    out = np.empty((R, len(raos), len(dofs), grid.size, m), dtype=complex)
    for s, rao in enumerate(raos):
        ok = np.ones(grid.size, bool)
        for l, e in enumerate(grid):
            try:
                rao(dofs[0], rao.frequency[0], e)
            except ParameterError:
                ok[l] = False
        for d, dof in enumerate(dofs):
            h = np.full((R, m, grid.size), np.nan, dtype=complex)
            h[..., ok] = rao(dof, w[..., None], grid[ok][None, None, :], strict=strict)
            out[:, s, d] = np.moveaxis(h * amp[..., None], 2, 1)
    return out.real.copy(), out.imag.copy()


def _coverage_error(rao: RAO, run: int, t: float) -> ParameterError:
    lo, hi = np.degrees(rao.heading[[0, -1]])
    return ParameterError(
        f"covers wave headings {lo:.4g} to {hi:.4g} deg (mirrored where it is a half table); "
        f"run {run} meets waves at relative headings outside it (first at t = {t:g} s)",
        field="rao.heading", unit="deg", run=run)


@dataclasses.dataclass(frozen=True, eq=False)
class FirstOrderMotions:
    """First-order motions of a batch of runs on the record's time grid.

    Attributes
    ----------
    time : numpy.ndarray, shape (n,)
        t [s].
    values : dict of str to numpy.ndarray, shape (runs, n)
        First-order response per degree of freedom [m or rad].
    heading : numpy.ndarray, shape (runs, n)
        The recorded (low-frequency) heading ψ [rad].
    components : WaveComponents
        What was summed.
    attrs : dict
        Metadata (conventions, band, speed handling).
    roll : numpy.ndarray or None
        The model's (low-frequency) roll angle [rad], shape (runs, n), where recorded.
    """

    time: np.ndarray
    values: dict[str, np.ndarray]
    heading: np.ndarray
    components: WaveComponents
    attrs: dict[str, Any]
    roll: np.ndarray | None = None

    def __getitem__(self, dof: str) -> np.ndarray:
        """The first-order response of ``dof`` [m or rad], shape (runs, n)."""
        return self.values[dof]

    @property
    def heading_total(self) -> np.ndarray | None:
        """ψ + ψ₁ [rad] (None without a yaw RAO)."""
        return self.heading + self.values["yaw"] if "yaw" in self.values else None

    def to_xarray(self, *, roll: Any = None, dims: tuple[str, ...] = ("run",),
                  shape: tuple[int, ...] | None = None) -> Any:
        """The motions as an :class:`xarray.Dataset` over (dims..., time), with units.

        Parameters
        ----------
        roll : array_like, optional
            The model's low-frequency roll angle [rad], shape (runs, n) (default the recorded
            one, :attr:`roll`): then ``roll`` is the total (model roll + ``roll_wave``);
            without either ``roll`` is ``roll_wave``.
        dims : tuple of str, optional
            The batch dimensions (default one ``run`` dimension).
        shape : tuple of int, optional
            Their sizes (default the number of runs).

        Returns
        -------
        xarray.Dataset
            ``heave`` [m], ``pitch`` [rad], ``roll_wave`` and ``roll`` [rad], ``yaw_wave`` and
            ``heading_total`` [rad] (those the RAO has).
        """
        import xarray as xr

        R = self.heading.shape[0]
        shape = (R,) if shape is None else tuple(shape)
        d = (*dims, "time")

        def arr(a: np.ndarray) -> np.ndarray:
            return np.asarray(a).reshape(*shape, self.time.size)

        data: dict[str, Any] = {}
        roll = self.roll if roll is None else roll
        for dof, v in self.values.items():
            unit = DOF_UNITS[dof].split("/")[0]
            data[OUTPUT_NAMES[dof]] = (d, arr(v), {"units": unit, "long_name":
                                                   f"first-order (wave-frequency) {dof}"})
        if "roll" in self.values:
            total = self.values["roll"] + (0.0 if roll is None else np.asarray(roll, float))
            data["roll"] = (d, arr(total), {"units": "rad", "long_name": "roll angle, "
                            + ("model roll + first-order roll" if roll is not None
                               else "first-order (the model has no roll)")})
        if self.heading_total is not None:
            data["heading_total"] = (d, arr(self.heading_total), {
                "units": "rad", "long_name": "heading psi + first-order yaw (after the run: the "
                "autopilot did not see it)"})
        attrs = {k: (v if isinstance(v, (int, float, str)) else str(v))
                 for k, v in self.attrs.items()}
        return xr.Dataset(data, coords={"time": ("time", self.time, {"units": "s"})},
                          attrs=attrs)


def first_order_motions(motion: Any, spectrum: Any, rao: RAO | Sequence[RAO], *,
                        wave_direction: float, seed: Any = 0, n_components: int = 64,
                        band: tuple[float, float] | None = None, spreading: str | None = None,
                        spreading_parameter: float = 2.0, dofs: Sequence[str] | None = None,
                        components: WaveComponents | None = None, threads: int | None = None,
                        gravity: float = GRAVITY, strict: bool | None = None
                        ) -> FirstOrderMotions:
    """Heave, roll, pitch (and yaw) in an irregular sea on a recorded manoeuvre.

    Parameters
    ----------
    motion : SimResult, xarray.Dataset or mapping
        The low-frequency record: ``time`` [s] (n,), the speed ``surge_speed`` (or ``u``)
        [m/s] and ``heading`` (or ``psi``) [rad], optionally ``north``, ``east`` (or ``x``,
        ``y``) [m] (without them the track is dead-reckoned) and ``roll_angle`` [rad], each
        (runs, n) or (n,) (or more batch axes before time).
    spectrum : WaveSpectrum
        One-sided sea spectrum.
    rao : RAO or sequence of RAO
        One RAO (used at every speed), or RAOs at increasing speeds (interpolated in u).
    wave_direction : float
        Mean direction the waves come from, clockwise from north [rad].
    seed : int, SeedSequence or sequence, optional
        Per-run seeds (:func:`draw_wave_components`).
    n_components : int, optional
        Wave components per run (default 64).
    band : (float, float), optional
        Frequency band [rad/s] (default: the RAOs' frequency table; a band beyond it warns as
        the RAO does).
    spreading : {"cos-2s", "cos-n"} or None, optional
        Directional spreading (:mod:`.spreading`); None: long-crested.
    spreading_parameter : float, optional
        s (cos-2s) or n (cos-n) [-].
    dofs : sequence of str, optional
        Degrees of freedom (default heave, roll, pitch and yaw, those the RAO has).
    components : WaveComponents, optional
        Components drawn beforehand (then ``seed``, ``n_components``, ``band`` and
        ``spreading`` are not used).
    threads : int, optional
        Worker threads over runs (default the CPU count).
    gravity : float, optional
        g [m/s²].
    strict : bool, optional
        Raise instead of warning when a component lies outside the RAO's frequencies.

    Returns
    -------
    FirstOrderMotions

    Raises
    ------
    ParameterError
        For a record with NaN, mismatched shapes or no u/psi, an RAO missing a degree of
        freedom or not covering the headings met, a seed count unlike the runs.
    """
    raos, dofs_t = _raos(rao, dofs)
    t, rec = _check_record(_record(motion))
    u, psi = rec["u"], rec["psi"]
    R = u.shape[0]
    if "x" in rec:
        x, y = rec["x"], rec["y"]
        track = "recorded x, y"
    else:
        x, y = _dead_reckoning(t, u, psi)
        track = "dead reckoning (trapezoid) of u along psi"
    if components is None:
        if band is None:
            band = (max(r.frequency[0] for r in raos), min(r.frequency[-1] for r in raos))
        components = draw_wave_components(spectrum, wave_direction, runs=R, seed=seed,
                                          n_components=n_components, band=band,
                                          spreading=spreading,
                                          spreading_parameter=spreading_parameter,
                                          gravity=gravity)
    if components.frequency.shape[0] != R:
        raise ParameterError(f"hold {components.frequency.shape[0]} runs, the record {R}",
                             field="components")
    grid, step = _heading_grid(raos)
    speeds = np.array([r.speed for r in raos])
    out = np.empty((R, t.size, len(dofs_t)))
    comp = components
    cb, sb = np.cos(comp.direction), np.sin(comp.direction)
    chunk = 16
    same = np.all(comp.direction == comp.direction[:, :1], axis=1)

    def work(start: int) -> None:
        rows = slice(start, min(start + chunk, R))
        tre, tim = _tables(raos, dofs_t, comp, rows, grid, strict)
        for j, r in enumerate(range(rows.start, rows.stop)):
            first_order_run(t, x[r], y[r], psi[r], u[r], comp.frequency[r],
                            comp.wavenumber[r], cb[r], sb[r], comp.direction[r], comp.phase[r],
                            tre[j], tim[j], step, speeds, same[r], out[r])

    starts = range(0, R, chunk)
    workers = min(len(starts), threads or os.cpu_count() or 1)
    if workers <= 1:
        for s in starts:
            work(s)
    else:
        with concurrent.futures.ThreadPoolExecutor(workers) as pool:
            list(pool.map(work, starts))
    bad = ~np.isfinite(out)
    if bad.any():
        r, k, _ = (int(i[0]) for i in np.nonzero(bad))
        raise _coverage_error(raos[0], r, float(t[k]))
    attrs = {"model": "first-order wave motions, two-time-scale superposition (Fossen 2011)",
             "track": track, "n_components": int(comp.frequency.shape[1]),
             "band": f"{comp.band[0]:g}-{comp.band[1]:g} rad/s",
             "speed_handling": ("one RAO at %g m/s used at every speed" % speeds[0]
                                if speeds.size == 1 else "RAOs at %s m/s interpolated in u"
                                % ", ".join(f"{s:g}" for s in speeds)),
             "spreading": "none (long-crested)" if spreading is None else
             f"{spreading} ({spreading_parameter:g})",
             "conventions": "heave up, roll starboard down, pitch bow up; wave direction "
                            "from, clockwise from north"}
    return FirstOrderMotions(t, {d: out[:, :, j] for j, d in enumerate(dofs_t)}, psi.copy(),
                             comp, attrs, rec.get("roll"))


def expected_variance(spectrum: Any, rao: RAO, dof: str, relative_heading: float, *,
                      band: tuple[float, float], spreading: str | None = None,
                      spreading_parameter: float = 2.0, points: int = 4001) -> float:
    """E[η_j²] = ∫∫ |H_j(ω, ε + θ)|² S(ω) D(θ) dθ dω over the band (module docstring).

    Parameters
    ----------
    spectrum : WaveSpectrum
        One-sided sea spectrum.
    rao : RAO
        The RAO.
    dof : str
        Degree of freedom.
    relative_heading : float
        Mean wave heading relative to the ship ε̄ = β̄ − ψ [rad] (0 following, π head).
    band : (float, float)
        (ω_lo, ω_hi) [rad/s].
    spreading : str or None, optional
        As in :func:`first_order_motions`.
    spreading_parameter : float, optional
        s or n [-].
    points : int, optional
        Simpson points in ω (and in θ).

    Returns
    -------
    float
        Variance [m² or rad²].
    """
    from scipy.integrate import simpson

    check_positive("points", points)
    w = np.linspace(band[0], band[1], int(points))
    s = np.asarray(spectrum.one_sided(w), float)
    if spreading is None:
        h2 = np.abs(rao(dof, w, relative_heading)) ** 2
        return float(simpson(h2 * s, x=w))
    spread = spreading_with_parameter(spreading, spreading_parameter)
    th = np.linspace(-spread.half_width, spread.half_width, int(points))
    dth = spread.density(th)
    h2 = np.abs(rao(dof, w[:, None], relative_heading + th[None, :])) ** 2
    return float(simpson(simpson(h2 * dth[None, :], x=th, axis=1) * s, x=w))
