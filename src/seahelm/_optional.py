"""One helper for optional imports (the error names the extra to install), and one for a
package's names imported from its submodules on first use."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping, Sequence
from types import ModuleType
from typing import Any

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


def lazy_exports(package: str, exports: Mapping[str, Sequence[str]]) -> tuple[
        list[str], Callable[[str], Any], Callable[[], list[str]]]:
    """The public names of a package that live in its submodules, each imported on first use.

    A subpackage's ``__init__`` names what it exports and where each name is defined, and
    importing the package (or one of its submodules) imports no other submodule: a light
    submodule (a result file's reader) stays light beside a heavy one (a check that compiles
    kernels). The names are the submodules' own objects, cached in the package on first access.

    Parameters
    ----------
    package : str
        The package (``__name__`` of its ``__init__``).
    exports : mapping of str to sequence of str
        Submodule name (relative to ``package``) -> the names it exports.

    Returns
    -------
    tuple
        ``(__all__, __getattr__, __dir__)`` to assign in the package's ``__init__``
        (PEP 562).

    Raises
    ------
    ValueError
        If a name is exported twice or is also the name of a submodule (importing that
        submodule would replace the name in the package).
    """
    home: dict[str, str] = {}
    for submodule, names in exports.items():
        for name in names:
            if name in home or name in exports:
                raise ValueError(f"{package}: the name {name!r} is exported twice or is also "
                                 "a submodule's name")
            home[name] = submodule

    def __getattr__(name: str) -> Any:
        if name not in home:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        import sys

        value = getattr(importlib.import_module(f"{package}.{home[name]}"), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        import sys

        return sorted(set(vars(sys.modules[package])) | set(home))

    return list(home), __getattr__, __dir__
