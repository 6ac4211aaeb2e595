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

__all__ = [
    "__version__",
    "SeahelmError",
    "ParameterError",
    "ValidityRangeWarning",
    "SimulationDiverged",
    "MissingDependencyError",
    "strict_validity",
]
