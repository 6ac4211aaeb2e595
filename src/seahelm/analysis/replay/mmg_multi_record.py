"""Output-error identification of a low-speed MMG ship (``mmg-ls``) from many measured records.

:func:`fit_mmg_ls` identifies chosen coefficients of an ``mmg-ls`` ship (the Esso Osaka 3 m
model of Miyauchi et al. 2022, catalog ship ``esso-osaka-3m``, is the start) from free-running
records that log position, heading, u, v, r, δ and n — and, as a *known input*, the measured
true wind (``wind="measured"``: the records' ``true_wind_speed`` and ``true_wind_direction``).

**Segments (multiple shooting).** Every record is cut into segments of ``segment`` seconds
(default 60 s, the window of the replay's early position error,
:data:`~seahelm.analysis.replay.simulate.RMS_WINDOW`); each segment is simulated from the *measured*
state at its start (u, v, r, position, heading: each the value of a quadratic fitted to the
samples within 1 s of the start, so that one sample's noise is not all of the initial-state
error) with the measured δ and n (first-order hold onto the integration grid) and the
measured wind (its speed a time series through the wind load model's ``wind_gust`` channel,
its direction held at the segment's circular mean — the engine's wind direction is a
parameter). One output-error simulation of a whole 10-min random record drifts so far that
the cost is not smooth in the coefficients; a minute is what the test files are judged on.
All segments of all records, and all parameter sets a Jacobian needs, are **one batched
engine run** (:mod:`seahelm.analysis.replay.segments`).

**Residuals** at every ``sample`` seconds of each segment: the position error over L (north,
east), the heading error [rad], and u, v, r over U_0, U_0, U_0/L (U_0 the records' mean speed)
— the first two are what the test figures (RMS position error) measure, the last three keep the
velocities. Diverged runs give residuals of 10.

**Fit.** Trust-region least squares (``scipy.optimize.least_squares``, ``trf``) within each
coefficient's admissible range (its :class:`~seahelm.parameters.Params` bounds); the
Jacobian J is forward differences, one batched run.

**Intervals.** The Laplace covariance σ² (JᵀJ)⁻¹, σ² the residuals' mean square over the
degrees of freedom, treats the residuals as independent and the initial states as exact;
neither holds. The *stated* covariance (:attr:`MultiRecordFit.stated_covariance`) is the
Laplace one times (1 + ρ)/(1 − ρ), ρ the residuals' mean lag-1 autocorrelation within the
segments (the variance inflation of an AR(1) series; at most the samples per segment), plus
the first-order effect of the initial states' errors: A (Σ σ_{s,k}² d_{s,k} d_{s,k}ᵀ) Aᵀ with
A = (JᵀJ)⁻¹Jᵀ, σ_{s,k} the standard error of state k of segment s (of its quadratic fit) and
d_{s,k} the residuals' sensitivity to it (six more batched runs: a segment's residuals depend
on its own start only, so one state of every segment is perturbed at once). Model error
(the published model's form) is in neither.

Coefficients whose standard error exceeds their magnitude, or whose correlation with another
exceeds 0.999, are set back to the start ship's values and the rest fitted again (at most
``max_rounds`` times), as :func:`~seahelm.identification.mmg_fit.identify_mmg` does for the ``mmg``
hull.

References
----------
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083.
Wakita, K. et al. (2022). On neural network identification for low-speed ship maneuvering
model. J. Mar. Sci. Technol. 27, 772–785 (the train/test split of the records).
Bock, H.G., Plitt, K.J. (1984). A multiple shooting algorithm for direct solution of optimal
control problems. Proc. 9th IFAC World Congress, 242–247 (segments from measured states).
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...identification.fit_result import FitResult
from .segments import (
    OUTPUTS,
    RECORD_CHANNELS,
    Segments,
    build_segments,
    residuals,
    simulate_segments,
)
from ...identification.records import ManoeuvreRecord

__all__ = ["FREE_DEFAULT", "OUTPUTS", "MultiRecordFit", "Segments", "build_segments",
           "simulate_segments", "fit_mmg_ls", "laplace_samples", "RECORD_CHANNELS"]

#: The coefficients freed by default, the ones that set the turning (module docstring of
#: :mod:`seahelm.vessels.mmg_low_speed`): the linear sway/yaw hull derivatives, the cross-flow
#: yaw-rate factors, the rudder's inflow (ε: u_R, so F_N ∝ u_R²) and flow straightening (γ_N,
#: γ_P: v_R, the inflow angle in a turn), the rudder–hull interaction a_H, and the straight-run
#: resistance X'_0F (the speed, hence the distance run in a minute).
FREE_DEFAULT = ("X_0F", "Y_v", "Y_r", "N_v", "N_r", "C_rY", "C_rN", "epsilon", "gamma_N",
                "gamma_P", "a_H")

@dataclasses.dataclass(frozen=True)
class MultiRecordFit(FitResult):
    """Coefficients of an ``mmg-ls`` ship identified from many records (:func:`fit_mmg_ls`).

    Attributes
    ----------
    names : tuple of str
    values, covariance : ndarray
        Estimates and their Laplace covariance (independent residuals: see
        :attr:`inflation`).
    start : dict of str to float
        The start ship's values of ``names``.
    records : tuple of str
    segments : int
        Segments fitted.
    segment, sample : float
        Segment length and sampling interval [s].
    wind : str
    rms_start, rms_fit : float
        RMS of the scaled residuals at the start and at the estimate.
    inflation : float
        (1 + ρ)/(1 − ρ), ρ the residuals' mean lag-1 autocorrelation within segments: how much
        the independent-residual variance understates an AR(1) one; at most the samples per
        segment (each segment's series then counts as one sample).
    condition_number : float
        Of JᵀJ (column-scaled).
    initial_state_covariance : ndarray or None
        The coefficients' covariance from the errors of the segments' measured initial
        states (:attr:`Segments.x0_std`), to first order (module docstring).
    fixed : dict of str to str
        Coefficients set back to the start values, with the evidence.
    params : MMGLowSpeedParams
        The start ship's parameters with the estimates.
    evaluations : int
    seconds : float
        Wall time of the fit.
    """

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    start: dict[str, float]
    records: tuple[str, ...]
    segments: int
    segment: float
    sample: float
    wind: str
    rms_start: float
    rms_fit: float
    inflation: float
    condition_number: float
    fixed: dict[str, str]
    params: Any
    evaluations: int
    seconds: float
    initial_state_covariance: np.ndarray | None = None

    @property
    def stated_covariance(self) -> np.ndarray:
        """The covariance the stated intervals are of: the Laplace covariance times
        :attr:`inflation`, plus :attr:`initial_state_covariance` (the segments' initial states
        are measured, with errors the fit passes on to the coefficients)."""
        extra = 0.0 if self.initial_state_covariance is None else self.initial_state_covariance
        return self.covariance * self.inflation + extra

    @property
    def stated_errors(self) -> np.ndarray:
        """Standard errors of the stated intervals (:attr:`stated_covariance`)."""
        return np.sqrt(np.diag(self.stated_covariance))

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON).

        Returns
        -------
        dict
        """
        rows = self.parameter_rows()
        stated = dict(zip(self.names, self.stated_errors))
        for row in rows:
            row["start"] = self.start[row["name"]]
            row["stated_error"] = float(stated[row["name"]])
        rows += [{"name": n, "identified": False, "fixed_at_base": True, "evidence": why}
                 for n, why in self.fixed.items()]
        return {"method": "output-error (segments)", "records": list(self.records),
                "segments": self.segments, "segment_s": self.segment, "sample_s": self.sample,
                "wind": self.wind, "parameters": rows, "rms_start": self.rms_start,
                "rms_fit": self.rms_fit, "autocorrelation_inflation": self.inflation,
                "condition_number": self.condition_number, "evaluations": self.evaluations,
                "seconds": self.seconds,
                "correlation": np.round(self.correlation, 6).tolist()}

    def ship(self, base: Any, *, name: str | None = None) -> Any:
        """``base`` with the identified coefficients, each with its source.

        Parameters
        ----------
        base : Ship
            The start ship.
        name : str, optional
            Default ``"<base>-identified"``.

        Returns
        -------
        Ship
        """
        n_rec = len(self.records)
        sources = dict(base.coefficient_sources)
        stated = self.stated_errors
        for i, n in enumerate(self.names):
            sources[n] = (f"output-error fit ({self.segments} segments of {self.segment:g} s, "
                          f"wind {self.wind}) to {n_rec} record(s): {self.values[i]:.6g} ± "
                          f"{stated[i]:.3g} (standard error: Laplace x {self.inflation:.3g} "
                          "for correlated residuals, plus initial-state errors); start "
                          f"{self.start[n]:.6g} ('{base.name}')")
        for n, why in self.fixed.items():
            sources[n] = f"not identified ({why}): kept at '{base.name}''s value. " + \
                base.source_of(n)
        return base.replace(
            name=name or f"{base.name}-identified",
            params={n: float(v) for n, v in zip(self.names, self.values)},
            coefficient_sources=tuple(sources.items()),
            description=f"{base.description} — {len(self.names)} coefficients identified "
                        f"from {n_rec} record(s)",
            provenance=f"{', '.join(self.names)} identified by output error over "
                       f"{self.segments} segments of {self.segment:g} s with the wind "
                       f"{self.wind} (seahelm.analysis.replay.mmg_multi_record) from "
                       f"{', '.join(self.records)}; the rest of '{base.name}': "
                       f"{base.provenance}")


def _laplace(J: np.ndarray, sigma2: float) -> tuple[np.ndarray, float]:
    """σ² (JᵀJ)⁻¹ by SVD of the column-scaled J, and the condition number of JᵀJ."""
    norms = np.linalg.norm(J, axis=0)
    norms[norms == 0] = 1.0
    _, s, Vt = np.linalg.svd(J / norms, full_matrices=False)
    with np.errstate(divide="ignore"):
        inv = np.where(s > s[0] * 1e-12, 1.0 / (s * s), np.inf)
    cond = float((s[0] / s[-1]) ** 2) if s[-1] > 0 else math.inf
    return (Vt.T * inv) @ Vt / np.outer(norms, norms) * sigma2, cond


def _lag1(res: np.ndarray, segments: Segments) -> float:
    """Mean lag-1 autocorrelation of the residual series of each segment and output."""
    keep = np.broadcast_to(segments.mask[:, None, :], segments.measured.shape)
    full = np.full(segments.measured.shape, np.nan)
    full[keep] = res
    a, b = full[..., :-1], full[..., 1:]
    ok = np.isfinite(a) & np.isfinite(b)
    num = np.sum(np.where(ok, a * b, 0.0))
    den = np.sum(np.where(ok, a * a, 0.0))
    return float(num / den) if den > 0 else 0.0


def fit_mmg_ls(records: ManoeuvreRecord | Sequence[ManoeuvreRecord], base: Any, *,
               names: Sequence[str] = FREE_DEFAULT, wind: str = "measured",
               segment: float = 60.0, sample: float = 1.0, dt: float | None = None,
               max_nfev: int = 40, max_rounds: int = 2) -> MultiRecordFit:
    """Identify ``names`` of an ``mmg-ls`` ship from many records (module docstring).

    Parameters
    ----------
    records : ManoeuvreRecord or sequence of them
    base : Ship
        The ``mmg-ls`` start ship (e.g. ``esso-osaka-3m``).
    names : sequence of str
        Coefficients to free (default :data:`FREE_DEFAULT`).
    wind : {"measured", "none"}
        The records' measured true wind as a known input, or still air.
    segment, sample : float
        Segment length and residual sampling interval [s].
    dt : float, optional
        Integration step [s] (default: :func:`build_segments`'s).
    max_nfev : int
        Most evaluations of the trust-region solver per round.
    max_rounds : int
        Most refits after setting unidentified coefficients back.

    Returns
    -------
    MultiRecordFit
    """
    from scipy.optimize import least_squares

    from ...vessels.mmg_low_speed import MMGLowSpeedParams

    if not isinstance(getattr(base, "params", None), MMGLowSpeedParams):
        model = getattr(getattr(base, "model", None), "name", type(base).__name__)
        raise ParameterError(f"must be an mmg-ls ship, got model {model}", field="ship")
    info = {i.name: i for i in MMGLowSpeedParams.info()}
    names = list(names)
    unknown = [n for n in names if n not in info or n.endswith("_model")]
    if unknown or not names:
        raise ParameterError(f"not coefficients of mmg-ls: {', '.join(unknown) or 'none'}; "
                             "e.g. " + ", ".join(FREE_DEFAULT), field="names")
    t_start = _time.perf_counter()
    recs = [records] if isinstance(records, ManoeuvreRecord) else list(records)
    segs = build_segments(recs, base, segment=segment, sample=sample, wind=wind, dt=dt)
    L = float(base.length)
    p0 = base.params
    start = {n: float(getattr(p0, n)) for n in names}
    fixed: dict[str, str] = {}
    params, evaluations, rounds = p0, 0, 0
    rms_start = math.nan
    while True:
        x0 = np.array([getattr(params, n) for n in names], dtype=float)
        lo = np.array([info[n].low for n in names], dtype=float)
        hi = np.array([info[n].high for n in names], dtype=float)
        lo = np.where(np.isfinite(lo), lo + 1e-9 * np.maximum(np.abs(x0), 1e-3), -np.inf)
        hi = np.where(np.isfinite(hi), hi - 1e-9 * np.maximum(np.abs(x0), 1e-3), np.inf)
        x0 = np.clip(x0, lo + 1e-12, hi - 1e-12)
        steps = lambda x: 1e-5 * np.maximum(np.abs(x), 1e-2)  # noqa: E731
        cache: dict[bytes, np.ndarray] = {}

        def with_values(x: np.ndarray, _p: Any = params) -> Any:
            return _p.replace(**{n: float(v) for n, v in zip(names, x)})

        def run(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            h = steps(x)
            sets = [with_values(x)] + [with_values(x + h[j] * np.eye(x.size)[j])
                                       for j in range(x.size)]
            r = residuals(simulate_segments(base, segs, sets), segs, L)
            J = (r[1:] - r[0]) / h[:, None]
            cache[x.tobytes()] = J.T
            return r[0], J.T

        def fun(x: np.ndarray) -> np.ndarray:
            return run(x)[0]

        def jac(x: np.ndarray) -> np.ndarray:
            got = cache.get(x.tobytes())
            return got if got is not None else run(x)[1]

        r0 = fun(x0)
        if rounds == 0:
            rms_start = float(np.sqrt(np.mean(r0 ** 2)))
        sol = least_squares(fun, x0, jac=jac, bounds=(lo, hi), x_scale="jac", method="trf",
                            max_nfev=max_nfev, xtol=1e-8, ftol=1e-8)
        evaluations += int(sol.nfev)
        res, J = run(sol.x)
        dof = max(res.size - sol.x.size, 1)
        sigma2 = float(res @ res) / dof
        cov, cond = _laplace(J, sigma2)
        cov_x0 = _initial_state_covariance(base, segs, with_values(sol.x), res, J, L)
        fit = MultiRecordFit(
            names=tuple(names), values=sol.x, covariance=cov, start=start,
            records=tuple(r.name for r in recs), segments=len(segs.names), segment=segment,
            sample=sample, wind=wind, rms_start=rms_start,
            rms_fit=float(np.sqrt(np.mean(res ** 2))),
            inflation=_inflation(_lag1(res, segs), segs.measured.shape[2]),
            condition_number=cond, fixed=dict(fixed), initial_state_covariance=cov_x0,
            params=with_values(sol.x), evaluations=evaluations,
            seconds=_time.perf_counter() - t_start)
        bad = fit.unidentifiable()
        if not bad or rounds >= max_rounds:
            return fit
        fixed.update(bad)
        names = [n for n in names if n not in bad]
        if not names:
            raise ParameterError("the records identify none of " + ", ".join(fixed) + ": "
                                 + "; ".join(f"{k}: {v}" for k, v in fixed.items()),
                                 field="names")
        params = fit.params.replace(**{n: float(getattr(p0, n)) for n in bad})
        rounds += 1


def _initial_state_covariance(base: Any, segs: Segments, params: Any, r0: np.ndarray,
                              J: np.ndarray, length: float) -> np.ndarray:
    """First-order covariance of the estimates from the initial-state errors (6 batched runs:
    one state of every segment perturbed at once, each segment's residuals depending on its
    own start only)."""
    keep = np.broadcast_to(segs.mask[:, None, :], segs.measured.shape)
    owner = np.broadcast_to(np.arange(len(segs.names))[:, None, None], segs.measured.shape)[keep]
    A = np.linalg.pinv(J)
    out = np.zeros((J.shape[1], J.shape[1]))
    for k in range(segs.x0.shape[1]):
        step = segs.x0_std[:, k]
        if not np.any(step > 0):
            continue
        x0 = segs.x0.copy()
        x0[:, k] += step
        r = residuals(simulate_segments(base, dataclasses.replace(segs, x0=x0), [params]),
                       segs, length)[0]
        effect = A * (r - r0)[None, :]  # σ d per residual, times A
        per_segment = np.zeros((len(segs.names), J.shape[1]))
        np.add.at(per_segment, owner, effect.T)
        out += per_segment.T @ per_segment
    return out


def _inflation(rho: float, per_segment: int) -> float:
    """(1 + ρ)/(1 − ρ), at most the samples per segment (a segment's series then counts as
    one sample)."""
    rho = min(max(rho, 0.0), 0.999999)
    return float(min((1.0 + rho) / (1.0 - rho), per_segment))


def laplace_samples(fit: MultiRecordFit, n: int, *, seed: int | None = None,
                    inflate: bool = False) -> np.ndarray:
    """Draws of the identified coefficients from the Laplace Gaussian, inside their ranges.

    Parameters
    ----------
    fit : MultiRecordFit
    n : int
        Number of draws.
    seed : int, optional
    inflate : bool
        Draw from :attr:`MultiRecordFit.stated_covariance` (the Laplace covariance inflated
        for residuals correlated in time, plus the initial-state errors) instead of the
        Laplace covariance.

    Returns
    -------
    ndarray, shape (n, len(fit.names))
        Rejected draws (outside a coefficient's admissible range) are drawn again.
    """
    from ...vessels.mmg_low_speed import MMGLowSpeedParams

    if n < 1:
        raise ParameterError(f"must be >= 1, got {n!r}", field="n")
    bad = fit.unidentifiable()
    if bad:
        raise ParameterError("not identified, cannot be sampled: " + "; ".join(
            f"{k} ({v})" for k, v in bad.items()), field="names")
    info = {i.name: i for i in MMGLowSpeedParams.info()}
    lo = np.array([info[k].low for k in fit.names])
    hi = np.array([info[k].high for k in fit.names])
    cov = fit.stated_covariance if inflate else fit.covariance
    rng = np.random.default_rng(seed)
    out = np.empty((0, len(fit.names)))
    for _ in range(100):
        x = rng.multivariate_normal(fit.values, cov, size=2 * n)
        ok = np.all((x > lo) & (x < hi), axis=1)
        out = np.vstack([out, x[ok]])
        if len(out) >= n:
            return out[:n]
    raise ParameterError(f"fewer than {n} of the draws lie in the coefficients' ranges: the "
                         "posterior is mostly outside them", field="n")
