"""What a fit's covariance says about its estimates: standard errors, correlations, and which
parameters the data do not identify (shared by the Nomoto and the MMG identification)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

__all__ = ["standard_errors", "correlation", "unidentifiable", "UNIDENTIFIABLE_RELATIVE_SE",
           "UNIDENTIFIABLE_CORRELATION", "CovarianceSummary"]

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


class CovarianceSummary:
    """What a fit result with ``names``, ``values`` and ``covariance`` says of its estimates (a
    base of the identification results: Nomoto, MMG hull, linear sway–yaw)."""

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray

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
