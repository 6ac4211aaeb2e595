"""Ships meeting ships: encounter geometry (CPA/TCPA, COLREG situations, ship domains), several
vessels in one stepped batch that see each other through an AIS-like sensor, collision
avoidance and per-encounter verdicts (docs: ``docs/guide/encounters.rst``)."""

from .geometry import (ColregSectors, FujiiDomain, Situation, classify, cpa_tcpa,
                       relative_bearing, velocity, wrap_pi)

__all__ = ["ColregSectors", "FujiiDomain", "Situation", "classify", "cpa_tcpa",
           "relative_bearing", "velocity", "wrap_pi"]
