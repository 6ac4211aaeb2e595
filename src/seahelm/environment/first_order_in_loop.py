"""First-order wave motions inside the closed loop: what a controller can see of them.

:func:`first_order_in_loop` prepares, for a batch of runs, the same first-order (wave-frequency)
motions as the post-pass :func:`~seahelm.environment.first_order.first_order_motions` — the
two-time-scale superposition of Fossen (2011), §10.4, with the components of each run drawn
from its seed (:func:`~seahelm.environment.first_order.draw_wave_components`) and a_i H_j
tabulated per component over a uniform heading grid and the RAOs' speeds — but to be evaluated
by the compiled closed loop at the **live** state: at every recorded step and at every
controller sample, :func:`~seahelm.environment.first_order_kernel.first_order_sample` (the
post-pass's own per-sample code) sums

    η_j(t) = Σ_i Re(a_i H_j(ω_i, β_i − ψ(t), u(t)) e^{iθ_i(t)}),
    θ_i(t) = ω_i t − k_i (x(t) cos β_i + y(t) sin β_i) + ϕ_i,

from the model's outputs ``north`` x, ``east`` y, ``heading`` ψ and ``surge_speed`` u
(:mod:`seahelm.simulation.wave_motion_stage`). So on the same recorded states the in-loop
values are the post-pass's (:meth:`FirstOrderInLoop.post_pass`; tested to 1e-9), and with
``autopilot_sees_first_order=True`` the controller's ``heading`` measurement is the total
heading ψ + ψ₁ (ψ₁ the first-order yaw): the autopilot sees the wave-frequency yaw a gyro
compass measures (Fossen 2011, §10.4: "the measured heading is the sum of the LF and WF
heading"). Only the heading is fed back; the measured ``yaw_rate`` stays the model's (a
first-order yaw rate would need the RAO's derivative: not given by any source used here).

The first-order yaw needs an RAO with a ``yaw`` degree of freedom: a panel-method database
(capytaine's NetCDF, :func:`~seahelm.environment.rao_io.read_rao`, such as the shipped box
barge :func:`~seahelm.environment.rao_io.box_barge_database`) or a table with a yaw column.
The closed-form RAOs (:func:`~seahelm.environment.rao.closed_form_rao`: heave, pitch, roll)
have none, and no yaw model is invented: asking the autopilot to see the first-order yaw with
such an RAO is a :class:`~seahelm.errors.ParameterError`.

Cost: the sum over the components is done only at the recorded steps and the controller's
samples, not at the integrator's stages (it does not act on the dynamics). Memory: the tables
take 16 · runs · speeds · DOF · (headings + 1) · components bytes (1,000 runs, one speed, four
DOF, 25 headings, 64 components: 0.1 GB).

References
----------
Fossen, T. I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control, §8.2, §10.4.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..constants import GRAVITY
from ..errors import ParameterError
from .first_order import (OUTPUT_NAMES, FirstOrderMotions, WaveComponents,
                          draw_wave_components, first_order_motions)
from .first_order import _heading_grid, _raos, _tables
from .rao import DOF_UNITS, RAO

__all__ = ["FirstOrderInLoop", "first_order_in_loop", "output_signals", "MOTION_INPUTS",
           "HEADING_TOTAL"]

#: The model outputs the in-loop motions are evaluated from, with their units.
MOTION_INPUTS: dict[str, str] = {"north": "m", "east": "m", "heading": "rad",
                                 "surge_speed": "m/s"}
#: The output holding ψ + ψ₁ (what the autopilot sees when it sees the first-order yaw).
HEADING_TOTAL = "heading_total"


def output_signals(dofs: Sequence[str], model_roll: bool = False
                   ) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Names and units of the outputs the loop records for ``dofs``.

    The first-order parts (``heave`` [m], ``roll_wave``, ``pitch``, ``yaw_wave`` [rad], ...,
    :data:`~seahelm.environment.first_order.OUTPUT_NAMES`), then with yaw ``heading_total``
    = ψ + ψ₁ [rad], then with roll on a model with roll ``roll`` = the model's ``roll_angle`` +
    ``roll_wave`` [rad].

    Parameters
    ----------
    dofs : sequence of str
        The degrees of freedom evaluated.
    model_roll : bool, optional
        The model outputs ``roll_angle``.

    Returns
    -------
    (tuple of str, tuple of str)
    """
    names = [OUTPUT_NAMES[d] for d in dofs]
    units = [DOF_UNITS[d].split("/")[0] for d in dofs]
    if "yaw" in dofs:
        names.append(HEADING_TOTAL)
        units.append("rad")
    if model_roll and "roll" in dofs:
        names.append("roll")
        units.append("rad")
    return tuple(names), tuple(units)


@dataclasses.dataclass(frozen=True, eq=False)
class FirstOrderInLoop:
    """The per-run wave components and RAO tables the closed loop evaluates (module docstring).

    Attributes
    ----------
    components : WaveComponents
        The drawn components (one set per run).
    raos : tuple of RAO
        The RAOs (one, or several at increasing speeds).
    dofs : tuple of str
        The degrees of freedom evaluated, in the RAOs' order.
    autopilot_sees_first_order : bool
        Whether the controller's ``heading`` measurement is ψ + ψ₁.
    spectrum : WaveSpectrum
        The sea spectrum (for :meth:`post_pass`).
    arrays : tuple of numpy.ndarray
        The kernel's inputs: components (runs, 6, m) (ω, k, cos β, sin β, β, ϕ), tables
        (runs, 2, speeds, DOF, headings + 1, m) (real and imaginary a_i H_j), long-crested flags
        (runs,), speeds [m/s] and the heading step [rad] (1,).
    settings : tuple
        What the components were drawn from, one per run, if its maker keeps it (e.g. a
        scenario's :class:`~seahelm.scenario.first_order.FirstOrderSettings`; default none):
        typed values, written into the result's metadata as JSON
        (``first_order_settings``) by the loop's stage; sliced with the runs.
    """

    components: WaveComponents
    raos: tuple[RAO, ...]
    dofs: tuple[str, ...]
    autopilot_sees_first_order: bool
    spectrum: Any
    arrays: tuple[np.ndarray, ...]
    settings: tuple[Any, ...] = ()

    @property
    def n_runs(self) -> int:
        """Number of runs the components were drawn for."""
        return int(self.components.frequency.shape[0])

    def output_signals(self, model_roll: bool = False) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The outputs the loop records, and their units (:func:`output_signals`).

        Parameters
        ----------
        model_roll : bool, optional
            The model has a ``roll_angle`` (then ``roll`` is its total).

        Returns
        -------
        (tuple of str, tuple of str)
        """
        return output_signals(self.dofs, model_roll)

    def select_runs(self, start: int, stop: int) -> "FirstOrderInLoop":
        """Runs ``start`` to ``stop`` − 1 alone, with their own components and tables (a
        sweep's chunk, :func:`seahelm.sweep.chunks.select_runs`: run i keeps run i's sea).

        Parameters
        ----------
        start, stop : int
            Run indices, 0 <= start < stop <= :attr:`n_runs`.

        Returns
        -------
        FirstOrderInLoop
        """
        if not 0 <= start < stop <= self.n_runs:
            raise ParameterError(f"runs {start}:{stop} are not a slice of the first-order "
                                 f"motions' {self.n_runs} runs", field="first_order")
        c = self.components
        comps = dataclasses.replace(c, **{f: getattr(c, f)[start:stop] for f in (
            "frequency", "wavenumber", "direction", "amplitude", "phase")},
            seeds=list(c.seeds[start:stop]))
        per_run = self.arrays[:3]  # components, tables, long-crested flags: by run
        arrays = tuple(a[start:stop] for a in per_run) + tuple(self.arrays[3:])
        return dataclasses.replace(self, components=comps, arrays=arrays,
                                   settings=tuple(self.settings[start:stop]))

    def post_pass(self, result: Any, **kwargs: Any) -> FirstOrderMotions:
        """The post-pass on ``result``'s recorded states with these very components.

        Parameters
        ----------
        result : SimResult
            A result of the loop (its ``north``, ``east``, ``heading``, ``surge_speed``).
        **kwargs
            Passed to :func:`~seahelm.environment.first_order.first_order_motions`
            (``threads``, ``strict``).

        Returns
        -------
        FirstOrderMotions
        """
        record = {"time": result.time, **{k: result[k] for k in MOTION_INPUTS}}
        return first_order_motions(record, self.spectrum, list(self.raos), wave_direction=0.0,
                                   components=self.components, dofs=self.dofs, **kwargs)


def first_order_in_loop(spectrum: Any, rao: RAO | Sequence[RAO], *, wave_direction: float,
                        runs: int = 1, seed: Any = 0, n_components: int = 64,
                        band: tuple[float, float] | None = None,
                        spreading: str | None = None, spreading_parameter: float = 2.0,
                        dofs: Sequence[str] | None = None,
                        autopilot_sees_first_order: bool = False,
                        components: WaveComponents | None = None,
                        gravity: float = GRAVITY, strict: bool | None = None
                        ) -> FirstOrderInLoop:
    """First-order motions for the closed loop (``Problem(first_order=...)``).

    Parameters
    ----------
    spectrum : WaveSpectrum
        One-sided sea spectrum.
    rao : RAO or sequence of RAO
        One RAO (used at every speed), or RAOs at increasing speeds (interpolated in u). Its
        headings must cover 0–360° (a half table is mirrored): a ship may turn any way.
    wave_direction : float
        Mean direction the waves come from, clockwise from north [rad].
    runs : int, optional
        Runs of the batch (the problem's).
    seed : int, SeedSequence or sequence, optional
        Per-run seeds (:func:`~seahelm.environment.first_order.draw_wave_components`).
    n_components : int, optional
        Components per run (default 64).
    band : (float, float), optional
        Frequency band [rad/s] (default the RAOs' frequency table).
    spreading : {"cos-2s", "cos-n"} or None, optional
        Directional spreading; None: long-crested.
    spreading_parameter : float, optional
        s (cos-2s) or n (cos-n) [-].
    dofs : sequence of str, optional
        Degrees of freedom (default heave, roll, pitch and yaw, those the RAO has).
    autopilot_sees_first_order : bool, optional
        Feed the controller ψ + ψ₁ as its ``heading`` (needs ``yaw``).
    components : WaveComponents, optional
        Components drawn beforehand (then ``seed``, ``n_components``, ``band`` and
        ``spreading`` are not used).
    gravity : float, optional
        g [m/s²].
    strict : bool, optional
        Raise instead of warning when a component lies outside the RAO's frequencies.

    Returns
    -------
    FirstOrderInLoop

    Raises
    ------
    ParameterError
        ``autopilot_sees_first_order`` with an RAO without yaw (named, with which RAOs have
        yaw); an RAO missing a DOF asked for or not covering every heading; bad components.
    """
    if not isinstance(autopilot_sees_first_order, (bool, np.bool_)):
        raise ParameterError(f"must be True or False, got {autopilot_sees_first_order!r}",
                             field="autopilot_sees_first_order",
                             value=autopilot_sees_first_order)
    raos, dofs_t = _raos(rao, dofs)
    if autopilot_sees_first_order and "yaw" not in dofs_t and "yaw" in raos[0].dofs:
        raise ParameterError("must include 'yaw' for the autopilot to see the first-order yaw, "
                             f"got {', '.join(dofs_t)}", field="dofs", value=dofs_t)
    if autopilot_sees_first_order and "yaw" not in dofs_t:
        raise ParameterError(
            f"needs an RAO with a yaw degree of freedom; this one has {', '.join(raos[0].dofs)}"
            ". The closed-form RAOs (Jensen et al. "
            "2004; closed_form_rao) have no yaw; a panel-method database has: capytaine's "
            "NetCDF (rao_io.read_rao, e.g. rao_io.box_barge_database()) or a table with a yaw "
            "column", field="autopilot_sees_first_order", value=True)
    if components is None:
        if band is None:
            band = (max(r.frequency[0] for r in raos), min(r.frequency[-1] for r in raos))
        components = draw_wave_components(spectrum, wave_direction, runs=runs, seed=seed,
                                          n_components=n_components, band=band,
                                          spreading=spreading,
                                          spreading_parameter=spreading_parameter,
                                          gravity=gravity)
    comp = components
    R = comp.frequency.shape[0]
    grid, step = _heading_grid(raos)
    tre, tim = _tables(raos, dofs_t, comp, slice(0, R), grid, strict)
    if not (np.isfinite(tre).all() and np.isfinite(tim).all()):
        lo, hi = np.degrees(raos[0].heading[[0, -1]])
        raise ParameterError(
            f"covers wave headings {lo:.4g} to {hi:.4g} deg; in the loop a ship may meet the "
            "waves at any heading, so the RAO must cover 0-360 deg (a half table 0-180 deg is "
            "mirrored)", field="rao.heading", unit="deg")
    packed = np.ascontiguousarray(np.stack(
        [comp.frequency, comp.wavenumber, np.cos(comp.direction), np.sin(comp.direction),
         comp.direction, comp.phase], axis=1))
    tables = np.ascontiguousarray(np.stack([tre, tim], axis=1))
    same = np.all(comp.direction == comp.direction[:, :1], axis=1).astype(float)
    speeds = np.array([r.speed for r in raos], dtype=float)
    return FirstOrderInLoop(comp, tuple(raos), dofs_t, bool(autopilot_sees_first_order),
                            spectrum, (packed, tables, same, speeds, np.array([step])))
