"""The ship-file format: its version, every key with its unit, and the error of a bad file.

:data:`FORMAT_REFERENCE` documents every key (the docs generate their reference page from
it); :mod:`seahelm.ships.files` reads ship files and :mod:`seahelm.ships.writing` writes them.
"""

from __future__ import annotations

import os
from typing import Any

from ..errors import ParameterError
from ..vessels.particulars import FIELD_UNITS
from .thrusters_file import THRUSTER_KEYS as _THRUSTER_KEYS

__all__ = ["FORMAT", "FORMAT_REFERENCE", "ShipFileError", "is_ship_path"]

#: The ship-file format version this seahelm writes and reads.
FORMAT = 1

#: Every key of a ship file: (key path, unit, required, what it is).
FORMAT_REFERENCE: tuple[tuple[str, str, str, str], ...] = (
    ("format", "", "yes", f"format version, {FORMAT}"),
    ("name", "", "yes", "the ship's name (labels results and tables)"),
    ("description", "", "no", "one line: what ship this is"),
    ("model", "", "yes", "the manoeuvring model, a registry name (`seahelm models`)"),
    ("base", "", "no", "a catalog ship or a ship file (relative to this file) that gives "
                       "every key not given here; tables merge key by key"),
    ("test_speed", "m/s", "no", "approach (test) speed U_0; only for a model whose parameters "
                                "have no design speed (approach_speed, nominal_speed, speed)"),
    ("water_depth", "m", "no", "water depth h (default: deep water); [params] are then the "
                               "deep-water ones, corrected for h (MMG model; needs [particulars]; "
                               "h > T)"),
    ("validity", "", "no", "what the parameter set is valid for: a text or a list of texts"),
    ("params.<name>", "model's", "yes", "every parameter of the model (its unit: `seahelm "
                                        "models`); an angle also as <name>_deg in degrees"),
    ("steering_gear.actuator", "", "with [steering_gear]", "the actuator, a registry name "
                                                            "(rudder-servo)"),
    ("steering_gear.params.<name>", "actuator's", "with [steering_gear]",
     "every parameter of the actuator; an angle also as <name>_deg"),
    ("propulsion.kind", "", "with [propulsion]", "in words (single fixed-pitch propeller, ...)"),
    ("propulsion.inputs", "", "no", "the model inputs it is commanded through"),
    *((f"particulars.{n}", u, "with [particulars]" if req else "no",
       {"length": "length between perpendiculars L", "beam": "beam B", "draft": "draft T",
        "block_coefficient": "block coefficient C_b, in (0, 1]",
        "displacement": "displacement volume (default C_b L B T)",
        "length_overall": "length overall (Blendermann's wind loads)",
        "frontal_area": "frontal windage area above the water",
        "lateral_area": "lateral windage area above the water",
        "windage_centre": "centre of the lateral windage area, forward of midships",
        "metacentric_height": "transverse metacentric height GM (the closed-form roll RAO)",
        "superstructure_lateral_area": "lateral area of the superstructure A_OD (Fujiwara's "
                                       "wind loads)",
        "superstructure_centre": "centre of A_OD, forward of midships C_BR (Fujiwara)",
        "superstructure_height": "top of the superstructure above the water H_BR (Fujiwara)",
        "windage_height": "centre of the lateral windage area above the water H_C (Fujiwara)",
        "model_scale": "Froude scale λ >= 1 of a model ship (the stopping test's engine "
                       "timings: full-scale / √λ)",
        "vessel_type": "Blendermann's vessel type (tanker-loaded, cargo-loaded, ...)"}[n])
      for n, u, req in FIELD_UNITS),
    *((f"thrusters[].{k}", u, "with [[thrusters]]" if req == "yes" else "no", what)
      for k, u, req, what in _THRUSTER_KEYS),
    ("provenance.params", "", "no", "where the parameter set comes from"),
    ("provenance.steering_gear", "", "no", "where the steering gear comes from"),
    ("provenance.propulsion", "", "no", "where the propulsion description comes from"),
    ("provenance.particulars", "", "no", "where the particulars come from"),
    ("provenance.thrusters", "", "no", "where the thruster layout comes from"),
    ("provenance.coefficients.<name>", "", "no", "the source of one coefficient, where it "
                                                 "differs from provenance.params"),
)

class ShipFileError(ParameterError):
    """A ship file (or mapping) is invalid: names the file, the key path and the unit.

    Attributes
    ----------
    source : str
        The file (or ``<mapping>``).
    field, reason, unit, value
        As :class:`~seahelm.errors.ParameterError`; ``field`` is the key path in the file.
    """

    def __init__(self, reason: str = "", *, source: str = "<mapping>", field: str | None = None,
                 unit: str | None = None, value: Any = None) -> None:
        self.source = source
        super().__init__(reason, field=field, unit=unit, value=value)

    def _render(self) -> str:
        return f"{self.source}: {super()._render()}"


def is_ship_path(text: str) -> bool:
    """Whether ``text`` names a ship file rather than a catalog ship.

    Parameters
    ----------
    text : str
        A catalog name or a path.

    Returns
    -------
    bool
        True when it ends in ``.toml`` or contains a path separator.
    """
    return text.endswith(".toml") or os.sep in text or "/" in text
