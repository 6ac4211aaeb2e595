"""Steering of a linearised ship: Nomoto's indices and course stability, and the heading and
track autopilots designed from them.

:mod:`.indices`
    :func:`steering_indices` of a :class:`~seahelm.analysis.equilibria.linearisation.LinearModel`:
    Nomoto's K, T_1, T_2, T_3 and T, the course-stability lever, as :class:`SteeringIndices`.
:mod:`.autopilot_tuning`
    :func:`tune_autopilot`: linearise, take K and T, design the ``pid-heading``, ``lq-heading``
    or ``lq-cross-track`` gains, check the closed loop, write a scenario
    (:class:`AutopilotTuning`; what ``seahelm autopilot tune`` calls).

The names below are the submodules' own objects, each imported on first use.
``seahelm.analysis.steering_indices`` and ``seahelm.analysis.autopilot_tuning`` are deprecated
paths to these modules (issue 47).
"""

from ..._optional import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {
    "indices": ("SteeringIndices", "steering_indices", "NON_STEERING_STATES", "ROLL_STATES"),
    "autopilot_tuning": ("DESIGNS", "MAX_PERIOD_SHARE", "AutopilotTuning", "tune_autopilot",
                         "cross_track_loop_poles", "cross_track_settles", "scenario_duration",
                         "settling_time", "scenario_toml", "poles_text"),
})
