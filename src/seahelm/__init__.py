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
_LAZY = {
    "simulate": "seahelm.simulation.engine",
    "RunStatus": "seahelm.simulation.engine",
    "RunBatch": "seahelm.simulation.batch",
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
    "__version__",
    "SeahelmError",
    "ParameterError",
    "ValidityRangeWarning",
    "SimulationDiverged",
    "MissingDependencyError",
    "strict_validity",
    *_LAZY,
]


def __getattr__(name: str):  # PEP 562: lazy public API
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'seahelm' has no attribute {name!r}")
    import importlib

    mod = importlib.import_module(module)
    value = mod if module.rsplit(".", 1)[-1] == name else getattr(mod, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
