"""Closed-form equilibria a model declares, tried before the iterative solves.

A model declares a closed form as a capability (:attr:`VesselModel.capabilities
<seahelm.vessels.base.VesselModel.capabilities>`, names of
:data:`seahelm.vessels.base.CAPABILITIES`); :data:`CLOSED_FORMS` names the function that
evaluates it:

``closed-form-self-propulsion``
    the propeller rps of the straight run (v = r = δ = 0) from the surge balance
    X_H + X_P = 0 with the K_T(J) quadratic and w_P = w_P0 (Yasukawa & Yoshimura 2015,
    eqs. (7), (9)-(11)): :func:`seahelm.vessels.mmg_four_quadrant.self_propulsion_rps`.
    Declared by the MMG model.

The batched solver (:func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states`)
takes a closed-form value where the model's own right-hand side vanishes there (scaled
residual ≤ :data:`RESIDUAL_TOL`), and solves the other runs as before;
``tests/test_equilibria_closed_forms.py`` checks the closed form against the Newton root.
"""

from __future__ import annotations

import importlib
import math

import numpy as np

from ...errors import ParameterError
from .plant import Plant

__all__ = ["CLOSED_FORMS", "RESIDUAL_TOL", "self_propulsion_rps"]

#: capability -> "module:function" of the closed form.
CLOSED_FORMS = {
    "closed-form-self-propulsion": "seahelm.vessels.mmg_four_quadrant:self_propulsion_rps",
}
#: Largest scaled surge residual |u̇| L/U² at which a closed-form value is taken.
RESIDUAL_TOL = 1e-12


def self_propulsion_rps(plant: Plant, speeds: np.ndarray) -> np.ndarray:
    """The closed-form self-propulsion rps of each run of ``plant`` at ``speeds`` [m/s].

    Parameters
    ----------
    plant : Plant
        The runs.
    speeds : numpy.ndarray
        Straight-run speed per run [m/s].

    Returns
    -------
    numpy.ndarray
        rps [1/s] per run; NaN for every run if the model declares no closed form, and for a
        run where the closed form gives none (its ParameterError).
    """
    out = np.full(plant.n_runs, math.nan)
    if not plant.model.supports("closed-form-self-propulsion"):
        return out
    module, name = CLOSED_FORMS["closed-form-self-propulsion"].split(":")
    func = getattr(importlib.import_module(module), name)
    for i, (p, U) in enumerate(zip(plant.params, speeds.tolist())):
        try:
            out[i] = func(p, U)
        except ParameterError:
            continue
    return out
