"""seahelm — batched, validated ship motion simulation and control.

Nothing heavy is imported at import time: subpackages load on first use.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("seahelm")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

from .errors import (  # noqa: E402
    MissingDependencyError,
    ParameterError,
    SeahelmError,
    SimulationDiverged,
    ValidityRangeWarning,
    strict_validity,
)

# The public API, imported on first use (``import seahelm`` stays light: no numba, no xarray).
# A user's objects first: ships, the request and the run, manoeuvres, the IMO check,
# linearisation and identification; then the lower-level pieces.
_USER_API = {
    "Ship": "seahelm.ships.ship",
    "get_ship": "seahelm.ships",
    "read_ship": "seahelm.ships",
    "Design": "seahelm.ships.estimate",
    "estimate_ship": "seahelm.ships.estimate",
    "Problem": "seahelm.simulation.problem",
    "simulate": "seahelm.simulation.engine",
    "Simulator": "seahelm.simulation.stepping",
    "turning_circle": "seahelm.analysis.maneuvers",
    "zigzag": "seahelm.analysis.maneuvers",
    "spirals": "seahelm.analysis.maneuvers",
    "pull_out": "seahelm.analysis.maneuvers",
    "crash_stop": "seahelm.analysis.maneuvers",
    "imo_check": "seahelm.analysis.imo",
    "linearize": "seahelm.analysis.equilibria.linearisation",
    "read_records": "seahelm.identification.records",
    "fit_nomoto": "seahelm.identification.nomoto_fit",
    "regress_hull": "seahelm.identification.mmg_fit",
    "refine_mmg": "seahelm.identification.mmg_fit",
}
_LAZY = {
    **_USER_API,
    "RunStatus": "seahelm.simulation.engine",
    "BatchLayout": "seahelm.simulation.batch",
    "simulate_batch": "seahelm.simulation.batch",
    "SimResult": "seahelm.results",
    "load_result": "seahelm.results",
    "flatten_runs": "seahelm.results",
    "load_scenario": "seahelm.scenario",
    "parse_scenario": "seahelm.scenario",
    "run_scenario": "seahelm.scenario",
    "get_model": "seahelm.registry",
    "get_actuator": "seahelm.registry",
    "get_controller": "seahelm.registry",
    "catalog": "seahelm.ships.catalog",  # the module itself
    "wrap_angle": "seahelm.constants",
}

__all__ = [
    *_USER_API,
    "__version__",
    "SeahelmError",
    "ParameterError",
    "ValidityRangeWarning",
    "SimulationDiverged",
    "MissingDependencyError",
    "strict_validity",
    *(name for name in _LAZY if name not in _USER_API),
]


#: Old names, deprecated: a DeprecationWarning naming the replacement on access.
_DEPRECATED = {"RunBatch": ("seahelm.simulation.problem", "Problem", "seahelm.Problem")}


def __getattr__(name: str):  # PEP 562: lazy public API
    module = _LAZY.get(name)
    if module is None:
        if name in _DEPRECATED:
            from .errors import deprecated_names

            return deprecated_names("seahelm", _DEPRECATED, stacklevel=3)(name)
        raise AttributeError(f"module 'seahelm' has no attribute {name!r}")
    import importlib

    mod = importlib.import_module(module)
    value = mod if module.rsplit(".", 1)[-1] == name else getattr(mod, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
