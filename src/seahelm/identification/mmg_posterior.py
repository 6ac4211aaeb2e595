"""The posterior of identified MMG hull derivatives, and the ships it stands for.

:func:`mmg_posterior` draws the hull derivatives of an :class:`~seahelm.identification.mmg_fit.HullFit`
given the records:

``"laplace"`` (default)
    The Gaussian of the fit: mean the estimate, covariance its Laplace covariance — for an
    output-error fit (:func:`~seahelm.identification.mmg_fit.refine_mmg`) σ² (JᵀJ)⁻¹, the inverse of
    the Gauss–Newton Hessian JᵀJ/σ² of the scaled u, v, r residuals with σ² their mean square
    over the degrees of freedom; for a regression-only fit the regression's covariance. The
    draws are truncated to the prior's support (below) by rejection.
``"mcmc"``
    An affine-invariant ensemble sampler (Goodman & Weare 2010; ``emcee``, the optional extra
    ``seahelm[mcmc]``). The likelihood is that of the output-error fit: the records simulated
    from their recorded δ and n and initial u, v, r, the residuals of u, v, r scaled by U_0,
    U_0 and U_0/L (the residual of :func:`~seahelm.identification.mmg_fit.refine_mmg`) white Gaussian
    with the σ of the residuals at the estimate. ``vectorize=True``: each half of the ensemble
    that the stretch move updates is **one batched engine run** per record (emcee moves the
    walkers in two halves, so a step is two runs of walkers/2 ships). The walkers start from
    Laplace draws; ``burn`` steps are discarded and the chain thinned by ``thin``; the
    acceptance fraction and the integrated autocorrelation time (emcee's
    ``get_autocorr_time(quiet=True)``, a warning, not an error, when the chain is shorter
    than 50 τ) are returned with the samples.

**Prior** (both methods): flat on the physical range — the resistance R'_0 > 0 and the
damping derivatives Y'_v < 0, N'_r < 0 — and zero outside; every other derivative is free.

**What the records do not identify is not sampled.** The derivatives a fit holds at the base
ship's values (:attr:`HullFit.fixed`, from :func:`~seahelm.identification.mmg_fit.identify_mmg`) stay
at them in every sample and are listed in :attr:`MMGPosterior.fixed`. A fit whose covariance
still has an unidentified parameter or a (numerically) singular direction — the smallest
eigenvalue of the correlation matrix below 1e-10 — is refused with that direction named, rather
than sampled as if it were known.

:func:`posterior_ships` turns samples into ships (the base ship with a sample's derivatives) for
:func:`~seahelm.analysis.imo.probability.imo_probabilities`: the probability of passing each
IMO criterion given the identification.

References
----------
Goodman, J., Weare, J. (2010). Ensemble samplers with affine invariance. Commun. Appl. Math.
Comput. Sci. 5(1), 65–80.
Foreman-Mackey, D., Hogg, D.W., Lang, D., Goodman, J. (2013). emcee: the MCMC hammer. PASP
125(925), 306–312.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError
from .mmg_fit import HULL_TERMS, HullFit, _scaled_outputs, _simulate
from .records import ManoeuvreRecord

__all__ = ["MMGPosterior", "mmg_posterior", "posterior_ships", "posterior_columns",
           "output_error_log_likelihood",
           "admissible", "POSTERIOR_METHODS", "PRIOR_SIGNS"]

POSTERIOR_METHODS = ("laplace", "mcmc")

#: The prior's support: these derivatives keep their physical sign (+1: > 0, −1: < 0).
PRIOR_SIGNS = {"R_0": 1.0, "Y_v": -1.0, "N_r": -1.0}

#: The smallest eigenvalue of the correlation matrix below which a direction is singular.
SINGULAR_EIGENVALUE = 1e-10


@dataclasses.dataclass(frozen=True)
class MMGPosterior:
    """Samples of the hull derivatives given the records.

    Attributes
    ----------
    names : tuple of str
        The sampled derivatives.
    samples : ndarray, shape (n, len(names))
    method : str
        ``"laplace"`` or ``"mcmc"``.
    fixed : dict of str to str
        Derivatives held at the base ship's values (not sampled), with the evidence.
    acceptance_fraction : float or None
        Mean acceptance fraction of the walkers (MCMC).
    autocorr_time : ndarray or None
        Integrated autocorrelation time of each derivative [steps] (MCMC).
    walkers, steps, burn, thin : int or None
        The MCMC settings (steps including the burn-in).
    """

    names: tuple[str, ...]
    samples: np.ndarray
    method: str
    fixed: dict[str, str]
    acceptance_fraction: float | None = None
    autocorr_time: np.ndarray | None = None
    walkers: int | None = None
    steps: int | None = None
    burn: int | None = None
    thin: int | None = None

    def as_dict(self) -> dict[str, Any]:
        """The settings and diagnostics, the sample means and standard deviations (for JSON).

        Returns
        -------
        dict
        """
        out: dict[str, Any] = {
            "method": self.method, "samples": int(self.samples.shape[0]),
            "mean": dict(zip(self.names, map(float, self.samples.mean(axis=0)))),
            "std": dict(zip(self.names, map(float, self.samples.std(axis=0, ddof=1)
                                             if len(self.samples) > 1 else
                                             np.zeros(len(self.names))))),
            "fixed_at_base": dict(self.fixed)}
        if self.method == "mcmc":
            tau = self.autocorr_time
            out.update(walkers=self.walkers, steps=self.steps, burn=self.burn, thin=self.thin,
                       acceptance_fraction=self.acceptance_fraction,
                       autocorr_time=None if tau is None else dict(zip(self.names,
                                                                       map(float, tau))))
        return out


def admissible(names: Sequence[str], thetas: np.ndarray) -> np.ndarray:
    """Which parameter sets lie in the prior's support (:data:`PRIOR_SIGNS`, all finite).

    Parameters
    ----------
    names : sequence of str
        The derivatives, the columns of ``thetas``.
    thetas : ndarray, shape (n, len(names))

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    thetas = np.atleast_2d(thetas)
    ok = np.all(np.isfinite(thetas), axis=1)
    for j, name in enumerate(names):
        if name in PRIOR_SIGNS:
            ok &= PRIOR_SIGNS[name] * thetas[:, j] > 0
    return ok


def _check_identified(fit: HullFit) -> None:
    bad = fit.unidentifiable()
    if bad:
        raise ParameterError(
            "the records do not identify " + "; ".join(f"{k} ({v})" for k, v in bad.items())
            + ": no posterior to sample them from (identify_mmg holds them at the base ship's "
            "values)", field="fit")
    se = fit.standard_errors
    corr = fit.covariance / np.outer(se, se)
    w, vecs = np.linalg.eigh(corr)
    if w[0] < SINGULAR_EIGENVALUE * max(w[-1], 1.0):
        v = vecs[:, 0]
        top = np.argsort(-np.abs(v))[:4]
        direction = " ".join(f"{v[i]:+.3f}·{fit.names[i]}" for i in top)
        raise ParameterError(f"the covariance is singular along {direction} (scaled; "
                             f"eigenvalue {w[0]:.2g}): the records do not identify that "
                             "combination; fit fewer derivatives", field="fit")


def output_error_log_likelihood(fit: HullFit, records: Sequence[ManoeuvreRecord]) -> Any:
    """The log-likelihood of the records as a function of a batch of derivative sets.

    Parameters
    ----------
    fit : HullFit
        Gives the derivatives' names, the base parameters and σ (the mean square of the
        scaled residuals at :attr:`HullFit.values` over their degrees of freedom).
    records : sequence of ManoeuvreRecord
        The records fitted.

    Returns
    -------
    callable
        ``f(thetas)``: thetas, shape (walkers, len(names)), to log-likelihoods, shape
        (walkers,); −inf where a run does not complete. Attribute ``sigma``: σ.
    """
    recs = list(records)
    names = fit.names
    base = fit.params
    scales, measured = _scaled_outputs(recs, base.length)
    targets = [m / scales[:, None] for m in measured]

    def sse(thetas: np.ndarray) -> np.ndarray:
        params = [base.replace(**{n: float(x) for n, x in zip(names, th)}) for th in thetas]
        total = np.zeros(len(params))
        for rec, target in zip(recs, targets):
            y = _simulate(params, rec) / scales[None, :, None]
            total += np.sum((target[None] - y) ** 2, axis=(1, 2))
        return np.where(np.isfinite(total), total, np.inf)

    n_obs = sum(t.size for t in targets)
    sigma2 = float(sse(np.asarray(fit.values)[None])[0]) / max(n_obs - len(names), 1)
    if not math.isfinite(sigma2) or sigma2 <= 0:
        raise ParameterError("the fit's own simulation of the records does not complete",
                             field="fit")

    def log_likelihood(thetas: np.ndarray) -> np.ndarray:
        return -0.5 * sse(np.atleast_2d(thetas)) / sigma2

    log_likelihood.sigma = math.sqrt(sigma2)  # type: ignore[attr-defined]
    return log_likelihood


def _laplace_draws(fit: HullFit, n: int, rng: Any) -> np.ndarray:
    out = np.empty((0, fit.values.size))
    for _ in range(100):
        draw = rng.multivariate_normal(fit.values, fit.covariance, size=2 * n, method="svd")
        out = np.vstack([out, draw[admissible(fit.names, draw)]])
        if len(out) >= n:
            return out[:n]
    raise ParameterError("the Laplace posterior lies mostly outside the prior's support "
                         "(R_0 > 0, Y_v < 0, N_r < 0)", field="fit")


def mmg_posterior(fit: HullFit, records: Sequence[ManoeuvreRecord] | None = None, *,
                  n: int = 200, method: str = "laplace", seed: int | None = None,
                  walkers: int | None = None, burn: int = 300, thin: int = 5) -> MMGPosterior:
    """Hull derivatives drawn from the posterior given the records (module docstring).

    Parameters
    ----------
    fit : HullFit
        An MMG identification (:func:`~seahelm.identification.mmg_fit.identify_mmg`).
    records : sequence of ManoeuvreRecord, optional
        The records fitted (needed for ``"mcmc"``).
    n : int
        Samples returned.
    method : {"laplace", "mcmc"}
    seed : int, optional
    walkers : int, optional
        MCMC walkers: even and ≥ twice the derivatives (default the smallest even number ≥
        2 × derivatives + 2).
    burn : int, optional
        MCMC steps discarded first.
    thin : int, optional
        Every ``thin``-th MCMC step kept after the burn-in.

    Returns
    -------
    MMGPosterior
    """
    if method not in POSTERIOR_METHODS:
        raise ParameterError(f"must be one of {', '.join(POSTERIOR_METHODS)}, got {method!r}",
                             field="method")
    for key, value, low in (("n", n, 1), ("burn", burn, 0), ("thin", thin, 1)):
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ParameterError(f"must be a whole number >= {low}, got {value!r}", field=key,
                                 value=value)
    _check_identified(fit)
    rng = np.random.default_rng(seed)
    if method == "laplace":
        return MMGPosterior(names=fit.names, samples=_laplace_draws(fit, n, rng),
                            method="laplace", fixed=dict(fit.fixed))
    return _mcmc(fit, records, n, rng, walkers, burn, thin)


def _mcmc(fit: HullFit, records: Sequence[ManoeuvreRecord] | None, n: int, rng: Any,
          walkers: int | None, burn: int, thin: int) -> MMGPosterior:
    from .._optional import optional_import

    emcee = optional_import("emcee", extra="mcmc", purpose="MCMC posteriors")
    if not records:
        raise ParameterError("the records are needed for an MCMC posterior", field="records")
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    if tuple(r.name for r in recs) != fit.records:
        raise ParameterError("these are not the records of the fit", field="records")
    ndim = fit.values.size
    if walkers is None:
        walkers = 2 * ndim + 2
    if isinstance(walkers, bool) or not isinstance(walkers, int) or walkers < 2 * ndim \
            or walkers % 2:
        raise ParameterError(f"must be even and >= {2 * ndim} (twice the derivatives), got "
                             f"{walkers!r}", field="walkers", value=walkers)
    log_likelihood = output_error_log_likelihood(fit, recs)
    names = fit.names

    def log_prob(points: np.ndarray) -> np.ndarray:
        points = np.atleast_2d(points)
        lp = np.full(points.shape[0], -np.inf)
        ok = admissible(names, points)
        if ok.any():
            lp[ok] = log_likelihood(points[ok])
        return lp

    start = _laplace_draws(fit, walkers, rng)
    steps = burn + int(math.ceil(n / walkers)) * thin
    sampler = emcee.EnsembleSampler(walkers, ndim, log_prob, vectorize=True)
    sampler.random_state = np.random.RandomState(int(rng.integers(2 ** 31))).get_state()
    sampler.run_mcmc(start, steps, progress=False)
    chain = sampler.get_chain(discard=burn, thin=thin, flat=True)
    with np.errstate(invalid="ignore", divide="ignore"):  # (a constant chain: τ is NaN)
        tau = sampler.get_autocorr_time(quiet=True, discard=burn) if steps > burn else None
    return MMGPosterior(names=names, samples=chain[-n:], method="mcmc", fixed=dict(fit.fixed),
                        acceptance_fraction=float(np.mean(sampler.acceptance_fraction)),
                        autocorr_time=tau, walkers=walkers, steps=steps, burn=burn, thin=thin)


def posterior_columns(fit: HullFit, samples: np.ndarray | MMGPosterior
                      ) -> dict[str, np.ndarray]:
    """Every hull derivative of the posterior ships, by key path (``vessel.params.<name>``):
    the sampled ones from the samples, the others at the fit's values (the fixed ones at the
    base ship's) — the columns of a samples file (:mod:`seahelm.identification.samples_file`) whose
    rows, put into the base ship, are the ships of :func:`posterior_ships`.

    Parameters
    ----------
    fit : HullFit
        Names the sampled derivatives.
    samples : ndarray, shape (n, len(fit.names)), or MMGPosterior

    Returns
    -------
    dict of str to ndarray, shape (n,)
    """
    if isinstance(samples, MMGPosterior):
        samples = samples.samples
    samples = np.atleast_2d(np.asarray(samples, dtype=float))
    if samples.shape[1] != len(fit.names):
        raise ParameterError(f"samples have {samples.shape[1]} columns, the fit "
                             f"{len(fit.names)} derivatives", field="samples")
    n = samples.shape[0]
    out = {}
    for name in (name for terms in HULL_TERMS.values() for name, _ in terms):
        out[f"vessel.params.{name}"] = (samples[:, fit.names.index(name)].copy()
                                        if name in fit.names else
                                        np.full(n, float(getattr(fit.params, name))))
    return out


def posterior_ships(fit: HullFit, samples: np.ndarray | MMGPosterior, base: Any, *,
                    name: str = "posterior") -> list[Any]:
    """One ship per posterior sample: ``base`` with the sample's hull derivatives (the other
    hull derivatives at the fit's values: the fixed ones at the base ship's;
    :func:`posterior_columns`).

    Parameters
    ----------
    fit : HullFit
        Names the sampled derivatives.
    samples : ndarray, shape (n, len(fit.names)), or MMGPosterior
    base : Ship
        The MMG ship of the identification (masses, propeller, rudder, steering gear).
    name : str, optional
        The ships are named ``"<name> #<i>"``.

    Returns
    -------
    list of Ship
    """
    columns = posterior_columns(fit, samples)
    prefix = len("vessel.params.")
    n = len(next(iter(columns.values())))
    return [base.replace(name=f"{name} #{i}",
                         params={k[prefix:]: float(v[i]) for k, v in columns.items()},
                         provenance=f"posterior sample {i} of the hull derivatives identified "
                                    f"from {', '.join(fit.records)}; the rest of '{base.name}'")
            for i in range(n)]
