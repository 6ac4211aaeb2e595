"""seahelm.analysis."""

from ..errors import deprecated_modules

#: Modules moved to :mod:`seahelm.identification` (issue 47): the old paths warn and give the
#: module itself.
_MOVED = {old: f"seahelm.identification.{new}" for old, new in {
    "nomoto_fit": "nomoto_fit", "nomoto_fit_result": "nomoto_fit_result",
    "nomoto_posterior": "nomoto_posterior", "mmg_fit": "mmg_fit",
    "mmg_posterior": "mmg_posterior", "mmg_checks": "mmg_checks", "linear_fit": "linear_fit",
    "fit_statistics": "fit_result", "records": "records",
    "velocity_smoother": "velocity_smoother", "samples_file": "samples_file"}.items()}

#: Modules moved to :mod:`seahelm.analysis.equilibria` (issue 47, item 3): the same.
_MOVED.update({old: f"seahelm.analysis.equilibria.{old}" for old in (
    "equilibrium", "batch_equilibrium", "batch_steady_turn", "constant_speed", "linearisation",
    "heel")})

__getattr__ = deprecated_modules(__name__, _MOVED)
