"""The versions seahelm runs with: for bug reports, CI logs and reproducible environments.

:func:`dependency_versions` reads installed distributions' metadata (nothing heavy is
imported); ``seahelm --version`` prints them, and ``make test`` prints them before the suite so
every CI log says what it tested.
"""

from __future__ import annotations

import platform
from importlib.metadata import PackageNotFoundError, version

__all__ = ["CORE_DEPENDENCIES", "dependency_versions", "version_report"]

CORE_DEPENDENCIES: tuple[str, ...] = ("numpy", "scipy", "numba", "llvmlite", "xarray",
                                      "h5netcdf", "h5py", "zarr", "pydantic", "typer",
                                      "rich", "matplotlib", "plotly")
"""The distributions whose versions decide seahelm's numerical results and behaviour (rich
renders the command's help and tables, plotly the HTML report's plots)."""


def dependency_versions(names: tuple[str, ...] = CORE_DEPENDENCIES) -> dict[str, str]:
    """Installed versions of Python, seahelm and ``names`` ("not installed" where absent).

    Parameters
    ----------
    names : tuple of str, optional
        Distribution names (default :data:`CORE_DEPENDENCIES`).

    Returns
    -------
    dict of str to str
        ``{"python": "3.11.7", "seahelm": "0.1.0", "numpy": ..., ...}`` in that order.
    """
    out = {"python": platform.python_version()}
    for name in ("seahelm", *names):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "not installed"
    return out


def version_report() -> str:
    """One line ``name version`` pair after another, e.g. ``python 3.11.7, numpy 2.4.6, ...``.

    Returns
    -------
    str
    """
    return ", ".join(f"{k} {v}" for k, v in dependency_versions().items())


if __name__ == "__main__":  # pragma: no cover - `python -m seahelm.versions`
    print(version_report())
