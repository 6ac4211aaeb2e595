"""DP station-keeping capability after DNV-ST-0111: the largest wind a vessel holds its position
in, per environment direction and failure case.

:mod:`.level1`
    level 1, quasi-static: the mean environmental load (wind, wave drift, current) balanced by
    the constrained thrust allocation (:func:`level1_capability`, :func:`environment_loads`,
    :func:`dp_vessel`).
:mod:`.level3`
    level 3, time domain: every case one run of one batch of the closed loop (vessel,
    ``dp-pid``, allocation) under that load, held when the position and heading stay inside
    their limits (:func:`level3_capability`).

The names below are the submodules' own objects, each imported on first use.
``seahelm.analysis.dp_capability`` and ``seahelm.analysis.dp_capability_level3`` are deprecated
paths to these modules (issue 47).
"""

from ..._optional import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {
    "level1": ("BEAUFORT_WIND", "DpVessel", "dp_vessel", "CapabilityResult", "level1_capability",
               "environment_loads", "sea_from_wind"),
    "level3": ("Level3Result", "level3_capability"),
})
