"""Named parameter sets for real ships, with their provenance.

``CATALOG[name]`` gives a :class:`CatalogEntry` (model name, parameters, provenance);
:func:`get` looks one up and lists the valid names on a typo.
"""

from __future__ import annotations

import dataclasses

from ..parameters import Params
from .nomoto import Nomoto1Params, Nomoto2Params

__all__ = ["CatalogEntry", "CATALOG", "get", "register"]


@dataclasses.dataclass(frozen=True)
class CatalogEntry:
    """A named parameter set for one vessel model."""

    name: str
    model: str
    params: Params
    provenance: str


CATALOG: dict[str, CatalogEntry] = {}


def register(entry: CatalogEntry) -> CatalogEntry:
    """Add a named parameter set (names are unique).

    Parameters
    ----------
    entry : CatalogEntry
        The named parameter set.

    Returns
    -------
    CatalogEntry
        ``entry``.

    Raises
    ------
    ValueError
        If an entry of that name exists already.
    """
    if entry.name in CATALOG:
        raise ValueError(f"catalog entry '{entry.name}' exists already")
    CATALOG[entry.name] = entry
    return entry


def get(name: str) -> CatalogEntry:
    """Look up a named parameter set; an unknown name raises ValueError listing the valid ones.

    Parameters
    ----------
    name : str
        Name of the parameter set.

    Returns
    -------
    CatalogEntry

    Raises
    ------
    ValueError
        If ``name`` is unknown (the message lists the valid ones).
    """
    try:
        return CATALOG[name]
    except KeyError:
        raise ValueError(
            f"unknown catalog entry '{name}'; valid: {', '.join(sorted(CATALOG))}"
        ) from None


_MARINER_PROVENANCE = (
    "Mariner-class cargo ship (L = 160.93 m, U = 15 kn = 7.7175 m/s): Nomoto constants "
    "K = 0.185 1/s, T1 = 118 s, T2 = 7.8 s, T3 = 18.5 s, identified from the nonlinear "
    "Mariner model of Chislett & Strøm-Tejsen (1965); Fossen (2021), Handbook of Marine Craft "
    "Hydrodynamics and Motion Control, 2nd ed., Table 7.1 / §7.1. First-order T = T1 + T2 - T3."
)

register(
    CatalogEntry(
        "mariner-nomoto2",
        "nomoto2",
        Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7175, length=160.93),
        _MARINER_PROVENANCE,
    )
)
register(
    CatalogEntry(
        "mariner-nomoto1",
        "nomoto1",
        Nomoto1Params(gain=0.185, time_constant=118.0 + 7.8 - 18.5, speed=7.7175, length=160.93),
        _MARINER_PROVENANCE,
    )
)

# Voitkunsky steering model (issue 4): Mariner coefficients derived from the PMM derivatives.
from .voitkunsky import MARINER_VOITKUNSKY, MARINER_VOITKUNSKY_PROVENANCE  # noqa: E402

register(CatalogEntry("mariner-voitkunsky", "voitkunsky", MARINER_VOITKUNSKY,
                      MARINER_VOITKUNSKY_PROVENANCE))

# Shushlyapin, Karapetyan, Bezuglaya & Afonina (2017): the 22.3 m research catamaran
from .catamaran import (  # noqa: E402
    CONSISTENT_PROVENANCE as _CAT_CONSISTENT,
    PAPER_PROVENANCE as _CAT_PAPER,
    consistent_params as _cat_consistent,
    paper_params as _cat_paper,
)

register(CatalogEntry("shushlyapin2017-listing", "catamaran", _cat_paper(), _CAT_PAPER))
register(CatalogEntry("shushlyapin2017-consistent", "catamaran", _cat_consistent(),
                      _CAT_CONSISTENT))

# MMG standard method (Yasukawa & Yoshimura 2015): KVLCC2 at full scale and as the L7 model,
# and the disputed L7 values by name (issue 13)
from . import mmg as _mmg  # noqa: E402

register(CatalogEntry("kvlcc2-full", "mmg", _mmg.KVLCC2_FULL, _mmg.KVLCC2_FULL_PROVENANCE))
register(CatalogEntry("kvlcc2-l7", "mmg", _mmg.KVLCC2_L7, _mmg.KVLCC2_L7_PROVENANCE))
register(CatalogEntry("kvlcc2-l7-wp0-0.35", "mmg", _mmg.KVLCC2_L7_WP0_035,
                      _mmg.KVLCC2_L7_PROVENANCE + " Variant: w_P0 = 0.35 (one open tool, "
                      "labelled 'assumed' there) instead of 0.40."))
register(CatalogEntry("kvlcc2-l7-xp-0.5", "mmg", _mmg.KVLCC2_L7_XP_050,
                      _mmg.KVLCC2_L7_PROVENANCE + " Variant: x'_P = -0.5 (geometric propeller "
                      "position) instead of -0.48 in beta_P = beta - x'_P r'."))

# Mariner nonlinear model (Chislett & Strøm-Tejsen 1965); steering gear: mariner.MARINER_SERVO
from .mariner import MARINER_NONLINEAR, MARINER_NONLINEAR_PROVENANCE  # noqa: E402

register(CatalogEntry("mariner-nonlinear", "mariner", MARINER_NONLINEAR,
                      MARINER_NONLINEAR_PROVENANCE))
