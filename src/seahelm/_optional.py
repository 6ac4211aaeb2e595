"""One helper for optional imports: the error names the extra to install."""

from __future__ import annotations

import importlib
from types import ModuleType

from .errors import MissingDependencyError

_EXTRAS = {"control": "control", "distributed": "dask", "dask": "dask", "emcee": "mcmc"}


def optional_import(module: str, *, extra: str | None = None, purpose: str = "") -> ModuleType:
    """Import ``module`` or raise :class:`MissingDependencyError` naming the pip extra."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - exercised by monkeypatching in tests
        extra = extra or _EXTRAS.get(module.split(".")[0], module)
        why = f" for {purpose}" if purpose else ""
        raise MissingDependencyError(
            f"the optional dependency '{module}' is needed{why}; "
            f"install it with: pip install 'seahelm[{extra}]'"
        ) from exc
