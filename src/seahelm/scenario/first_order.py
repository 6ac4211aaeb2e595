"""``[environment.waves] first_order_motions = true``: wave-frequency motions in a run's result.

With an irregular sea (``irregular = true``), ``seahelm run`` adds to the result, on its run
and time axes, the first-order motions of the same sea
(:func:`seahelm.environment.first_order.first_order_motions`) superposed on the recorded
manoeuvre:

* ``heave`` [m] and ``pitch`` [rad] (the manoeuvring models have neither);
* ``roll_wave`` [rad], the first-order roll, and ``roll`` [rad]: the model's ``roll_angle`` +
  ``roll_wave`` on a model with roll (the 4-DOF ``container``), else ``roll_wave``.

The RAOs are the closed-form estimates of the ship's particulars
(:func:`~seahelm.environment.rao.closed_form_rao`: heave and pitch by Jensen et al. 2004,
roll with the section's ``metacentric_height`` GM [m], else the particulars' — a ship file's
``[particulars]`` or the catalog ship's; without either heave and pitch only),
evaluated per run: at its mid speed when its recorded surge speed spans less than 0.25 m/s,
else at the multiples of 0.25 m/s that bracket its speeds, interpolated linearly in the
speed. A run's motions depend on its own record only, not on the runs computed with it (a
sweep's chunks give the whole batch's values). The sea is the section's spectrum for its height
(as for the load envelope, Table 2's peak frequency), mean direction ``direction_deg`` (from),
``components`` per run (default 64), optional ``spreading``. Run i draws its components from
the second child of run i's sea stream (``SeedSequence(seed, spawn_key=(i, 1))``; the load
envelope draws from the first), with the batch seed as the load envelope has it.

``rao_file`` (relative to the scenario file; :func:`~seahelm.environment.rao_io.read_rao`: a
capytaine NetCDF such as the shipped box barge, seahelm's RAO NetCDF or an RAO table) replaces
the closed form (its one speed used at every speed).

By default the pass runs after the simulation: the autopilot does not see the first-order
yaw. ``autopilot_sees_first_order = true`` evaluates the motions inside the closed loop instead
(:func:`first_order_in_the_loop`, :mod:`seahelm.environment.first_order_in_loop`: the same
components, seeds and per-sample code) and feeds the autopilot's ``heading`` measurement ψ + ψ₁;
the result then also has ``yaw_wave`` and ``heading_total`` (what the autopilot saw), and
``roll`` only on a model with roll. It needs an RAO with yaw — a ``rao_file`` with a yaw degree
of freedom (the closed-form RAOs have none; refused, naming the key) — the same setting in
every run, one ``rao_file`` and one ``components`` for the batch.
"""

from __future__ import annotations

import dataclasses
import math
import types
from typing import Any

import numpy as np

from ..errors import ParameterError
from .errors import at_key as _err

__all__ = ["FirstOrderSettings", "first_order_settings", "FirstOrderPostPass",
           "first_order_in_the_loop"]


@dataclasses.dataclass(frozen=True)
class FirstOrderSettings:
    """One run's first-order motions, as its ``[environment.waves]`` section gives them
    (:func:`first_order_settings`): the post-pass's :attr:`FirstOrderPostPass.specs`, the
    in-loop motions' :attr:`~seahelm.environment.first_order_in_loop.FirstOrderInLoop.settings`.

    Hashable (runs of equal settings are computed together); :meth:`as_dict` is its form in a
    result's metadata (``first_order_settings``, JSON).

    Attributes
    ----------
    h3 : float
        The sea's h3% wave height [m].
    spectrum : str
        The spectrum's name.
    seed : int
        The sea's seed.
    rao_file : str or None
        The RAO file (absolute path), or None for the closed-form RAOs.
    autopilot_sees : bool
        The motions are evaluated in the loop and the autopilot sees ψ + ψ₁.
    direction : float
        Mean wave direction (from) [rad].
    gm : float or None
        Metacentric height GM [m] of the closed-form roll RAO (None: no roll).
    components : int
        Wave components per run.
    spreading : str or None
        Directional spreading function (None: long-crested).
    spreading_parameter : float
        Its parameter [-].
    hull : tuple of float
        Length, beam, draft [m] and block coefficient [-] of the closed-form RAOs.
    """

    h3: float
    spectrum: str
    seed: int
    rao_file: str | None
    autopilot_sees: bool
    direction: float
    gm: float | None
    components: int
    spreading: str | None
    spreading_parameter: float
    hull: tuple[float, float, float, float]

    def as_dict(self) -> dict[str, Any]:
        """The settings as plain values (the hull as a list), in the fields' order.

        Returns
        -------
        dict
        """
        out = dataclasses.asdict(self)
        out["hull"] = list(self.hull)
        return out

    def sea(self) -> "FirstOrderSettings":
        """The settings but the direction and the seed (the sea a frequency-domain cell
        needs)."""
        return dataclasses.replace(self, direction=0.0, seed=0)


def first_order_settings(v: dict[str, Any], h3: float, ship: Any, source: str
                         ) -> FirstOrderSettings:
    """One run's settings (:class:`FirstOrderSettings`), checked.

    Parameters
    ----------
    v : dict
        The run's ``[environment.waves]`` values.
    h3 : float
        Its h3% [m].
    ship : Particulars or None
        The scenario ship's particulars.
    source : str
        Scenario name for messages.

    Returns
    -------
    FirstOrderSettings
    """
    if ship is None or any(getattr(ship, k, None) is None for k in
                           ("length", "beam", "draft", "block_coefficient")):
        raise _err(source, "environment.waves.first_order_motions",
                   "needs the ship's particulars (length, beam, draft, block_coefficient) "
                   "for its closed-form RAOs: a catalog ship or a ship file with [particulars]")
    if v.get("spreading") is not None:  # its bounds checked before the runs, not after
        from ..environment.directional_spreading import spreading_with_parameter

        try:
            spreading_with_parameter(v["spreading"], float(v.get("spreading_parameter", 2.0)))
        except ParameterError as exc:
            raise _err(source, "environment.waves.spreading_parameter",
                       exc.reason.lstrip(": ")) from None
    rao_file = v.get("rao_file")
    if rao_file is not None:
        from pathlib import Path

        from ..environment.rao_io import read_rao

        path = Path(rao_file)
        path = path if path.is_absolute() else Path(source).parent / path
        try:
            dofs = read_rao(path).dofs
        except (OSError, ParameterError) as exc:
            raise _err(source, "environment.waves.rao_file", str(exc)) from None
        rao_file = str(path)
    else:
        dofs = ("heave", "pitch") + (("roll",) if v.get("metacentric_height", getattr(
            ship, "metacentric_height", None)) is not None else ())
    from ..environment.first_order import MAX_COMPONENTS

    n = v.get("components", 64)  # a grid's value arrives as a float: 16.0 is 16, 2.5 is not
    if isinstance(n, bool) or not isinstance(n, (int, float)) or not (
            math.isfinite(n) and n == int(n) and 1 <= n <= MAX_COMPONENTS):
        raise _err(source, "environment.waves.components",
                   f"must be an integer in [1, {MAX_COMPONENTS}] [-], got {n!r}")
    sees = bool(v.get("autopilot_sees_first_order", False))
    if sees and "yaw" not in dofs:
        raise _err(source, "environment.waves.autopilot_sees_first_order",
                   "needs an RAO with a yaw degree of freedom; "
                   + (f"`rao_file` {rao_file} has {', '.join(dofs)}" if rao_file else
                      "the closed-form RAOs (Jensen et al. 2004, the default) have none")
                   + ". Give `rao_file`: a capytaine NetCDF (e.g. the shipped box barge, "
                   "seahelm.environment.rao_io.box_barge_database()) or an RAO table with a yaw "
                   "column")
    return FirstOrderSettings(
        h3=float(h3), spectrum=v["spectrum"], seed=int(v.get("seed", 0)), rao_file=rao_file,
        autopilot_sees=sees, direction=math.radians(float(v["direction_deg"])),
        gm=v.get("metacentric_height", getattr(ship, "metacentric_height", None)),
        components=int(n), spreading=v.get("spreading"),
        spreading_parameter=float(v.get("spreading_parameter", 2.0)),
        hull=(float(ship.length), float(ship.beam), float(ship.draft),
              float(ship.block_coefficient)))


#: The speed step of the RAOs [m/s]: a run whose recorded surge speed spans less takes the
#: RAO at its mid speed; another takes the RAOs at the multiples of it that bracket its speeds.
SPEED_STEP = 0.25


def _rao_speeds(lo: float, hi: float) -> tuple[float, ...]:
    """The RAO speeds of runs whose speeds span [lo, hi] [m/s] (:data:`SPEED_STEP`)."""
    lo, hi = max(lo, 0.0), max(hi, 0.0)
    if hi - lo < SPEED_STEP:
        return (0.5 * (lo + hi),)
    k0, k1 = math.floor(lo / SPEED_STEP), math.ceil(hi / SPEED_STEP)
    return tuple(k * SPEED_STEP for k in range(k0, k1 + 1))


def _raos(spec: FirstOrderSettings, speeds: tuple[float, ...]) -> list[Any]:
    from ..environment.rao import closed_form_rao

    if spec.rao_file:
        from ..environment.rao_io import read_rao

        return [read_rao(spec.rao_file)]

    L, B, T, cb = spec.hull
    hull = types.SimpleNamespace(length=L, beam=B, draft=T, block_coefficient=cb)
    return [closed_form_rao(hull, s, metacentric_height=spec.gm) for s in speeds]


def _speed_groups(speed: np.ndarray, rows: list[int]) -> list[tuple[tuple[float, ...],
                                                                    list[int]]]:
    """The runs ``rows`` by the RAO speeds they are computed with.

    A run whose speed spans less than :data:`SPEED_STEP` takes the RAO at its mid speed (runs
    of the same mid speed together); the others take the multiples of the step that bracket
    their speeds, interpolated linearly, in groups whose speed ranges lie within a step of each
    other (a sweep's distinct speeds: a group each). Either way a run's motions depend on its
    own record only, not on the runs computed with it (a sweep's chunks give the same values
    as the whole batch).
    """
    single: dict[float, list[int]] = {}
    spread: list[tuple[float, float, int]] = []
    for i in rows:
        lo, hi = float(np.min(speed[i])), float(np.max(speed[i]))
        speeds = _rao_speeds(lo, hi)
        if len(speeds) == 1:
            single.setdefault(speeds[0], []).append(i)
        else:
            spread.append((max(lo, 0.0), max(hi, 0.0), i))
    out = [((u,), members) for u, members in sorted(single.items())]
    group: list[tuple[float, float, int]] = []
    for item in sorted(spread) + [(math.inf, math.inf, -1)]:
        if group and item[0] > max(g[1] for g in group) + SPEED_STEP:
            out.append((_rao_speeds(min(g[0] for g in group), max(g[1] for g in group)),
                        sorted(g[2] for g in group)))
            group = []
        group.append(item)
    return out


@dataclasses.dataclass(frozen=True)
class FirstOrderPostPass:
    """The first-order motions after the run: a :attr:`Problem.post_pass
    <seahelm.simulation.problem.Problem>` (``simulate`` computes it from the recordings into
    the result's ``extra`` channels).

    Attributes
    ----------
    specs : tuple of FirstOrderSettings
        Each run's settings (:func:`first_order_settings`).
    batch_seed : int or None
        The batch's (Monte-Carlo) seed.
    source : str
        Scenario name for messages.
    first_run : int
        The flat index of the first run (a sweep's chunk, :meth:`select_runs`), by which the
        runs are seeded.
    """

    specs: tuple[FirstOrderSettings, ...]
    batch_seed: int | None
    source: str
    first_run: int = 0

    def select_runs(self, start: int, stop: int) -> "FirstOrderPostPass":
        """Runs ``start`` to ``stop`` − 1 alone (a sweep's chunk: run i keeps run i's sea).

        Parameters
        ----------
        start, stop : int

        Returns
        -------
        FirstOrderPostPass
        """
        return dataclasses.replace(self, specs=self.specs[start:stop],
                                   first_run=self.first_run + start)

    def compute(self, result: Any) -> tuple[dict[str, Any], dict[str, Any]]:
        """The motions of ``result``'s runs (NaN in diverged runs).

        Parameters
        ----------
        result : SimResult
            The simulated runs (before it is returned).

        Returns
        -------
        (dict, dict)
            The ``extra`` channels (name -> (values (runs, time), unit, description)) and the
            metadata's ``first_order_motions`` (what was added, from which RAOs).
        """
        return _first_order_motions(result, list(self.specs), self.batch_seed, self.source,
                                    self.first_run)


def _first_order_motions(result: Any, specs: list[FirstOrderSettings], batch_seed: int | None,
                         source: str, first: int) -> tuple[dict[str, Any], dict[str, Any]]:
    from ..environment.first_order import first_order_motions
    from ..environment.spectra import spectrum_from_wave_height

    n, R = result.time.size, result.n_runs
    groups: dict[FirstOrderSettings, list[int]] = {}
    for i, spec in enumerate(specs):
        groups.setdefault(spec, []).append(i)
    values: dict[str, np.ndarray] = {}
    has_roll = "roll_angle" in result.channel_names()
    for spec, rows in groups.items():
        ok = [i for i in rows if result.status[i] == 0]  # a diverged run has no wave motions
        entropy = spec.seed if batch_seed is None else [spec.seed, batch_seed]
        for speeds, members in _speed_groups(result["surge_speed"], ok):
            record = {"time": result.time,
                      **{name: result[name][members] for name in ("surge_speed", "heading",
                                                                  "north", "east")}}
            try:
                m = first_order_motions(
                    record, spectrum_from_wave_height(spec.spectrum, spec.h3),
                    _raos(spec, speeds), wave_direction=spec.direction,
                    seed=[np.random.SeedSequence(entropy, spawn_key=(first + i, 1))
                          for i in members],
                    n_components=spec.components, spreading=spec.spreading,
                    spreading_parameter=spec.spreading_parameter)
            except (KeyError, ParameterError) as exc:
                raise _err(source, "environment.waves.first_order_motions", str(exc)) from None
            for dof, v in m.values.items():
                values.setdefault(dof, np.full((R, n), np.nan))[members] = v
    from ..environment.first_order import OUTPUT_NAMES
    from ..environment.rao import DOF_UNITS

    extra: dict[str, Any] = {}
    for dof, v in values.items():
        extra[OUTPUT_NAMES[dof]] = (v, DOF_UNITS[dof].split("/")[0],
                                    f"first-order (wave-frequency) {dof}")
    if "roll" in values:
        total = values["roll"] + (result["roll_angle"] if has_roll else 0.0)
        extra["roll"] = (total, "rad", "model roll angle + first-order roll" if has_roll
                         else "first-order roll (the model has no roll)")
    if "yaw" in values:
        extra["heading_total"] = (result["heading"] + values["yaw"], "rad",
                                  "heading + first-order yaw (after the run: the "
                                  "autopilot did not see it)")
    files = {spec.rao_file for spec in specs}
    return extra, {"first_order_motions": (
        ", ".join(values) + " from "
        + ("closed-form RAOs (Jensen et al. 2004)" if files == {None} else
           "RAO file(s) " + ", ".join(str(f) for f in files if f)
           + (" and closed-form RAOs" if None in files else ""))
        + " in the irregular sea, added after the run (seahelm.environment.first_order); NaN "
        "in diverged runs")}


def first_order_in_the_loop(specs: list[FirstOrderSettings], batch_seed: int | None,
                            source: str, surge_sway: bool = False) -> Any:
    """The in-loop motions of a batch whose runs ask for ``autopilot_sees_first_order``.

    Run i's components are drawn as the post-pass draws them (the second child of run i's sea
    stream, over the RAO's frequency table) and stacked for the loop.

    Parameters
    ----------
    specs : list of FirstOrderSettings
        The runs' settings (:func:`first_order_settings`).
    batch_seed : int or None
        The batch's (Monte-Carlo) seed.
    source : str
        Scenario name for messages.
    surge_sway : bool, optional
        Evaluate the RAO's surge and sway too (``[sensors] wave_motion``: the DP sensors
        see them), with its heave, roll, pitch and yaw.

    Returns
    -------
    FirstOrderInLoop or None
        None when no run asks for it (the post-pass then runs after the simulation); its
        :attr:`~seahelm.environment.first_order_in_loop.FirstOrderInLoop.settings` are
        ``specs``.
    """
    sees = {bool(s.autopilot_sees) for s in specs}
    if sees == {False}:
        return None
    if len(sees) > 1:
        raise _err(source, "environment.waves.autopilot_sees_first_order",
                   "must be the same in every run (the motions are in the loop or after it)")
    for key, what in (("rao_file", "one RAO file"), ("components", "one number of "
                                                                     "components")):
        if len({getattr(s, key) for s in specs}) > 1:
            raise _err(source, f"environment.waves.{key}", f"must be the same in every run "
                       f"when the autopilot sees the first-order yaw ({what} for the batch's "
                       "tables)")
    from ..environment.first_order import WaveComponents, draw_wave_components
    from ..environment.first_order_in_loop import first_order_in_loop
    from ..environment.rao_io import read_rao
    from ..environment.spectra import spectrum_from_wave_height

    rao = read_rao(specs[0].rao_file)
    band = (float(rao.frequency[0]), float(rao.frequency[-1]))
    spectra: dict[tuple[str, float], Any] = {}
    parts = []
    for i, spec in enumerate(specs):
        key = (spec.spectrum, spec.h3)
        if key not in spectra:
            spectra[key] = spectrum_from_wave_height(*key)
        entropy = spec.seed if batch_seed is None else [spec.seed, batch_seed]
        parts.append(draw_wave_components(
            spectra[key], spec.direction, runs=1,
            seed=[np.random.SeedSequence(entropy, spawn_key=(i, 1))],
            n_components=spec.components, band=band, spreading=spec.spreading,
            spreading_parameter=spec.spreading_parameter))
    stacked = WaveComponents(*(np.concatenate([getattr(p, f) for p in parts]) for f in (
        "frequency", "wavenumber", "direction", "amplitude", "phase")), band,
        [p.seeds[0] for p in parts])
    try:
        dofs = None if not surge_sway else [d for d in ("surge", "sway", "heave", "roll",
                                                         "pitch", "yaw") if d in rao.dofs]
        in_loop = first_order_in_loop(next(iter(spectra.values())), rao, wave_direction=0.0,
                                      components=stacked, autopilot_sees_first_order=True,
                                      dofs=dofs)
        return dataclasses.replace(in_loop, settings=tuple(specs))
    except ParameterError as exc:
        raise _err(source, "environment.waves.rao_file", str(exc)) from None
