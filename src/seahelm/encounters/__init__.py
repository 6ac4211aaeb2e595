"""Ships meeting ships: encounter geometry (CPA/TCPA, COLREG situations, ship domains), several
vessels in one stepped batch that see each other through an AIS-like sensor, collision
avoidance, per-encounter verdicts and Monte-Carlo studies (docs: ``docs/guide/encounters.rst``).

>>> from seahelm.encounters import Encounter, Vessel
>>> own = Vessel(ship="kvlcc2-full", course=0.0, avoid=True)
>>> target = Vessel(ship="kvlcc2-full", north=4000.0, east=4000.0, course=-1.5708)
>>> result = Encounter([own, target], t_final=900.0, avoidance="rule-based").run()
>>> bool(result.collision[0, 0]), bool(result.verdicts["acted"][0, 0, 0])
(False, True)
"""

from .avoidance import AVOIDANCE, RuleBased, VelocityObstacles
from .encounter import Encounter, HeadingAutopilot, Vessel
from .geometry import (ColregSectors, FujiiDomain, Situation, classify, cpa_tcpa,
                       relative_bearing, velocity, wrap_pi)
from .monte_carlo import monte_carlo_vessels, sample_geometry
from .result import EncounterResult, VerdictRules, wilson_interval
from .sensing import AIS

__all__ = ["AIS", "AVOIDANCE", "ColregSectors", "Encounter", "EncounterResult", "FujiiDomain",
           "HeadingAutopilot", "RuleBased", "Situation", "VelocityObstacles", "VerdictRules",
           "Vessel", "classify", "cpa_tcpa", "monte_carlo_vessels", "relative_bearing",
           "sample_geometry", "velocity", "wilson_interval", "wrap_pi"]
