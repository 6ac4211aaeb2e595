"""The base of every identification result (:class:`FitResult`): what a fit's covariance says
about its estimates -- standard errors, correlations, confidence intervals, and which
parameters the data do not identify. Shared by the Nomoto fit
(:class:`~seahelm.identification.nomoto_fit_result.NomotoFit`), the MMG hull
(:class:`~seahelm.identification.mmg_fit.HullFit`), the linear sway–yaw model
(:class:`~seahelm.identification.linear_fit.LinearFit`) and Romanov & Chirkova's reduced
steady-turn model (:class:`~seahelm.identification.reduced.forms.SteadyTurnFit`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import ParameterError, deprecated_names

__all__ = ["standard_errors", "correlation", "unidentifiable", "UNIDENTIFIABLE_RELATIVE_SE",
           "UNIDENTIFIABLE_CORRELATION", "FitResult"]

#: Evidence thresholds for "unidentifiable": standard error over |value|, |correlation|.
UNIDENTIFIABLE_RELATIVE_SE = 1.0
UNIDENTIFIABLE_CORRELATION = 0.999


def standard_errors(covariance: np.ndarray) -> np.ndarray:
    """√diag of a covariance matrix (negative round-off clipped to 0).

    Parameters
    ----------
    covariance : ndarray, shape (n, n)

    Returns
    -------
    ndarray, shape (n,)
    """
    return np.sqrt(np.clip(np.diag(covariance), 0.0, None))


def correlation(covariance: np.ndarray) -> np.ndarray:
    """The correlation matrix of a covariance matrix (NaN where a variance is 0).

    Parameters
    ----------
    covariance : ndarray, shape (n, n)

    Returns
    -------
    ndarray, shape (n, n)
    """
    se = standard_errors(covariance)
    with np.errstate(invalid="ignore", divide="ignore"):
        return covariance / np.outer(se, se)


def unidentifiable(names: Sequence[str], values: np.ndarray, covariance: np.ndarray, *,
                   units: Mapping[str, str] | None = None,
                   value_test_exempt: Sequence[str] = ()) -> dict[str, str]:
    """The parameters the data do not identify, each with the evidence: a standard error above
    :data:`UNIDENTIFIABLE_RELATIVE_SE` times |value|, or a correlation above
    :data:`UNIDENTIFIABLE_CORRELATION` with another parameter.

    Parameters
    ----------
    names : sequence of str
    values : ndarray
        The estimates.
    covariance : ndarray
        Their covariance.
    units : mapping, optional
        Units to name in the evidence.
    value_test_exempt : sequence of str, optional
        Parameters whose value may be near zero (an offset): only the correlation test.

    Returns
    -------
    dict of str to str
    """
    se, corr = standard_errors(covariance), correlation(covariance)
    units = units or {}
    out: dict[str, str] = {}
    for i, name in enumerate(names):
        why = []
        value = abs(float(values[i]))
        if name not in value_test_exempt and (not np.isfinite(se[i])
                                              or se[i] > UNIDENTIFIABLE_RELATIVE_SE * value):
            unit = f" {units[name]}" if units.get(name) else ""
            why.append(f"standard error {se[i]:.3g}{unit} exceeds the value {value:.3g}")
        others = [(abs(corr[i, j]), names[j]) for j in range(len(names))
                  if j != i and np.isfinite(corr[i, j])]
        worst = max(others, default=(0.0, ""))
        if worst[0] > UNIDENTIFIABLE_CORRELATION:
            why.append(f"correlation {worst[0]:.4f} with {worst[1]}")
        if why:
            out[name] = "; ".join(why)
    return out


class FitResult:
    """What a fit result with ``names``, ``values`` and ``covariance`` says of its estimates (the
    base of the identification results: Nomoto, MMG hull, linear sway–yaw, reduced steady
    turn).

    A subclass holds (or computes) ``names``, ``values`` and ``covariance``, and says in
    :attr:`interval_dof` which distribution its intervals take.
    """

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray

    @property
    def interval_dof(self) -> int | None:
        """Degrees of freedom of the Student-t intervals (a covariance scaled by the residual
        variance), or None for normal intervals (a covariance taken as known)."""
        return None

    def confidence_intervals(self, level: float = 0.95) -> np.ndarray:
        """Intervals of the estimates from their standard errors, shape (parameters, 2):
        Student-t with :attr:`interval_dof` degrees of freedom, normal where that is None.

        Parameters
        ----------
        level : float
            Confidence level in (0, 1).

        Returns
        -------
        ndarray
        """
        if not 0.0 < level < 1.0:
            raise ParameterError(f"must be in (0, 1), got {level!r}", field="level")
        dof = self.interval_dof
        if dof is None:
            from scipy.stats import norm

            quantile = norm.ppf(0.5 + level / 2)
        else:
            from scipy.stats import t as student

            quantile = student.ppf(0.5 + level / 2, dof)
        half = quantile * self.standard_errors
        values = np.asarray(self.values, dtype=float)
        return np.column_stack([values - half, values + half])

    @property
    def standard_errors(self) -> np.ndarray:
        """Standard errors of :attr:`values`."""
        return standard_errors(self.covariance)

    @property
    def correlation(self) -> np.ndarray:
        """Correlation matrix of the estimates."""
        return correlation(self.covariance)

    def unidentifiable(self) -> dict[str, str]:
        """Parameters not identified, with the evidence (relative error, correlation).

        Returns
        -------
        dict of str to str
        """
        return unidentifiable(self.names, self.values, self.covariance)

    def parameter_rows(self, units: Mapping[str, str] | None = None) -> list[dict]:
        """One row per estimate for JSON: ``name`` (and ``unit`` from ``units``),
        ``identified``, then ``value`` and ``standard_error``, or the ``evidence`` that the
        data do not identify it.

        Parameters
        ----------
        units : mapping of str to str, optional
            The unit of each name.

        Returns
        -------
        list of dict
        """
        bad = self.unidentifiable()
        rows = []
        for i, n in enumerate(self.names):
            row: dict = {"name": n}
            if units is not None:
                row["unit"] = units[n]
            row["identified"] = n not in bad
            if n in bad:
                row["evidence"] = bad[n]
            else:
                row.update(value=float(self.values[i]),
                           standard_error=float(self.standard_errors[i]))
            rows.append(row)
        return rows


#: Old names (issue 47: the base of the fit results, named for what it is).
__getattr__ = deprecated_names(__name__, {"CovarianceSummary": (
    __name__, "FitResult", "seahelm.identification.fit_result.FitResult")})
