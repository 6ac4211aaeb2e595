"""seahelm.analysis: what is computed from simulated (and measured) runs, one subpackage a
concept.

:mod:`~seahelm.analysis.equilibria`
    the steady motions of a model (self-propulsion, straight approach, steady turn, the roll
    balance of a steady heel) and the linearisation there;
:mod:`~seahelm.analysis.maneuvers`
    the standard manoeuvres (turning circle, zig-zag, spirals, pull-out, crash stop) and the
    metrics of recorded tracks (advance and transfer, course keeping, settling, overshoot);
:mod:`~seahelm.analysis.imo`
    the IMO MSC.137(76) check of a ship, and of an ensemble (probabilities, Monte-Carlo,
    given an identification);
:mod:`~seahelm.analysis.seakeeping`
    seakeeping statistics: response spectral moments, short-term statistics, the per-run
    statistics of records with first-order motions;
:mod:`~seahelm.analysis.replay`
    measured records replayed (and the stops in them, and the multi-record fit built on
    replayed segments);
:mod:`~seahelm.analysis.steering`
    Nomoto's steering indices of a linearised ship and the autopilots designed from them;
:mod:`~seahelm.analysis.dp`
    DP station-keeping capability after DNV-ST-0111, levels 1 and 3;
:mod:`~seahelm.analysis.statistics`
    the statistics of a batch's per-run metrics (the Monte-Carlo tables, the report, sweeps).

Modules that moved keep their old path as a deprecated alias (a :class:`DeprecationWarning`
naming the new module, which is given itself).
"""

from ..errors import deprecated_modules

#: Modules moved to :mod:`seahelm.identification` (issue 47): the old paths warn and give the
#: module itself.
_MOVED = {old: f"seahelm.identification.{new}" for old, new in {
    "nomoto_fit": "nomoto_fit", "nomoto_fit_result": "nomoto_fit_result",
    "nomoto_posterior": "nomoto_posterior", "mmg_fit": "mmg_fit",
    "mmg_posterior": "mmg_posterior", "mmg_checks": "mmg_checks", "linear_fit": "linear_fit",
    "fit_statistics": "fit_result", "records": "records",
    "velocity_smoother": "velocity_smoother", "samples_file": "samples_file"}.items()}

#: Modules regrouped into the subpackages of :mod:`seahelm.analysis` (issue 47, item 2): the old
#: paths warn and give the module itself.
_REGROUPED = {
    "imo_probability": "seahelm.analysis.imo.probability",
    "imo_monte_carlo": "seahelm.analysis.imo.monte_carlo",
    "imo_ensemble": "seahelm.analysis.imo.ensemble",
    "imo_given_fit": "seahelm.analysis.imo.given_fit",
    "response_statistics": "seahelm.analysis.seakeeping.response_statistics",
    "wave_motion_metrics": "seahelm.analysis.seakeeping.time_domain",
    "replay_dataset": "seahelm.analysis.replay.dataset",
    "reversals": "seahelm.analysis.replay.reversals",
    "record_segments": "seahelm.analysis.replay.segments",
    "mmg_multi_record": "seahelm.analysis.replay.mmg_multi_record",
    "turning": "seahelm.analysis.maneuvers.advance_transfer",
    "course_keeping": "seahelm.analysis.maneuvers.course_keeping",
    "steering_indices": "seahelm.analysis.steering.indices",
    "autopilot_tuning": "seahelm.analysis.steering.autopilot_tuning",
    "dp_capability": "seahelm.analysis.dp.level1",
    "dp_capability_level3": "seahelm.analysis.dp.level3",
    # generic numerics (no ship): below everything
    "nonsmooth": "seahelm.numerics.nonsmooth",
    # used by Platonov & Platonova's study only: beside it
    "averaging": "seahelm.studies.platonov.averaging",
}

#: Modules moved to :mod:`seahelm.analysis.equilibria` (issue 47, item 3): the same.
_MOVED.update({old: f"seahelm.analysis.equilibria.{old}" for old in (
    "equilibrium", "batch_equilibrium", "batch_steady_turn", "constant_speed", "linearisation",
    "heel")})

__getattr__ = deprecated_modules(__name__, {**_MOVED, **_REGROUPED})
