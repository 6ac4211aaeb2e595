"""Saving a figure: atomically, in the format its file name asks for, and closed after.

The one figure-saving path of the package (the CLI's commands all write through it). The
format comes from the suffix (``.png``, ``.pdf``, ``.svg``, … whatever the canvas supports), so
``--out figure.pdf`` writes a PDF, not PNG bytes under a PDF name; an unsupported suffix is an
error naming the supported ones, raised before anything is drawn or written. The file appears
only complete (:func:`seahelm.results.atomic_write`).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..errors import ParameterError

__all__ = ["save_figure", "check_figure_path"]


def check_figure_path(path: str | os.PathLike[str]) -> Path:
    """The path a figure will be written to (``.png`` appended to a name without a suffix),
    checked: its suffix names a format matplotlib writes.

    Parameters
    ----------
    path : str or os.PathLike
        Destination.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ParameterError
        For a suffix matplotlib cannot write, naming the supported ones.
    """
    from matplotlib.backend_bases import FigureCanvasBase

    path = Path(path)
    if not path.suffix:
        path = path.with_suffix(".png")
    supported = FigureCanvasBase.get_supported_filetypes()
    if path.suffix[1:].lower() not in supported:
        raise ParameterError(f"cannot write a figure as '{path.suffix}' ({path}); supported: "
                             + ", ".join(f".{k}" for k in sorted(supported)))
    return path


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: float = 110.0,
                close: bool = True, force: bool = False) -> Path:
    """Write ``fig`` to ``path`` atomically in the format of the path's suffix.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (an ``Axes`` is accepted too: its figure is saved).
    path : str or os.PathLike
        Destination; its suffix chooses the format (no suffix: PNG, and ``.png`` is appended).
    dpi : float, optional
        Resolution of raster formats [dots per inch] (default 110).
    close : bool, optional
        Close the figure afterwards, also when writing fails (default True).
    force : bool, optional
        Replace an existing file that is not a figure seahelm wrote (default False; the
        output policy, :func:`seahelm.output_files.check_output`).

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ParameterError
        If the suffix names a format the figure's canvas cannot write.
    """
    import matplotlib.pyplot as plt

    from .. import __version__
    from ..output_files import FIGURE_METADATA, write_output

    fig = getattr(fig, "figure", fig)
    path = Path(path)
    if not path.suffix:
        path = path.with_suffix(".png")
    fmt = path.suffix[1:].lower()
    try:
        supported = fig.canvas.get_supported_filetypes()
        if fmt not in supported:
            raise ParameterError(
                f"cannot write a figure as '{path.suffix}' ({path}); supported: "
                + ", ".join(f".{k}" for k in sorted(supported)))
        # seahelm's name in the file's metadata: its own figure, replaced again without force
        meta = ({FIGURE_METADATA[fmt]: f"seahelm {__version__}"} if fmt in FIGURE_METADATA
                else None)
        return write_output(path, lambda tmp: fig.savefig(tmp, dpi=dpi, format=fmt,
                                                          metadata=meta), "figure", force=force)
    finally:
        if close:
            plt.close(fig)
