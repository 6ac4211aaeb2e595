"""The posterior of an identified Nomoto model, and the ships it stands for.

:func:`posterior_samples` draws parameter sets (K, T or K, T_1, T_2, T_3, and δ_0) given the
records:

``"laplace"`` (default)
    The Gaussian of the output-error fit (mean the estimate, covariance its Laplace covariance),
    truncated to the models' range (K, T > 0, T_3 ≥ 0) by rejection.
``"mcmc"``
    An affine-invariant ensemble sampler (Goodman & Weare 2010; the ``emcee`` package, the
    optional extra ``seahelm[mcmc]``) on the likelihood of the records' residuals, white
    Gaussian with the fit's residual σ, flat priors on the models' range; the records' initial
    states are sampled too (they correlate with K), and only the model parameters are
    returned. Its walkers are **one batched engine run per step**
    (``vectorize=True``): the whole ensemble is simulated together. Chosen because it needs no
    gradient and no tuning beyond the number of walkers, and its moves are invariant to the
    strong K–T correlation of zig-zag records.

:func:`posterior_ships` turns samples into ships (for
:func:`~seahelm.analysis.imo.probability.imo_probabilities`: the probability of passing the
IMO criteria given the identification).

References
----------
Goodman, J., Weare, J. (2010). Ensemble samplers with affine invariance. Commun. Appl. Math.
Comput. Sci. 5(1), 65–80.
Foreman-Mackey, D., Hogg, D.W., Lang, D., Goodman, J. (2013). emcee: the MCMC hammer. PASP
125(925), 306–312.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError
from .nomoto_fit import _measured, simulate_records
from .nomoto_fit_result import NomotoFit
from .records import ManoeuvreRecord

__all__ = ["posterior_samples", "posterior_ships", "POSTERIOR_METHODS"]

POSTERIOR_METHODS = ("laplace", "mcmc")


def _admissible(fit: NomotoFit, thetas: np.ndarray) -> np.ndarray:
    ok = np.all(thetas[:, :fit.order + 1] > 0, axis=1)
    if fit.order == 2:
        ok &= thetas[:, 3] >= 0
    return ok & np.all(np.isfinite(thetas), axis=1)


def posterior_samples(fit: NomotoFit, records: Sequence[ManoeuvreRecord] | None = None, *,
                      n: int = 200, method: str = "laplace", seed: int | None = None,
                      walkers: int = 32, burn: int = 200) -> np.ndarray:
    """Parameter sets drawn from the posterior (module docstring).

    Parameters
    ----------
    fit : NomotoFit
    records : sequence of ManoeuvreRecord, optional
        The records fitted (needed for ``"mcmc"``).
    n : int
        Samples returned.
    method : {"laplace", "mcmc"}
    seed : int, optional
    walkers : int, optional
        MCMC walkers (even, ≥ twice the parameters with the records' initial states).
    burn : int, optional
        MCMC steps discarded first.

    Returns
    -------
    ndarray, shape (n, parameters)
    """
    if method not in POSTERIOR_METHODS:
        raise ParameterError(f"must be one of {', '.join(POSTERIOR_METHODS)}, got {method!r}",
                             field="method")
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ParameterError(f"must be a whole number >= 1, got {n!r}", field="n", value=n)
    rng = np.random.default_rng(seed)
    if method == "laplace":
        out = np.empty((0, fit.values.size))
        for _ in range(100):
            draw = rng.multivariate_normal(fit.values, fit.covariance, size=2 * n,
                                           method="svd")
            out = np.vstack([out, draw[_admissible(fit, draw)]])
            if len(out) >= n:
                return out[:n]
        raise ParameterError("the Laplace posterior lies mostly outside the model's range "
                             "(K, T > 0): the records do not identify the model", field="fit")
    return _mcmc(fit, records, n, rng, walkers, burn)


def _mcmc(fit: NomotoFit, records: Sequence[ManoeuvreRecord] | None, n: int, rng: Any,
          walkers: int, burn: int) -> np.ndarray:
    from .._optional import optional_import

    emcee = optional_import("emcee", extra="mcmc", purpose="MCMC posteriors")
    if not records:
        raise ParameterError("the records are needed for an MCMC posterior", field="records")
    recs = list(records)
    if tuple(r.name for r in recs) != fit.records:
        raise ParameterError("these are not the records of the fit", field="records")
    n_model = fit.values.size
    n_init = fit.initial_states.shape[1]
    ndim = n_model + n_init * len(recs)
    if walkers < 2 * ndim or walkers % 2:
        raise ParameterError(f"must be even and >= {2 * ndim} (twice the parameters with "
                             f"the records' initial states), got {walkers!r}",
                             field="walkers", value=walkers)
    sigma = fit.residual_std
    measured = [_measured(r, fit.output) for r in recs]

    def log_prob(points: np.ndarray) -> np.ndarray:
        points = np.atleast_2d(points)
        lp = np.full(points.shape[0], -np.inf)
        ok = _admissible(fit, points[:, :n_model])
        if not ok.any():
            return lp
        good = points[ok]
        total = np.zeros(good.shape[0])
        for k, (rec, m) in enumerate(zip(recs, measured)):
            inits = good[:, n_model + k * n_init:n_model + (k + 1) * n_init]
            y = simulate_records(fit.order, good[:, :n_model], inits, rec, fit.output)
            total += -0.5 * np.sum(((m[None] - y) / sigma) ** 2, axis=1)
        lp[ok] = np.where(np.isfinite(total), total, -np.inf)
        return lp

    model = posterior_samples(fit, n=walkers, method="laplace",
                              seed=int(rng.integers(2 ** 31)))
    inits = fit.initial_states.ravel()[None] * (1 + 1e-4 * rng.standard_normal(
        (walkers, n_init * len(recs)))) + 1e-6 * rng.standard_normal((walkers, n_init * len(recs)))
    start = np.hstack([model, inits])
    steps = burn + int(math.ceil(n / walkers)) * 5
    sampler = emcee.EnsembleSampler(walkers, ndim, log_prob, vectorize=True)
    sampler.random_state = np.random.RandomState(int(rng.integers(2 ** 31))).get_state()
    sampler.run_mcmc(start, steps, progress=False)
    chain = sampler.get_chain(discard=burn, thin=5, flat=True)
    return chain[-n:, :n_model]


def posterior_ships(fit: NomotoFit, samples: np.ndarray, *, name: str, speed: float,
                    length: float, max_rudder: float = math.radians(35.0),
                    rudder_rate: float = math.radians(65.0 / 28.0)) -> list[Any]:
    """One ship per posterior sample (the model of the fit with the sample's K, T …).

    Parameters
    ----------
    fit : NomotoFit
    samples : ndarray, shape (n, parameters)
    name : str
    speed, length : float
        U [m/s], L [m].
    max_rudder, rudder_rate : float, optional
        The steering gear [rad], [rad/s].

    Returns
    -------
    list of Ship
    """
    from ..actuators.servo import ServoParams
    from ..ships import Ship, SteeringGear
    from ..vessels.nomoto import Nomoto1Params, Nomoto2Params

    gear = SteeringGear(actuator="rudder-servo", params=ServoParams(
        max_angle=max_rudder, max_rate=rudder_rate, time_constant=1.0))
    ships = []
    for i, th in enumerate(np.asarray(samples, dtype=float)):
        if fit.order == 1:
            p: Any = Nomoto1Params(gain=th[0], time_constant=th[1], speed=speed, length=length)
        else:
            p = Nomoto2Params(gain=th[0], t1=th[1], t2=th[2], t3=th[3], speed=speed,
                              length=length)
        ships.append(Ship(name=f"{name} #{i}", model=f"nomoto{fit.order}", params=p,
                          steering_gear=gear, provenance="posterior sample"))
    return ships
