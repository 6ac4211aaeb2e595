"""The flat approximation Y of the CPP control set V, Platonov & Platonova eq. (24), and V
against Y by Hausdorff distance.

V is convex and very thin (width ≈ 0.036 across (1, −1, 0)/√2), so a flat approximation is
sound. Eq. (24) is inconsistent (its segment does not meet the arc's ends): Y is the convex
hull of the arc (β1 t, β2 t, β3 t²), t ∈ [-1, 1] (:data:`ARC_HULL`, ``variant="hull"``); the
printed set (arc plus segment y1 = y2 ∈ [-1, 1], y3 = β3, hulled) is :data:`PRINTED_EQ24`
(``variant="printed"``), registry :data:`FLAT_VARIANTS`. :func:`cpp_admissible_set` reports the
Hausdorff distance of each to V (:mod:`seahelm.studies.platonov.control_set`).
"""

from __future__ import annotations

import abc
import dataclasses
import math
import time
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any

import numpy as np

from ..._validate import as_float_array
from .averaging import hausdorff_from_support, maximise_polynomial, sphere_grid
from ...errors import ParameterError
from ...registry import lookup
from .control_set import _check_waves, cpp_betas, cpp_boundary_map, cpp_support_function

__all__ = [
    "FlatVariant",
    "ArcHull",
    "PrintedEq24",
    "ARC_HULL",
    "PRINTED_EQ24",
    "FLAT_VARIANTS",
    "get_flat_variant",
    "flat_support_function",
    "CPPControlSetResult",
    "cpp_admissible_set",
]


# ---------------------------------------------------------------------------------------
# the flat approximation Y of eq. (24): the arc's hull and the printed set, as objects
# ---------------------------------------------------------------------------------------
class FlatVariant(abc.ABC):
    """A reading of the flat approximation Y of eq. (24) (a :data:`FLAT_VARIANTS` entry)."""

    #: Registry name.
    name: str = ""

    @abc.abstractmethod
    def support(self, h_arc: np.ndarray, z: np.ndarray, beta3: float) -> np.ndarray:
        """h_Y(z) from the support function of the arc's convex hull.

        Parameters
        ----------
        h_arc : numpy.ndarray
            Support function of conv{(β1 t, β2 t, β3 t²) : t ∈ [-1, 1]} at ``z``.
        z : numpy.ndarray, shape (..., 3)
            Directions.
        beta3 : float
            β3 [-].

        Returns
        -------
        numpy.ndarray
            h_Y(z).
        """

    def extra_segment(self, beta3: float) -> np.ndarray | None:
        """The segment this reading adds to the arc's hull, as its two end points (2, 3), or
        None (drawn by :func:`~seahelm.studies.platonov.figures.plot_set_Y`).

        Parameters
        ----------
        beta3 : float
            β3 [-].

        Returns
        -------
        numpy.ndarray or None
        """
        return None


class ArcHull(FlatVariant):
    """Y = conv{(β1 t, β2 t, β3 t²) : t ∈ [-1, 1]} (the correct reading)."""

    name = "hull"

    def support(self, h_arc: np.ndarray, z: np.ndarray, beta3: float) -> np.ndarray:
        """The arc's hull: h_Y = h_arc.

        Parameters
        ----------
        h_arc : numpy.ndarray
            Support function of the arc's hull.
        z : numpy.ndarray, shape (..., 3)
            Directions (not used).
        beta3 : float
            β3 [-] (not used).

        Returns
        -------
        numpy.ndarray
            h_Y(z).
        """
        return h_arc


class PrintedEq24(FlatVariant):
    """Eq. (24) as printed: the hull of the arc and the segment {(s, s, β3) : s ∈ [-1, 1]}
    (erratum: it does not meet the arc's ends and sticks out of V)."""

    name = "printed"

    def support(self, h_arc: np.ndarray, z: np.ndarray, beta3: float) -> np.ndarray:
        """max(h_arc, |z1 + z2| + β3 z3).

        Parameters
        ----------
        h_arc : numpy.ndarray
            Support function of the arc's hull.
        z : numpy.ndarray, shape (..., 3)
            Directions.
        beta3 : float
            β3 [-].

        Returns
        -------
        numpy.ndarray
            h_Y(z).
        """
        return np.maximum(h_arc, np.abs(z[..., 0] + z[..., 1]) + beta3 * z[..., 2])

    def extra_segment(self, beta3: float) -> np.ndarray:
        """The printed segment {(s, s, β3) : s ∈ [-1, 1]}: its end points.

        Parameters
        ----------
        beta3 : float
            β3 [-].

        Returns
        -------
        numpy.ndarray, shape (2, 3)
        """
        return np.array([[-1.0, -1.0, beta3], [1.0, 1.0, beta3]])


#: The arc's convex hull (``"hull"``, the default).
ARC_HULL: FlatVariant = ArcHull()
#: Eq. (24) as printed (``"printed"``).
PRINTED_EQ24: FlatVariant = PrintedEq24()
#: Readings of eq. (24), by name.
FLAT_VARIANTS: Mapping[str, FlatVariant] = MappingProxyType(
    {v.name: v for v in (ARC_HULL, PRINTED_EQ24)})


def get_flat_variant(variant: str | FlatVariant) -> FlatVariant:
    """A reading of eq. (24) by name (a key of :data:`FLAT_VARIANTS`) or the object itself.

    Parameters
    ----------
    variant : str or FlatVariant
        ``"hull"``, ``"printed"`` or a :class:`FlatVariant`.

    Returns
    -------
    FlatVariant

    Raises
    ------
    ParameterError
        If ``variant`` is an unknown name (the message lists the valid ones).
    """
    return lookup("`variant`", FLAT_VARIANTS, variant, FlatVariant, error=ParameterError)


def flat_support_function(
    z: Any, betas: Sequence[float], variant: str | FlatVariant = "hull"
) -> np.ndarray:
    """Support function of the flat approximation Y, Platonov & Platonova, eq. (24).

    ``variant="hull"``: Y = conv{(β1 t, β2 t, β3 t²) : t ∈ [-1, 1]} (correct reading);
    h_Y(z) = max_t (β1 z1 + β2 z2) t + β3 z3 t². ``variant="printed"``: the convex hull of that
    arc and the printed segment {(s, s, β3) : s ∈ [-1, 1]} (erratum: it does not meet the arc's
    ends and sticks out of V); h = max(h_arc, |z1 + z2| + β3 z3).

    Parameters
    ----------
    z : array_like, shape (..., 3)
        Directions (need not be unit).
    betas : sequence of float
        (β1, β2, β3) of :func:`cpp_betas` [-].
    variant : str or FlatVariant, optional
        Reading of eq. (24): a key of :data:`FLAT_VARIANTS` or the object (default "hull",
        :data:`ARC_HULL`; ``"printed"`` is :data:`PRINTED_EQ24`).

    Returns
    -------
    numpy.ndarray, shape (...)
        h_Y(z).
    """
    variant = get_flat_variant(variant)
    z = as_float_array("z", z)
    b1, b2, b3 = (float(b) for b in betas)
    q = np.stack([np.zeros(z.shape[:-1]), b1 * z[..., 0] + b2 * z[..., 1], b3 * z[..., 2]], -1)
    return variant.support(maximise_polynomial(q)[1], z, b3)


@dataclasses.dataclass(frozen=True)
class CPPControlSetResult:
    """V and Y for the CPP ship (Platonov & Platonova, Figs. 1 and 2, eq. (14)-(24))."""

    immersion: float
    amplitude: float
    betas: tuple[float, float, float]
    phi1: np.ndarray  #: azimuths of the grid [rad]
    phi2: np.ndarray  #: elevations of the grid [rad]
    directions: np.ndarray  #: (n_elevation, n_azimuth, 3) unit z
    boundary: np.ndarray  #: ς(z) on the grid, points of ∂V, (n_elevation, n_azimuth, 3)
    support_V: np.ndarray
    support_Y: np.ndarray
    support_Y_printed: np.ndarray
    hausdorff_V_Y: float
    hausdorff_V_Y_printed: float
    width: float  #: thickness of V across (1, −1, 0)/√2: h_V(n) + h_V(−n)
    elapsed: float  #: wall time [s]

    @property
    def grid_points(self) -> int:
        return int(self.directions.shape[0] * self.directions.shape[1])

    def summary(self) -> dict[str, Any]:
        """Plain-number summary (the CLI's JSON)."""
        b1, b2, b3 = self.betas
        return {
            "immersion": self.immersion,
            "amplitude": self.amplitude,
            "beta1": b1,
            "beta2": b2,
            "beta3": b3,
            "hausdorff_V_Y": self.hausdorff_V_Y,
            "hausdorff_V_Y_printed": self.hausdorff_V_Y_printed,
            "width_V": self.width,
            "grid_points": self.grid_points,
            "elapsed_s": self.elapsed,
        }


def _refine_hausdorff(
    phi1: float, phi2: float, immersion: float, amplitude: float, betas: Sequence[float],
    variant: FlatVariant,
) -> float:
    from scipy.optimize import minimize

    def neg(a: np.ndarray) -> float:
        z = np.array([math.cos(a[0]) * math.cos(a[1]), math.sin(a[0]) * math.cos(a[1]),
                      math.sin(a[1])])
        hv = cpp_support_function(z, immersion, amplitude)
        hy = flat_support_function(z, betas, variant)
        return -abs(float(hv - hy))

    res = minimize(neg, np.array([phi1, phi2]), method="Nelder-Mead",
                   options={"xatol": 1e-7, "fatol": 1e-12, "maxiter": 400})
    return -float(res.fun)


def cpp_admissible_set(
    immersion: float = 1.2,
    amplitude: float = 0.96,
    *,
    n_azimuth: int = 200,
    n_elevation: int = 100,
    refine: bool = True,
) -> CPPControlSetResult:
    """Boundary of V on the grid of eq. (17), the flat set Y and their Hausdorff distances.

    Parameters
    ----------
    immersion, amplitude : float
        h0/R and eψ0/R [R] (Platonov & Platonova, eq. (12)); defaults give α = 0.5 − 0.4 sin τ.
    n_azimuth, n_elevation : int
        Grid of φ1 ∈ [0, 2π] and φ2 ∈ [−π/2, π/2].
    refine : bool
        Polish each Hausdorff distance by a local maximisation over the sphere started at the
        best grid direction (otherwise the grid value, a lower bound).
    """
    start = time.perf_counter()
    _check_waves(immersion, amplitude)
    z, phi1, phi2 = sphere_grid(n_azimuth, n_elevation)
    betas = cpp_betas(immersion, amplitude)
    sigma = cpp_boundary_map(z, immersion, amplitude)
    hv = np.sum(sigma * z, axis=-1)
    hy = flat_support_function(z, betas, ARC_HULL)
    hyp = flat_support_function(z, betas, PRINTED_EQ24)
    dists = []
    for h in (hy, hyp):
        d = hausdorff_from_support(hv, h)
        if refine:
            i, j = np.unravel_index(np.argmax(np.abs(hv - h)), hv.shape)
            d = max(d, _refine_hausdorff(phi1[j], phi2[i], immersion, amplitude, betas,
                                         ARC_HULL if h is hy else PRINTED_EQ24))
        dists.append(d)
    n = np.array([[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]]) / math.sqrt(2.0)
    width = float(np.sum(cpp_support_function(n, immersion, amplitude)))
    return CPPControlSetResult(
        immersion=float(immersion), amplitude=float(amplitude), betas=betas, phi1=phi1,
        phi2=phi2, directions=z, boundary=sigma, support_V=hv, support_Y=hy,
        support_Y_printed=hyp, hausdorff_V_Y=dists[0], hausdorff_V_Y_printed=dists[1],
        width=width, elapsed=time.perf_counter() - start,
    )
