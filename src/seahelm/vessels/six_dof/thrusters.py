"""Thrusters of a 6-DOF craft: the configuration matrix and control allocation.

Each thruster i at r_i with direction α_i in the body x-y plane gives the generalized force
τ = Σ_i T_i b_i, b_i = (cos α_i, sin α_i, 0, r_i × (cos α_i, sin α_i, 0)) — the columns of the
thrust configuration matrix T(α) (Fossen 2021, §11.2). With thrust T_i = k_i n_i|n_i| the
allocation problem for the controlled degrees of freedom (rows ``dofs``) is τ_c = B f,
f_i = T_i, solved by the weighted pseudo-inverse (Fossen 2021, §11.2.2)::

    f = W⁻¹ Bᵀ (B W⁻¹ Bᵀ)⁻¹ τ_c,   n_i = sign(f_i) √(|f_i| / k_i),   then n_i limited

(minimising fᵀ W f subject to B f = τ_c). It needs at least as many effective thrusters as
controlled DOF (B of full row rank); fewer is a :class:`~seahelm.errors.ParameterError`.
The saturation is the plain clip of each n_i to its limits (the constrained allocations belong
to the DP issue).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...errors import ParameterError
from .params import SixDofParams

__all__ = ["configuration_matrix", "Allocation", "allocate", "DOF_NAMES"]

#: Generalized-force names, in τ order.
DOF_NAMES: tuple[str, ...] = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def configuration_matrix(params: SixDofParams, angles: Any = None) -> np.ndarray:
    """T(α) (6 × n_thrusters): the generalized force of a unit thrust of each thruster.

    Parameters
    ----------
    params : SixDofParams
        The craft (thruster positions and directions).
    angles : array_like, optional
        Directions α_i [rad] of the thrusters (default: ``thruster_direction``; an azimuth
        thruster's angle is its state).

    Returns
    -------
    numpy.ndarray, shape (6, n_thrusters)
    """
    n = int(params.thruster_count)
    alpha = (np.asarray(params.thruster_direction[:n], dtype=float) if angles is None
             else np.asarray(angles, dtype=float).reshape(n))
    out = np.zeros((6, n))
    for i in range(n):
        f = np.array([math.cos(alpha[i]), math.sin(alpha[i]), 0.0])
        r = np.array([params.thruster_x[i], params.thruster_y[i], params.thruster_z[i]])
        out[:3, i] = f
        out[3:, i] = np.cross(r, f)
    return out


class Allocation:
    """Weighted pseudo-inverse allocation of the generalized forces ``dofs`` to shaft speeds.

    Parameters
    ----------
    params : SixDofParams
        The craft.
    dofs : sequence of str
        Controlled degrees of freedom, names in :data:`DOF_NAMES` (e.g. ``("surge", "yaw")``).
    weights : array_like, optional
        W = diag(weights) > 0, one per thruster (default ones): a larger weight uses a
        thruster less.

    Raises
    ------
    ParameterError
        For an unknown DOF name, weights that are not > 0, or fewer effective thrusters than
        controlled DOF (B W⁻¹ Bᵀ singular).
    """

    def __init__(self, params: SixDofParams, dofs: Any, *, weights: Any = None) -> None:
        dofs = tuple(dofs)
        unknown = [d for d in dofs if d not in DOF_NAMES]
        if unknown or not dofs:
            raise ParameterError(f"must name some of {', '.join(DOF_NAMES)}, got "
                                 f"{list(dofs)}", field="dofs")
        n = int(params.thruster_count)
        w = np.ones(n) if weights is None else np.asarray(weights, dtype=float).reshape(-1)
        if w.shape != (n,) or not np.all(w > 0.0) or not np.all(np.isfinite(w)):
            raise ParameterError(f"must be {n} numbers > 0 [-], got {weights!r}",
                                 field="weights", unit="-")
        b = configuration_matrix(params)[[DOF_NAMES.index(d) for d in dofs], :]
        rank = np.linalg.matrix_rank(b) if n else 0
        if rank < len(dofs):
            raise ParameterError(
                f"allocation of {len(dofs)} DOF ({', '.join(dofs)}) needs {len(dofs)} effective "
                f"thrusters, the craft has {rank} (of {n} thrusters)", field="dofs",
                value=rank)
        winv = np.diag(1.0 / w)
        self.dofs = dofs
        self.matrix = b
        #: the weighted pseudo-inverse B_W⁺ = W⁻¹ Bᵀ (B W⁻¹ Bᵀ)⁻¹ (n × len(dofs))
        self.pseudo_inverse = winv @ b.T @ np.linalg.inv(b @ winv @ b.T)
        self._k_pos = np.asarray(params.thruster_k_pos[:n], dtype=float)
        self._k_neg = np.asarray(params.thruster_k_neg[:n], dtype=float)
        self._lo = np.asarray(params.thruster_min_speed[:n], dtype=float)
        self._hi = np.asarray(params.thruster_max_speed[:n], dtype=float)

    def thrusts(self, tau: Any) -> np.ndarray:
        """Thrusts f [N] for the generalized forces ``tau``: f = B_W⁺ τ.

        Parameters
        ----------
        tau : array_like, shape (..., len(dofs))
            Generalized forces [N, N·m] in the order of ``dofs``.

        Returns
        -------
        numpy.ndarray, shape (..., n_thrusters)
        """
        return np.asarray(tau, dtype=float) @ self.pseudo_inverse.T

    def __call__(self, tau: Any) -> np.ndarray:
        """Shaft-speed commands n [rad/s] for ``tau``: n_i = sign(f_i) √(|f_i|/k_i), limited.

        Parameters
        ----------
        tau : array_like, shape (..., len(dofs))
            Generalized forces [N, N·m] in the order of ``dofs``.

        Returns
        -------
        numpy.ndarray, shape (..., n_thrusters)
        """
        f = self.thrusts(tau)
        k = np.where(f >= 0.0, self._k_pos, self._k_neg)
        return np.clip(np.sign(f) * np.sqrt(np.abs(f) / k), self._lo, self._hi)


def allocate(params: SixDofParams, tau: Any, dofs: Any, *, weights: Any = None) -> np.ndarray:
    """Shaft-speed commands for ``tau`` by :class:`Allocation` (see it).

    Parameters
    ----------
    params : SixDofParams
    tau : array_like, shape (..., len(dofs))
    dofs : sequence of str
    weights : array_like, optional

    Returns
    -------
    numpy.ndarray, shape (..., n_thrusters)
    """
    return Allocation(params, dofs, weights=weights)(tau)
