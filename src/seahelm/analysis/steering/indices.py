"""Steering indices of a linearised ship: Nomoto K, T_1, T_2, T_3, T and course stability.

From a :class:`~seahelm.analysis.equilibria.linearisation.LinearModel` of the ship alone (linearised
without its steering gear, input ``rudder_angle``), the *steering states* are the states other
than position, heading and surge: sway and yaw rate of a 3-DOF model, yaw rate (and the
auxiliary state) of a Nomoto model, drift angle and yaw rate of Voitkunsky's. Nomoto's (1957)
transfer function r/δ = K (1 + T_3 s)/((1 + T_1 s)(1 + T_2 s)) is the one of that block
(:func:`seahelm.hydrodynamics.linear_model.nomoto_from_state_space`; the first-order
T = T_1 + T_2 − T_3). Nomoto's model holds the speed constant: the surge coupling of a 3-DOF
model is dropped. It vanishes at the straight run of a port–starboard symmetric hull; it is
small but not zero for the Mariner's single-screw bias (Y_0, N_0) and in a turn, and
:attr:`SteeringIndices.surge_coupling` reports its size: the largest
|A_{s,u} A_{u,s'}| / |A_{s,s'}| over the steering states s, s' (0 when decoupled).

Roll (a 4-DOF model such as Son & Nomoto's container ship)
    Nomoto's form is a sway–yaw theory. With roll states (roll rate p, roll angle φ) in the
    steering block, the roll mode is *residualised*: held quasi-static (ṗ = φ̇ = 0), the
    singular-perturbation reduction of Kokotović, Khalil & O'Reilly (1986, §1.2),
    A_r = A_ss − A_sf A_ff⁻¹ A_fs, b_r = b_s − A_sf A_ff⁻¹ b_f (s: sway and yaw, f: roll).
    The reduced model keeps the steady-state gain of the full model exactly (K is the steady
    r/δ with the ship heeled), and its poles approximate the full model's non-oscillatory
    ones. :attr:`SteeringIndices.poles` and :attr:`SteeringIndices.course_stable` are those
    of the full block (roll included); :attr:`SteeringIndices.roll_coupling` is
    max |A_r − A_ss| / |A_ss| over the sway–yaw entries (0 without roll), the size of the
    heel's effect on steering. Freezing roll instead (φ = 0) would be wrong: for the container
    ship it turns a course-stable ship (T_1 = 107 s) into an unstable one (T_1 = −1007 s).

Course stability
    The ship is straight-line (course) stable when both poles of the sway–yaw block are
    negative (Clarke, Gedling & Hine 1983). The *stability index* is the non-dimensional
    slowest pole σ'_1 = −L/(U T_1) (negative: stable; Clarke et al.'s stability root), and
    the *stability lever* is the product of the non-dimensional poles σ'_1 σ'_2 =
    det(A) (L/U)², which for a 3-DOF model is C' = Y'_v N'_r − N'_v(Y'_r − m') over the
    mass-matrix determinant: positive with a negative trace means stable.

References
----------
Nomoto, K., Taguchi, T., Honda, K., Hirano, S. (1957). On the steering qualities of ships.
Int. Shipbuilding Progress 4(35), 354–370.
Clarke, D., Gedling, P., Hine, G. (1983). The application of manoeuvring criteria in hull
design using linear theory. Trans. RINA 125, 45–68.
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.,
§7.1 and §7.2 (course stability).
Kokotović, P., Khalil, H. K., O'Reilly, J. (1986). Singular Perturbation Methods in Control:
Analysis and Design. Academic Press.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...hydrodynamics.linear_model import NomotoConstants, nomoto_from_state_space
from ..equilibria.linearisation import LinearModel

__all__ = ["SteeringIndices", "steering_indices", "NON_STEERING_STATES", "ROLL_STATES"]

#: States that are not steering states: position, heading and surge.
NON_STEERING_STATES = ("north", "east", "heading", "surge_speed", "surge_perturbation")
#: Roll states, residualised (held quasi-static) for Nomoto's form (module docstring).
ROLL_STATES = ("roll_rate", "roll_angle")


@dataclasses.dataclass(frozen=True)
class SteeringIndices:
    """Nomoto's constants and the course-stability indices of a linearised ship.

    Attributes
    ----------
    nomoto : NomotoConstants
        K [1/s], T_1, T_2, T_3 [s]; ``nomoto.time_constant`` the first-order T [s].
    poles : numpy.ndarray
        Poles of the steering block [1/s] (roll included).
    stability_index : float
        σ'_1 = −L/(U T_1) [-]: negative for a course-stable ship (nan without L).
    stability_lever : float
        σ'_1 σ'_2 = det(A) (L/U)² [-] (nan without L, or for a one-state block).
    course_stable : bool
        Every pole of the steering block negative.
    surge_coupling : float
        Size of the dropped surge coupling relative to the block's own entries [-].
    steering_states : tuple of str
        The states of the block (roll included).
    speed, length : float
        U [m/s] and L [m].
    roll_coupling : float
        Size of the residualised roll's effect on the sway–yaw block [-] (0 without roll).
    """

    nomoto: NomotoConstants
    poles: np.ndarray
    stability_index: float
    stability_lever: float
    course_stable: bool
    surge_coupling: float
    steering_states: tuple[str, ...]
    speed: float
    length: float
    roll_coupling: float = 0.0

    def as_dict(self) -> dict[str, Any]:
        """The indices as plain numbers (for JSON; ``roll_coupling`` for a model with roll).

        Returns
        -------
        dict
        """
        n = self.nomoto
        roll = ({"roll_coupling": self.roll_coupling}
                if set(ROLL_STATES) & set(self.steering_states) else {})
        return {"K_per_s": n.gain, "T1_s": n.t1, "T2_s": n.t2, "T3_s": n.t3,
                "T_s": n.time_constant, "stability_index": self.stability_index,
                "stability_lever": self.stability_lever, "course_stable": self.course_stable,
                "surge_coupling": self.surge_coupling,
                "poles_per_s": [[float(p.real), float(p.imag)] for p in self.poles],
                "steering_states": list(self.steering_states), "speed_mps": self.speed,
                "length_m": self.length, **roll}


def steering_indices(linear: LinearModel) -> SteeringIndices:
    """Nomoto constants and course-stability indices of a linearised ship (module docstring).

    Parameters
    ----------
    linear : LinearModel
        The ship linearised without its steering gear (an input ``rudder_angle`` and a state
        ``yaw_rate``), e.g. ``linearize(ship, actuator=False)``.

    Returns
    -------
    SteeringIndices

    Raises
    ------
    ParameterError
        Without a ``rudder_angle`` input or a ``yaw_rate`` state, with more than two steering
        states besides roll, when the steering block depends on position or heading (an
        environment in the loop), or when its poles are complex (no Nomoto form).
    """
    if "rudder_angle" not in linear.input_labels:
        raise ParameterError(
            "needs the input rudder_angle: linearise the ship without its steering gear "
            f"(actuator=False); inputs: {', '.join(linear.input_labels)}", field="linear")
    if "yaw_rate" not in linear.state_labels:
        raise ParameterError(f"needs a state yaw_rate; states: {', '.join(linear.state_labels)}",
                             field="linear")
    block = tuple(s for s in linear.state_labels if s not in NON_STEERING_STATES)
    states = tuple(s for s in block if s not in ROLL_STATES)
    if len(states) > 2:
        raise ParameterError(
            f"has {len(states)} steering states besides roll ({', '.join(states)}); Nomoto's "
            "form takes a one- or two-state block", field="linear")
    idx = [linear.state_labels.index(s) for s in states]
    roll = [linear.state_labels.index(s) for s in block if s in ROLL_STATES]
    others = [i for i, s in enumerate(linear.state_labels) if s in NON_STEERING_STATES
              and s not in ("surge_speed", "surge_perturbation")]
    A = linear.A
    scale = np.abs(A[np.ix_(idx, idx)]).max()
    if others and np.abs(A[np.ix_(idx + roll, others)]).max() > 1e-9 * scale:
        raise ParameterError("the steering block depends on position or heading (an "
                             "environment in the model?): no Nomoto form", field="linear")
    coupling = 0.0
    for s in ("surge_speed", "surge_perturbation"):
        if s in linear.state_labels:
            iu = linear.state_labels.index(s)
            through = np.abs(np.outer(A[idx, iu], A[iu, idx]))
            coupling = float((through / np.maximum(np.abs(A[np.ix_(idx, idx)]),
                                                   1e-300)).max())
    sub = A[np.ix_(idx, idx)]
    column = linear.B[:, linear.input_labels.index("rudder_angle")]
    b = column[idx]
    poles = np.linalg.eigvals(A[np.ix_(idx + roll, idx + roll)])
    roll_coupling = 0.0
    if roll:  # residualise roll (Kokotović et al. 1986): A_r = A_ss − A_sf A_ff⁻¹ A_fs
        a_sf, a_ff = A[np.ix_(idx, roll)], A[np.ix_(roll, roll)]
        reduced = sub - a_sf @ np.linalg.solve(a_ff, A[np.ix_(roll, idx)])
        b = b - a_sf @ np.linalg.solve(a_ff, column[roll])
        roll_coupling = float((np.abs(reduced - sub) / np.maximum(np.abs(sub), 1e-300)).max())
        sub = reduced
    nomoto = nomoto_from_state_space(sub, b, speed=linear.speed,
                                     yaw_rate_index=states.index("yaw_rate"),
                                     require_stable=False)
    L, U = linear.length, linear.speed
    time_scale = L / U if (L > 0 and U > 0) else math.nan
    index = -time_scale / nomoto.t1
    lever = float(np.linalg.det(sub) * time_scale ** 2) if len(idx) == 2 else math.nan
    return SteeringIndices(nomoto=nomoto, poles=poles, stability_index=float(index),
                           stability_lever=lever, course_stable=bool(np.all(poles.real < 0)),
                           surge_coupling=coupling, steering_states=block, speed=float(U),
                           length=float(L), roll_coupling=roll_coupling)
