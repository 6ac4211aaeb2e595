"""The general final-state method (метод конечного состояния, МКС), numpy and batched.

General method (eq. (12)-(15))
    For a control-affine system dz/dt = Φ(t, z) + B(t, z) u and a smooth criterion J(z(t_f))
    with target J*, the control is::

        u = G⁺ f_J,   G = ∂J/∂z|_{z̄} · W · B(t, z),   f_J = (J* − J(z̄)) / T_u,
        G⁺ = Gᵀ (G Gᵀ)⁻¹                                   (pseudo-inverse, eq. (13))

    with the predicted final state z̄ of the *uncontrolled* motion and Alekseev's nonlinear
    transition matrix W from eq. (14)::

        dz̄/dϑ = Φ(ϑ, z̄),   dW/dϑ = ∂Φ/∂z|_{z̄} W,   ϑ ∈ [t, t_f],  z̄(t) = z(t), W(t) = I

    or their one-step approximation over a short interval h, eq. (15)::

        z̄ = z + Φ(t, z) h,   W = I + ∂Φ/∂z|_{z} h.

    :class:`FinalStateController` implements both (``prediction="one-step"`` or
    ``"integrate"``, registry :data:`PREDICTIONS`) for any batch of states, any number of
    controls r and criteria m (vector criteria through the Moore-Penrose pseudo-inverse).
    :func:`simulate_final_state` closes the loop in numpy (RK4 by default, zero-order hold)
    for tests and small studies.

The compiled yaw-rate and heading controllers of the paper for the catamaran (engine plug-ins)
are in :mod:`seahelm.control.final_state`.

References
----------
Shushlyapin, E. A., Karapetyan, V. A., Bezuglaya, A. E., Afonina, A. A. (2017), SPIIRAS
Proceedings 4(53), eq. (12)-(23). Shushlyapin, E. A. (2012). Control of nonlinear systems based
on the prediction of the final state of the uncontrolled motion. Sevastopol: SevNTU.
Alekseev, V. M. (1961). An estimate for the perturbations of the solutions of ordinary
differential equations. Vestnik MGU, Ser. 1, 2, 28-36.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np

from .._validate import as_float_array, check_positive, lookup_name
from ..errors import ParameterError
from ..numerics.runge_kutta import ButcherTableau, get_integrator, rk_step

__all__ = [
    "FinalStateController",
    "PREDICTIONS",
    "one_step_prediction",
    "integrated_prediction",
    "simulate_final_state",
]


Array = np.ndarray


# ------------------------------------------------------------------------------------------
# the general method (numpy, batched)
# ------------------------------------------------------------------------------------------
def _fd_jacobian(f: Callable[[Array], Array], z: Array, eps: float = 1e-7) -> Array:
    """Central-difference Jacobian of a batched f: (N, n) -> (N, m); returns (N, m, n)."""
    n = z.shape[-1]
    cols = []
    for j in range(n):
        step = eps * np.maximum(1.0, np.abs(z[:, j]))
        dz = np.zeros_like(z)
        dz[:, j] = step
        cols.append((f(z + dz) - f(z - dz)) / (2.0 * step[:, None]))
    return np.stack(cols, axis=-1)


def one_step_prediction(ctrl: "FinalStateController", t: float, z: Array, t_f: float
                        ) -> tuple[Array, Array]:
    """Eq. (15): z̄ = z + Φ h, W = I + ∂Φ/∂z h with h = t_f − t. Shapes (N, n), (N, n, n).

    Parameters
    ----------
    ctrl : FinalStateController
        Controller providing the drift Φ(t, z) and its Jacobian.
    t : float
        Current time [s].
    z : numpy.ndarray, shape (N, n)
        Current states.
    t_f : float
        Final time of the prediction [s].

    Returns
    -------
    zbar : numpy.ndarray, shape (N, n)
        Predicted final states z̄.
    W : numpy.ndarray, shape (N, n, n)
        Sensitivity ∂z̄/∂z.
    """
    h = t_f - t
    n = z.shape[-1]
    zbar = z + h * ctrl.drift(t, z)
    W = np.eye(n)[None] + h * ctrl.jacobian(t, z)
    return zbar, W


def integrated_prediction(ctrl: "FinalStateController", t: float, z: Array, t_f: float
                          ) -> tuple[Array, Array]:
    """Eq. (14) integrated over [t, t_f] with ``ctrl.substeps`` steps of ``ctrl.integrator``.

    Parameters
    ----------
    ctrl : FinalStateController
        Controller providing the drift Φ(t, z), its Jacobian, ``substeps`` and ``integrator``.
    t : float
        Current time [s].
    z : numpy.ndarray, shape (N, n)
        Current states.
    t_f : float
        Final time of the prediction [s].

    Returns
    -------
    zbar : numpy.ndarray, shape (N, n)
        Predicted final states z̄.
    W : numpy.ndarray, shape (N, n, n)
        Sensitivity ∂z̄/∂z.
    """
    N, n = z.shape
    k = ctrl.substeps
    h = (t_f - t) / k
    # z̄ and W side by side in one state (N, n + n²), so one step advances both
    zw = np.concatenate([z, np.broadcast_to(np.eye(n).ravel(), (N, n * n))], axis=1)

    def f(s: float, zz: Array) -> Array:
        zb, W = zz[:, :n], zz[:, n:].reshape(N, n, n)
        return np.concatenate([ctrl.drift(s, zb), (ctrl.jacobian(s, zb) @ W).reshape(N, n * n)],
                              axis=1)

    s = t
    for _ in range(k):
        zw = rk_step(ctrl.integrator, f, s, zw, h)
        s += h
    return zw[:, :n].copy(), zw[:, n:].reshape(N, n, n).copy()


PREDICTIONS: dict[str, Callable[..., tuple[Array, Array]]] = {
    "one-step": one_step_prediction,
    "integrate": integrated_prediction,
}
"""How z̄ and W are obtained: eq. (15) or eq. (14) integrated."""


@dataclasses.dataclass(frozen=True)
class FinalStateController:
    """The final-state method for dz/dt = Φ(t, z) + B(t, z) u, eq. (13)-(15), batched.

    Parameters
    ----------
    drift : callable(t, z) -> (N, n)
        Φ(t, z) over a batch of states ``z`` (N, n).
    input_matrix : callable(t, z) -> (N, n, r), or array (n, r)
        B(t, z).
    criterion : callable(z) -> (N, m)
        J(z) (a scalar criterion is m = 1).
    time_constant : float
        T_u [s] of dJ/dt = (J* − J)/T_u.
    horizon : float
        Prediction interval [s]: h of eq. (15), or t_f − t for ``prediction="integrate"``
        (receding horizon); ignored when ``terminal_time`` is given.
    drift_jacobian : callable(t, z) -> (N, n, n), optional
        ∂Φ/∂z; central differences if omitted.
    criterion_gradient : callable(z) -> (N, m, n), optional
        ∂J/∂z; central differences if omitted.
    prediction : {"one-step", "integrate"}
        Eq. (15) or eq. (14) (registry :data:`PREDICTIONS`).
    terminal_time : float, optional
        A fixed final time t_f (terminal control, the method's original use); the prediction
        then runs over [t, t_f].
    substeps : int
        Integration steps for ``prediction="integrate"``.
    integrator : str or ButcherTableau
        Fixed-step method of ``prediction="integrate"`` and of :func:`simulate_final_state`:
        a name in :data:`~seahelm.numerics.runge_kutta.INTEGRATORS` (default "rk4") or a
        tableau.

    Raises
    ------
    ParameterError
        Non-positive ``time_constant``, ``horizon`` or ``substeps``; ValueError for an unknown
        ``prediction`` or ``integrator`` (listing the valid ones).
    """

    drift: Callable[[float, Array], Array]
    input_matrix: Callable[[float, Array], Array] | Array
    criterion: Callable[[Array], Array]
    time_constant: float
    horizon: float
    drift_jacobian: Callable[[float, Array], Array] | None = None
    criterion_gradient: Callable[[Array], Array] | None = None
    prediction: str = "one-step"
    terminal_time: float | None = None
    substeps: int = 20
    integrator: str | ButcherTableau = "rk4"

    def __post_init__(self) -> None:
        get_integrator(self.integrator)
        check_positive("time_constant", self.time_constant, "s")
        check_positive("horizon", self.horizon, "s")
        lookup_name("prediction", PREDICTIONS, self.prediction)
        if isinstance(self.substeps, bool) or int(self.substeps) != self.substeps or \
                self.substeps < 1:
            raise ParameterError(f"`substeps` must be a whole number >= 1, got {self.substeps!r}")

    # -- pieces --------------------------------------------------------------------------
    def jacobian(self, t: float, z: Array) -> Array:
        """∂Φ/∂z (N, n, n): the given function or central differences.

        Parameters
        ----------
        t : float
            Time [s].
        z : numpy.ndarray, shape (N, n)
            States.

        Returns
        -------
        numpy.ndarray, shape (N, n, n)
        """
        if self.drift_jacobian is not None:
            return np.asarray(self.drift_jacobian(t, z), dtype=float)
        return _fd_jacobian(lambda zz: self.drift(t, zz), z)

    def _B(self, t: float, z: Array) -> Array:
        if callable(self.input_matrix):
            return np.asarray(self.input_matrix(t, z), dtype=float)
        B = np.asarray(self.input_matrix, dtype=float)
        return np.broadcast_to(B, (z.shape[0],) + B.shape)

    def _J(self, z: Array) -> Array:
        J = np.asarray(self.criterion(z), dtype=float)
        return J.reshape(z.shape[0], -1)

    def _dJ(self, z: Array) -> Array:
        if self.criterion_gradient is not None:
            g = np.asarray(self.criterion_gradient(z), dtype=float)
            return g.reshape(z.shape[0], -1, z.shape[1])
        return _fd_jacobian(self._J, z)

    def final_time(self, t: float) -> float:
        """Final time t_f [s] of the prediction made at ``t``: ``terminal_time`` or t + ``horizon``.

        Parameters
        ----------
        t : float
            Current time [s].

        Returns
        -------
        float
            t_f [s].
        """
        if self.terminal_time is not None:
            if self.terminal_time <= t:
                raise ParameterError(
                    f"`terminal_time` {self.terminal_time!r} [s] must be after t = {t!r} [s]"
                )
            return float(self.terminal_time)
        return float(t) + float(self.horizon)

    def predict(self, t: float, z: Any) -> tuple[Array, Array]:
        """Predicted final state z̄ (N, n) and transition matrix W (N, n, n).

        Parameters
        ----------
        t : float
            Current time [s].
        z : array_like, shape (n,) or (N, n)
            Current states.

        Returns
        -------
        zbar : numpy.ndarray, shape (N, n)
            Predicted final states z̄.
        W : numpy.ndarray, shape (N, n, n)
            Transition matrix ∂z̄/∂z.
        """
        z = np.atleast_2d(as_float_array("z", z))
        return PREDICTIONS[self.prediction](self, float(t), z, self.final_time(t))

    def gain(self, t: float, z: Any) -> tuple[Array, Array]:
        """G = ∂J/∂z(z̄) W B (N, m, r) and J(z̄) (N, m).

        Parameters
        ----------
        t : float
            Current time [s].
        z : array_like, shape (n,) or (N, n)
            Current states.

        Returns
        -------
        G : numpy.ndarray, shape (N, m, r)
            Gain ∂J/∂z(z̄) W B.
        J : numpy.ndarray, shape (N, m)
            Criterion at the predicted final state, J(z̄).
        """
        z = np.atleast_2d(as_float_array("z", z))
        zbar, W = self.predict(t, z)
        G = self._dJ(zbar) @ W @ self._B(t, z)
        return G, self._J(zbar)

    def control(self, t: float, z: Any, target: Any) -> Array:
        """u = G⁺ (J* − J(z̄))/T_u for a batch of states ``z`` (N, n) → (N, r).

        ``target`` J* broadcasts against (N, m). Where G Gᵀ is singular the Moore-Penrose
        pseudo-inverse gives the least-norm least-squares control.

        Parameters
        ----------
        t : float
            Current time [s].
        z : array_like, shape (n,) or (N, n)
            Current states.
        target : array_like
            Wanted criterion value J*, broadcast against (N, m).

        Returns
        -------
        numpy.ndarray, shape (N, r)
            Control u.
        """
        z = np.atleast_2d(as_float_array("z", z))
        G, Jbar = self.gain(t, z)
        target = np.broadcast_to(as_float_array("target", target), Jbar.shape)
        fJ = (target - Jbar) / self.time_constant
        return np.einsum("nrm,nm->nr", np.linalg.pinv(G), fJ)


def simulate_final_state(
    ctrl: FinalStateController,
    z0: Any,
    target: Any | Callable[[float], Any],
    *,
    t_final: float,
    dt: float,
    control_every: int = 1,
) -> tuple[Array, Array, Array]:
    """Closed loop dz/dt = Φ + B u with u from ``ctrl`` (zero-order hold), numpy.

    Integrated with ``ctrl.integrator`` (default RK4).

    Returns ``(t, z, u)`` with shapes (steps+1,), (N, steps+1, n), (N, steps+1, r)
    (the last u repeats the previous one). A reference implementation for tests; the engine
    runs the compiled controllers.

    Parameters
    ----------
    ctrl : FinalStateController
        The controller.
    z0 : array_like, shape (n,) or (N, n)
        Initial states.
    target : array_like or callable(t)
        Target J* of the criterion, constant or a function of time [s].
    t_final : float
        Duration [s] (> 0).
    dt : float
        Integration step [s] (> 0).
    control_every : int, optional
        Control update every this many steps (default 1).
    """
    check_positive("dt", dt, "s")
    check_positive("t_final", t_final, "s")
    z = np.atleast_2d(as_float_array("z0", z0)).copy()
    n_steps = int(round(t_final / dt))
    t = np.arange(n_steps + 1) * dt
    zs = np.empty((z.shape[0], n_steps + 1, z.shape[1]))
    us: list[Array] = []

    def rhs(s: float, zz: Array, u: Array) -> Array:
        return ctrl.drift(s, zz) + np.einsum("nij,nj->ni", ctrl._B(s, zz), u)

    u = None
    for k in range(n_steps):
        zs[:, k] = z
        tk = t[k]
        if k % control_every == 0 or u is None:
            tgt = target(tk) if callable(target) else target
            u = ctrl.control(tk, z, tgt)
        us.append(u)
        z = rk_step(ctrl.integrator, rhs, tk, z, dt, u)
    zs[:, -1] = z
    us.append(us[-1])
    return t, zs, np.stack(us, axis=1)
