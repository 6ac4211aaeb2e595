"""DP controller tuning by pole placement, with the closed loop checked on the vessel's own M, D.

The ``dp-pid`` law (:mod:`seahelm.control.dp_pid`; Fossen 2021, *Handbook of Marine Craft
Hydrodynamics and Motion Control*, 2nd ed., §12.2.6) places, per DOF i with the design model's
diagonal m_i, d_i, the poles of::

    m_i ẍ + d_i ẋ = −K_p x − K_d ẋ − K_i ∫x,   K_p = ω_i² m_i,  K_d = 2ζω_i m_i − d_i,
                                                K_i = (ω_i/10) K_p

that is of s³ + 2ζω_i s² + ω_i² s + ω_i³/10 = 0 (the designed poles, :func:`designed_poles`).
The check (:attr:`DpTuning.poles`) is the linear closed loop about ψ = 0 on the vessel's full
3 × 3 M and D (off-diagonal terms too: Fossen's supply vessel has M₂₃, D₂₃ ≠ 0)::

    η̇ = ν,  M ν̇ = −D ν − K_p η − K_d ν − K_i z,  ż = η

whose nine eigenvalues equal the designed ones when M and D are diagonal (the tests check
this) and move where the coupling is; a positive real part is reported as unstable.
:meth:`DpTuning.scenario` writes a set-point scenario (the supply vessel's example's form).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .dp_pid import DpPidParams, dp_pid_params

__all__ = ["DpTuning", "tune_dp", "designed_poles"]

_DOFS = ("surge", "sway", "yaw")


def designed_poles(bandwidth: float, damping: float, integral_ratio: float = 0.1
                   ) -> np.ndarray:
    """The three poles of one DOF: the roots of s³ + 2ζω s² + ω² s + κω³ (κ = 1/10).

    Parameters
    ----------
    bandwidth : float
        ω [rad/s].
    damping : float
        ζ [-].
    integral_ratio : float, optional
        κ [-] of K_i = κ ω K_p (default 0.1, Fossen's ω/10).

    Returns
    -------
    numpy.ndarray of complex, shape (3,)
    """
    w, z = bandwidth, damping
    return np.sort_complex(np.roots([1.0, 2.0 * z * w, w * w, integral_ratio * w ** 3]))


@dataclasses.dataclass(frozen=True)
class DpTuning:
    """The gains of ``dp-pid`` for a vessel and their closed-loop check (module docstring).

    Attributes
    ----------
    vessel : str
        The ship's name.
    params : DpPidParams
        The controller's parameters (gains and the thruster layout).
    bandwidth : tuple of float
        ω per DOF (surge, sway, yaw) [rad/s].
    damping : float
        ζ [-].
    gains : dict
        ``kp_surge`` … ``ki_yaw`` [N/m, N·s/m, N/(m·s); N·m/rad …].
    designed : numpy.ndarray
        The designed poles, (3 DOF, 3) [1/s].
    poles : numpy.ndarray
        The closed loop's nine eigenvalues on the full M, D [1/s].
    dt : float
        The controller's sample period [s].
    """

    vessel: str
    params: DpPidParams
    bandwidth: tuple[float, float, float]
    damping: float
    gains: dict[str, float]
    designed: np.ndarray
    poles: np.ndarray
    dt: float

    @property
    def stable(self) -> bool:
        """Every closed-loop pole in the open left half-plane."""
        return bool(np.all(self.poles.real < 0.0))

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the check found (an unstable loop; a bandwidth near the sample rate)."""
        out = []
        if not self.stable:
            out.append("the closed loop on the vessel's full M and D is unstable (a pole at "
                       f"{max(self.poles, key=lambda p: p.real):.4g} 1/s): lower the bandwidth")
        fast = max(self.bandwidth)
        if fast * self.dt > 0.1:
            out.append(f"ω·dt = {fast * self.dt:.3g} > 0.1: the sampled loop departs from the "
                       "continuous design; shorten --dt")
        return tuple(out)

    def as_dict(self) -> dict[str, Any]:
        """The tuning as JSON-ready values."""
        def cx(p):
            return [float(p.real), float(p.imag)]

        return {"vessel": self.vessel, "controller": "dp-pid",
                "bandwidth_rad_s": dict(zip(_DOFS, self.bandwidth)), "damping": self.damping,
                "dt_s": self.dt, "gains": self.gains,
                "designed_poles": {d: [cx(p) for p in row] for d, row in
                                   zip(_DOFS, self.designed)},
                "closed_loop_poles": [cx(p) for p in self.poles], "stable": self.stable,
                "warnings": list(self.warnings)}

    def scenario(self, ship: str, *, north: float = 10.0, east: float = 10.0,
                 heading_deg: float = 10.0, t_final: float = 300.0) -> dict[str, Any]:
        """A set-point scenario with these gains (as ``examples/supply_dp_setpoint.toml``).

        Parameters
        ----------
        ship : str
            The scenario's ``[vessel]``: a catalog name or a ship file's path.
        north, east : float, optional
            The set-point [m] (from rest at the origin).
        heading_deg : float, optional
            The set-point heading [deg].
        t_final : float, optional
            Run length [s].

        Returns
        -------
        dict
            The scenario's tables.
        """
        vessel = {"ship": ship} if ship.endswith(".toml") else {"catalog": ship}
        p = self.params
        return {
            "title": f"{self.vessel}: dp-pid by pole placement, ω = "
                     + ", ".join(f"{w:g}" for w in self.bandwidth) + f" rad/s, ζ = "
                     f"{self.damping:g}",
            "vessel": vessel,
            "actuator": {"model": "direct"},
            "controller": {"model": "dp-pid", "dt": self.dt,
                           "params": {"frequency_surge": p.frequency_surge,
                                      "frequency_sway": p.frequency_sway,
                                      "frequency_yaw": p.frequency_yaw,
                                      "damping_ratio": p.damping_ratio},
                           "reference": {"north": north, "east": east,
                                         "heading_deg": heading_deg, "wind_force_x": 0.0,
                                         "wind_force_y": 0.0, "wind_moment_z": 0.0}},
            "simulation": {"t_final": t_final, "dt": self.dt,
                           "record_every": max(1, int(round(1.0 / self.dt)))},
        }

    def comment(self) -> str:
        """The scenario's opening comment."""
        return ("seahelm dp tune: the dp-pid gains by pole placement (Fossen 2021, "
                "§12.2.6)\nK_p = ω² M_d, K_d = 2ζω M_d − D_d, K_i = ω/10 K_p per DOF; closed "
                "loop on the full M, D: " + ("stable" if self.stable else "UNSTABLE"))


def _check(name: str, value: float, unit: str, low: float = 0.0) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not (math.isfinite(value) and value > low):
        raise ParameterError(f"must be a finite number > {low:g} [{unit}], got {value!r}",
                             field=name, unit=unit, value=value)
    return float(value)


def tune_dp(ship: Any, *, bandwidth: Any = (0.1, 0.1, 0.2), damping: float = 1.0,
            dt: float = 0.1) -> DpTuning:
    """The ``dp-pid`` gains for a ship with thrusters and a ``dp-3dof`` model (module
    docstring).

    Parameters
    ----------
    ship : Ship
        A ship with thrusters whose parameters have M and D (``m11`` … ``d33``).
    bandwidth : float or sequence of 3 float, optional
        ω [rad/s], one for every DOF or per surge, sway, yaw (default 0.1, 0.1, 0.2: the
        controller's defaults).
    damping : float, optional
        ζ [-] (default 1).
    dt : float, optional
        Controller sample period [s] (default 0.1).

    Returns
    -------
    DpTuning

    Raises
    ------
    ParameterError
        A bandwidth, damping or dt not > 0 and finite, not one or three bandwidths; a
        derivative gain 2ζω m − d below zero (the vessel's damping alone is more than asked:
        raise ω or ζ); a ship the controller cannot take (:func:`dp_pid_params`).
    """
    ws = np.atleast_1d(np.asarray(bandwidth, dtype=object))
    if ws.ndim != 1 or ws.size not in (1, 3):
        raise ParameterError(f"must be one bandwidth or three (surge, sway, yaw) [rad/s], got "
                             f"{bandwidth!r}", field="bandwidth", unit="rad/s", value=bandwidth)
    w = tuple(_check("bandwidth", v, "rad/s") for v in np.broadcast_to(ws, (3,)))
    z = _check("damping", damping, "-")
    h = _check("dt", dt, "s")
    params = dp_pid_params(ship, frequency_surge=w[0], frequency_sway=w[1], frequency_yaw=w[2],
                           damping_ratio=z)
    m = np.array([params.mass_surge, params.mass_sway, params.inertia_yaw])
    d = np.array([params.damping_surge, params.damping_sway, params.damping_yaw])
    om = np.array(w)
    kp = om ** 2 * m
    kd = 2.0 * z * om * m - d
    ki = params.integral_ratio * om * kp
    for j, dof in enumerate(_DOFS):
        if kd[j] < 0.0:
            raise ParameterError(
                f"= {om[j]:g} [rad/s] gives a negative derivative gain in {dof} (2ζω m = "
                f"{2 * z * om[j] * m[j]:.4g} "
                f"< the vessel's damping {d[j]:.4g}): raise the bandwidth or the damping",
                field="bandwidth", unit="rad/s", value=float(om[j]))
    gains = {f"{g}_{dof}": float(v[j]) for g, v in (("kp", kp), ("kd", kd), ("ki", ki))
             for j, dof in enumerate(_DOFS)}
    M, D = ship.params.mass_matrix(), ship.params.damping_matrix()
    Minv = np.linalg.inv(M)
    a = np.zeros((9, 9))
    a[0:3, 3:6] = np.eye(3)
    a[3:6, 0:3] = -Minv @ np.diag(kp)
    a[3:6, 3:6] = -Minv @ (D + np.diag(kd))
    a[3:6, 6:9] = -Minv @ np.diag(ki)
    a[6:9, 0:3] = np.eye(3)
    poles = np.sort_complex(np.linalg.eigvals(a))
    designed = np.array([designed_poles(wj, z, params.integral_ratio) for wj in w])
    return DpTuning(vessel=ship.name, params=params, bandwidth=w, damping=z, gains=gains,
                    designed=designed, poles=poles, dt=h)
