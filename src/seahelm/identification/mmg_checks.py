"""The checks a careful analyst makes on identified MMG hull derivatives (issue 45, item 5).

:func:`seahelm.identification.mmg_fit.identify_mmg` takes the base ship's masses, propeller and rudder
as given. If one of them is wrong — a rudder area of 13.1 m² where the ship has 16 m² — the
fit does not fail: the hull derivatives absorb the error, with small standard errors (an
estimated 120 m cargo ship: Y'_vvv = +2.3 ± 0.17 where the truth is −0.75). Standard errors
measure the noise, not a wrong model. So :func:`check_hull_fit` adds three checks:

1. **Physical signs** (:data:`SIGN_RULES`): in the MMG sign convention (Yasukawa & Yoshimura
   2015) a hull resists and damps: R'_0 > 0; Y'_v < 0, N'_v < 0, N'_r < 0 (Kijima et al.
   1990, the signs of their regressions for every ship of their data; Clarke, Gedling &
   Hine 1983 for the linear sway and yaw damping); Y'_vvv < 0 and N'_rrr < 0, the cross-flow
   drag of the hull in sway and yaw (Yoshimura & Masumoto 2012: Y'_vvv = −0.185 L/B + 0.48
   is negative for every L/B > 2.6 of their data; their N'_rrr regression is negative
   throughout). A value of the wrong sign, beyond two standard errors, is implausible.
2. **Plausible range** (:data:`RANGE_CHECKED`: the sway and yaw derivatives): each estimate
   against the regression value for the base ship's particulars (Kijima et al. 1990 for the
   linear, Yoshimura & Masumoto 2012 for the nonlinear terms;
   :mod:`seahelm.hydrodynamics.hull_derivatives`): outside ``RANGE_FACTOR`` (3) times the
   regression's magnitude of it, beyond two standard errors, is implausible. A loose band:
   the KVLCC2's captive-test Y'_vvv (−1.607) is three times its regression value (−0.54).
   The surge terms are not range-checked: their regressions miss the KVLCC2's captive values
   by more than that (X'_vvvv 0.771 against 0.12, X'_rr 0.011 against −0.0045).
3. **Residual whiteness**: the Ljung–Box (1978) statistic Q = n(n+2) Σ_{k=1..h} ρ_k²/(n−k)
   of the output-error residuals (h = 20 lags) against χ²_h, per record and output, with n
   the record's samples thinned to one per second. Output-error residuals of a right model
   and noisy records are white; of a wrong model, slowly varying. A p-value below 10⁻³ with
   a lag-one autocorrelation ρ_1 > 0.5 (the effect, not only its significance: a right
   model fitted to noisy records leaves ρ_1 ≈ 0.2) and an RMS residual above ``RESOLUTION``
   (10⁻³ of U_0, or of U_0/L for r: the resolution of trial instruments) flags a **poor
   fit**. Below that size the colour
   says nothing: noise-free records of the right model leave coloured residuals of 10⁻⁵
   (the integration's own error).

4. **Held-out prediction** (with two records or more): the derivatives refitted without the
   last record predict it (driven by its rudder and rps from its initial state); an RMS
   prediction error above ``HELDOUT_FACTOR`` (10) times the refit's own residual and above
   ``HELDOUT_FLOOR`` (1 % of U_0, U_0/L) is a model that reproduces its data but not the ship.
   Measured (a 35° turn predicted from a 10/10 and a 20/20 zig-zag): the cargo ship with the
   wrong rudder area 4.5 % against 0.08 % in-sample (55×); with the right one 0.13 % (below
   the floor); the KVLCC2 from records with 0.5 % noise 3.4 % against 0.66 % (5×): a turn is
   an extrapolation of zig-zags, hence the wide factor. A posterior-
   predictive check in the sense of Gelman et al. (2013, ch. 6) with the parameters at their
   estimate: the Laplace spread of the derivatives is small next to that factor.

When any of them fails, :attr:`HullCheck.warning` names the inputs to check in the base ship:
the rudder (area, and its position x'_R, through Y'_δ-like force absorbed by Y'_v, Y'_vvv), the
propeller (diameter, K_T, wake: absorbed by R'_0, X'_vv) and the masses (m, m_x, m_y, I_z:
absorbed by the inertia-like terms), picked by which equations' derivatives fail.

References
----------
Gelman, A., Carlin, J. B., Stern, H. S., Dunson, D. B., Vehtari, A., Rubin, D. B. (2013).
Bayesian Data Analysis, 3rd ed. CRC Press.
Ljung, G. M., Box, G. E. P. (1978). On a measure of lack of fit in time series models.
Biometrika 65(2), 297–303.
Kijima, K., Katsuno, T., Nakiri, Y., Furukawa, Y. (1990). On the manoeuvring performance of a
ship with the parameter of loading condition. J. Soc. Naval Arch. Japan 168, 141–148.
Yoshimura, Y., Masumoto, Y. (2012). Hydrodynamic database and manoeuvring prediction method
with medium high-speed merchant ships and fishing vessels. MARSIM 2012.
Clarke, D., Gedling, P., Hine, G. (1983). The application of manoeuvring criteria in hull
design using linear theory. Trans. RINA 125, 45–68.
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Any

import numpy as np

__all__ = ["HELDOUT_FACTOR", "HELDOUT_FLOOR", "SIGN_RULES", "RANGE_FACTOR", "RANGE_CHECKED",
           "RESOLUTION", "HullCheck", "check_hull_fit", "ljung_box", "SuspectBaseShipWarning"]

#: The sign each hull derivative must have (module docstring, with sources).
SIGN_RULES: dict[str, int] = {"R_0": 1, "Y_v": -1, "N_v": -1, "N_r": -1, "Y_vvv": -1,
                              "N_rrr": -1}
#: Plausible range: within this factor of the regression's magnitude of the regression value.
RANGE_FACTOR = 3.0
#: The derivatives whose regressions are good enough for the range check (module docstring).
RANGE_CHECKED = ("Y_v", "Y_r", "N_v", "N_r", "Y_vvv", "Y_vvr", "Y_vrr", "Y_rrr", "N_vvv",
                 "N_vvr", "N_vrr", "N_rrr")
#: Ljung–Box lags and the p-value below which residuals are not white.
LAGS, P_WHITE = 20, 1e-3
#: Scaled RMS residual below which the colour of the residuals is not evidence of a poor fit.
RESOLUTION = 1e-3
#: A held-out record predicted this many times worse than the refit's residual is a poor model.
HELDOUT_FACTOR = 10.0
#: ... and worse than this scaled RMS error (a prediction within 1 % of the scale is good).
HELDOUT_FLOOR = 1e-2


class SuspectBaseShipWarning(UserWarning):
    """Identified derivatives are implausible or the fit is poor: check the base ship."""


def ljung_box(residuals: np.ndarray, lags: int = LAGS) -> tuple[float, float, float]:
    """Ljung–Box Q of a residual series, its χ²_lags p-value and the lag-one autocorrelation.

    Parameters
    ----------
    residuals : ndarray
    lags : int, optional

    Returns
    -------
    q, p_value, rho1 : float
    """
    from scipy.stats import chi2

    e = np.asarray(residuals, dtype=float)
    e = e[np.isfinite(e)] - np.mean(e[np.isfinite(e)])
    n = e.size
    denom = float(e @ e)
    if n <= lags + 1 or denom == 0.0:
        return 0.0, 1.0, 0.0
    rho = np.array([float(e[:-k] @ e[k:]) / denom for k in range(1, lags + 1)])
    q = float(n * (n + 2) * np.sum(rho ** 2 / (n - np.arange(1, lags + 1))))
    return q, float(chi2.sf(q, lags)), float(rho[0])


@dataclasses.dataclass(frozen=True)
class HullCheck:
    """The result of :func:`check_hull_fit`.

    Attributes
    ----------
    implausible : dict of str to str
        Derivative → why (sign or range, with the numbers).
    whiteness : dict of str to tuple
        Record/output → (Q, p-value, ρ_1, RMS of the scaled residuals).
    poor_fit : bool
        Some residual series is not white.
    heldout : tuple or None
        (record, in-sample RMS, held-out RMS) of the held-out prediction (scaled u, v, r).
    suspects : tuple of str
        The base ship's inputs to check.
    warning : str
        One message naming them (empty when every check passes).
    """

    implausible: dict[str, str]
    whiteness: dict[str, tuple[float, float, float, float]]
    poor_fit: bool
    suspects: tuple[str, ...]
    warning: str
    heldout: tuple[str, float, float] | None = None

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON)."""
        held = None if self.heldout is None else dict(zip(
            ("record", "in_sample_rms", "heldout_rms"), self.heldout))
        return {"implausible": self.implausible, "poor_fit": self.poor_fit, "heldout": held,
                "suspects": list(self.suspects), "warning": self.warning,
                "whiteness": {k: {"ljung_box_q": q, "p_value": p, "rho1": r, "rms": e}
                              for k, (q, p, r, e) in self.whiteness.items()}}


def _regression(base: Any) -> dict[str, float]:
    """Kijima / Yoshimura & Masumoto values for the base ship's particulars (or nothing)."""
    from ..hydrodynamics.hull import HullParticulars
    from ..hydrodynamics.hull_derivatives import hull_derivatives

    part = getattr(base, "particulars", None)
    if part is None or part.block_coefficient is None:
        return {}
    try:
        hull = HullParticulars(length=part.length, beam=part.beam, draft=part.draft,
                               block_coefficient=part.block_coefficient)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return {k: float(c.value) for k, c in hull_derivatives(hull).items()}
    except Exception:  # noqa: BLE001 - a base ship without usable particulars: no range check
        return {}


def check_hull_fit(fit: Any, base: Any, residuals: dict[str, np.ndarray] | None = None,
                   heldout: tuple[str, float, float] | None = None) -> HullCheck:
    """Signs, plausible ranges and residual whiteness of an identified hull (module docstring).

    Parameters
    ----------
    fit : HullFit
    base : Ship
        The base ship of the fit.
    residuals : dict of str to ndarray, optional
        Output-error residual series by name (record and output), sampled at 1 s or so.
    heldout : tuple, optional
        (record, in-sample RMS, held-out RMS) of a held-out prediction.

    Returns
    -------
    HullCheck
    """
    ref = _regression(base)
    se = fit.standard_errors
    bad: dict[str, str] = {}
    for name, value, s in zip(fit.names, fit.values, se):
        sign = SIGN_RULES.get(name)
        if sign is not None and sign * value < -2.0 * s:
            bad[name] = (f"{value:+.4g} ± {s:.2g}: must be {'> 0' if sign > 0 else '< 0'} "
                         "(the hull damps: seahelm.identification.mmg_checks.SIGN_RULES)")
            continue
        r = ref.get(name) if name in RANGE_CHECKED else None
        if r is not None and abs(value - r) > RANGE_FACTOR * abs(r) + 2.0 * s:
            bad[name] = (f"{value:+.4g} ± {s:.2g}: outside {r:+.4g} ± {RANGE_FACTOR:g}×"
                         f"{abs(r):.3g} (the regression for the base ship's particulars)")
    white: dict[str, tuple[float, float, float, float]] = {}
    for key, e in (residuals or {}).items():
        rms = float(np.sqrt(np.nanmean(np.asarray(e, dtype=float) ** 2)))
        white[key] = ljung_box(e) + (rms,)
    poor = any(p < P_WHITE and rho > 0.5 and rms > RESOLUTION
               for _, p, rho, rms in white.values())
    unseen = heldout is not None and heldout[2] > max(HELDOUT_FACTOR * heldout[1], HELDOUT_FLOOR)
    poor = poor or unseen
    suspects: list[str] = []
    eqs = {n[0] for n in bad}
    if eqs & {"Y", "N"}:
        suspects.append("rudder (area A_R, position x'_R, lift slope f_α, flow straightening "
                        "γ_R)")
    if "R" in eqs or "X" in eqs:
        suspects.append("propeller (diameter D_P, K_T, wake w_P0, thrust deduction t_P)")
    if bad or poor:
        suspects.append("mass and inertia (m, m_x, m_y, I_z, x_G)")
    warning = ""
    if bad or poor:
        parts = []
        if bad:
            parts.append("implausible hull derivatives: " + "; ".join(
                f"{k}' {v}" for k, v in bad.items()))
        if unseen:
            parts.append(f"the record {heldout[0]}, held out, is predicted with an RMS error "
                         f"{heldout[2]:.2g} against {heldout[1]:.2g} in the records fitted")
        if poor and white and any(p < P_WHITE and rho > 0.5 and rms > RESOLUTION
                                  for _, p, rho, rms in white.values()):
            worst = max(white.items(), key=lambda kv: kv[1][3])
            parts.append(f"a poor fit: residuals not white and large (Ljung–Box p = "
                         f"{worst[1][1]:.2g}, lag-1 autocorrelation {worst[1][2]:.2f}, RMS "
                         f"{worst[1][3]:.2g} of the scale, in {worst[0]})")
        warning = ("; ".join(parts) + ". The base ship's inputs the fit takes as given are "
                   "probably wrong; check its " + ", ".join(suspects)
                   + " (docs: identification, what must be right in the base ship)")
    return HullCheck(implausible=bad, whiteness=white, poor_fit=poor,
                     suspects=tuple(suspects) if warning else (), warning=warning,
                     heldout=heldout)
