"""The IMO manoeuvrability check (Resolution MSC.137(76), 2002): of one ship, of an ensemble.

:mod:`.check`
    :func:`imo_check` of one ship (turning circles, initial turning, zig-zags, stopping) and
    the criteria's limits (:data:`ADVANCE_LIMIT`, :func:`imo_overshoot_limits`, ...).
:mod:`.probability`
    :func:`imo_probabilities`: the probability of passing each criterion over an ensemble of
    ships (one batch per manoeuvre, Wilson intervals); :func:`monte_carlo_ships` draws one.
:mod:`.monte_carlo`
    :func:`imo_monte_carlo` and :func:`imo_of_samples`: draw (or read), check and keep what
    was drawn (:class:`ImoEnsemble`).
:mod:`.ensemble`
    the ensemble's check as a Dataset, ``imo-probabilities.nc`` (:func:`ensemble_dataset`)
    and its reading back (:func:`ensemble_payload`).
:mod:`.given_fit`
    the check given an identification: fit -> posterior -> ships -> probabilities
    (:func:`imo_given_nomoto_fit`, :func:`imo_given_mmg_fit`).

The names below are the submodules' own objects, each imported on first use (the reader of a
result file does not compile the manoeuvres' kernels). The old modules
``seahelm.analysis.imo_probability``, ``imo_monte_carlo``, ``imo_ensemble`` and
``imo_given_fit`` are deprecated paths to these (issue 47).
"""

from ..._optional import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {
    "check": ("ADVANCE_LIMIT", "TACTICAL_DIAMETER_LIMIT", "INITIAL_TURNING_LIMIT",
              "STOPPING_LIMIT", "ZIGZAG_20_FIRST_OVERSHOOT_LIMIT", "OvershootLimits",
              "ImoCriterion", "ImoReport", "imo_overshoot_limits", "imo_check"),
    "probability": ("ImoProbabilities", "imo_probabilities", "probabilities_from_values",
                    "wilson_interval", "monte_carlo_ships", "UNCERTAIN_COEFFICIENTS",
                    "DEFAULT_UNCERTAINTY", "MAX_UNCERTAINTY", "NO_APPROACH"),
    "monte_carlo": ("SHARED_KEYS", "ImoEnsemble", "drawn_statistics", "imo_monte_carlo",
                    "imo_of_samples", "drawn_values", "ships_of_samples"),
    "ensemble": ("ENSEMBLE_FILE", "ensemble_dataset", "is_ensemble_dataset", "ensemble_payload",
                 "criterion_label", "criteria_json", "excluded_samples"),
    "given_fit": ("imo_given_nomoto_fit", "imo_given_mmg_fit", "write_posterior_samples"),
})
