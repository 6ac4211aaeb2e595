"""seahelm.identification: every estimator, record reader and fit result.

- Records: :mod:`~seahelm.identification.records` (:class:`ManoeuvreRecord`, the readers of
  every record format: CSV, NetCDF, a seahelm result, the steady-turn log).
- Fit results: :mod:`~seahelm.identification.fit_result` (the base every result shares:
  standard errors, correlations, intervals, the evidence for what is not identified).
- Nomoto: :mod:`~seahelm.identification.nomoto_fit` (output error),
  :mod:`~seahelm.identification.nomoto_fit_result`,
  :mod:`~seahelm.identification.nomoto_posterior`.
- MMG hull: :mod:`~seahelm.identification.mmg_fit` (regression, output error),
  :mod:`~seahelm.identification.mmg_checks`, :mod:`~seahelm.identification.mmg_posterior`,
  :mod:`~seahelm.identification.velocity_smoother` (velocities from positions);
  :mod:`~seahelm.identification.linear_fit` (the linear sway–yaw model);
  :mod:`~seahelm.identification.samples_file` (posterior samples on disk).
- :mod:`~seahelm.identification.reduced`: Romanov & Chirkova's reduced steady-turn model
  (steady turns of Voitkunsky's model, the reduced forms and their fits).
"""

from ..errors import deprecated_modules

#: Modules of the reduced steady-turn model, moved into :mod:`.reduced`, and the turn log's
#: reader, now in :mod:`.records` with every record reader (issue 47): the old paths warn and
#: give the module itself.
_MOVED = {**{old: f"seahelm.identification.reduced.{new}" for old, new in {
    "criteria": "criteria", "fitting": "fitting", "reduced_forms": "forms",
    "segments": "segments", "steady_turns": "turns"}.items()},
          "turn_log": "seahelm.identification.records"}

__getattr__ = deprecated_modules(__name__, _MOVED)
