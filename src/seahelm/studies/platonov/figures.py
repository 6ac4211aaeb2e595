"""The paper's figures: the averaged control set V and its flat approximation Y (Platonov &
Platonova, Figs. 1 and 2) and the averaging error against ε. matplotlib is imported inside the
functions."""

from __future__ import annotations

from typing import Any

import numpy as np

from .flat_set import FlatVariant, get_flat_variant

__all__ = ["plot_set_V", "plot_set_Y", "plot_control_sets", "plot_averaging_study"]


def _axes3d(ax: Any = None, fig: Any = None) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    fig = fig if fig is not None else plt.figure(figsize=(6, 5))
    return fig.add_subplot(projection="3d")


def _label(ax: Any, title: str) -> None:
    from matplotlib.ticker import MaxNLocator

    ax.set_xlabel("ς1 = ⟨p c1⟩", labelpad=8)
    ax.set_ylabel("ς2 = ⟨p c2⟩", labelpad=8)
    ax.set_zlabel("ς3 = ⟨p² c2⟩", labelpad=8)
    # the default 0.25 steps crowd the foreshortened horizontal axes into overlapping labels
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
    ax.tick_params(labelsize=8)
    ax.set_title(title)


def plot_set_V(result: Any, *, ax: Any = None, fig: Any = None, **surface_kw: Any) -> Any:
    """Boundary of V, ς(z) on the direction grid of eq. (17), as a 3-D surface (Fig. 1).

    ``result`` is a :class:`seahelm.studies.platonov.flat_set.CPPControlSetResult`. Returns the axes.

    Parameters
    ----------
    result : CPPControlSetResult
        Result with the boundary ς(z) on the direction grid.
    ax : matplotlib Axes3D, optional
        Axes to draw into (default: new 3-D axes).
    fig : matplotlib Figure, optional
        Figure for the new axes when ``ax`` is None.
    **surface_kw
        Passed to ``plot_surface``.

    Returns
    -------
    matplotlib Axes3D
    """
    ax = _axes3d(ax, fig)
    s = result.boundary
    kw = {"cmap": "viridis", "linewidth": 0, "antialiased": True, "alpha": 0.9}
    kw.update(surface_kw)
    ax.plot_surface(s[..., 0], s[..., 1], s[..., 2], **kw)
    _label(ax, "V (Platonov & Platonova, Fig. 1)")
    return ax


def plot_set_Y(
    betas: Any, *, variant: str | FlatVariant = "hull", n: int = 101, ax: Any = None,
    fig: Any = None, **surface_kw: Any,
) -> Any:
    """The flat set Y of eq. (24) as a 3-D surface (Fig. 2).

    The convex hull of the arc (β1 t, β2 t, β3 t²), t ∈ [-1, 1]: the arc is a parabola in the
    plane β2 y1 = β1 y2, and its hull, drawn as the union of the chords between t and −t, is
    the flat region between the parabola and the chord y3 = β3; plus what the reading of
    eq. (24) adds to it (:meth:`~seahelm.studies.platonov.flat_set.FlatVariant.extra_segment`):
    nothing for ``"hull"``, the printed segment y1 = y2 ∈ [-1, 1], y3 = β3 (which does not meet
    the arc, see the errata) for ``"printed"``.

    Parameters
    ----------
    betas : sequence of float
        (β1, β2, β3) [-] of :func:`~seahelm.studies.platonov.control_set.cpp_betas`.
    variant : str or FlatVariant, optional
        Reading of eq. (24): a name of
        :data:`~seahelm.studies.platonov.flat_set.FLAT_VARIANTS` (default "hull") or the object.
    n : int, optional
        Number of chord positions t ∈ [0, 1] (default 101).
    ax : matplotlib Axes3D, optional
        Axes to draw into (default: new 3-D axes).
    fig : matplotlib Figure, optional
        Figure for the new axes when ``ax`` is None.
    **surface_kw
        Passed to ``plot_surface``.

    Returns
    -------
    matplotlib Axes3D
    """
    reading = get_flat_variant(variant)
    ax = _axes3d(ax, fig)
    b1, b2, b3 = (float(b) for b in betas)
    t = np.linspace(0.0, 1.0, n)
    s = np.linspace(-1.0, 1.0, 21)[:, None]
    x = s * b1 * t
    y = s * b2 * t
    zz = np.broadcast_to(b3 * t * t, x.shape)
    kw = {"color": "tab:orange", "alpha": 0.6, "linewidth": 0}
    kw.update(surface_kw)
    ax.plot_surface(x, y, zz, **kw)
    tt = np.linspace(-1, 1, 201)
    ax.plot(b1 * tt, b2 * tt, b3 * tt * tt, color="k", lw=1.5, label="arc (β1 t, β2 t, β3 t²)")
    extra = reading.extra_segment(b3)
    if extra is not None:
        ax.plot(*extra.T, color="tab:red", lw=2, label=f"{reading.name} segment")
    ax.legend(loc="upper left")
    _label(ax, "Y (Platonov & Platonova, Fig. 2, eq. (24))")
    return ax


def plot_control_sets(result: Any, *, fig: Any = None) -> Any:
    """V (left) and both variants of Y (right) side by side; returns the figure.

    Parameters
    ----------
    result : CPPControlSetResult
        Result with the boundary of V, the β's and the Hausdorff distances.
    fig : matplotlib Figure, optional
        Figure to draw into (default: a new one).

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt

    fig = fig if fig is not None else plt.figure(figsize=(12, 5))
    ax1 = fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = fig.add_subplot(1, 2, 2, projection="3d")
    plot_set_V(result, ax=ax1)
    plot_set_Y(result.betas, variant="printed", ax=ax2)
    ax2.set_title(
        f"Y: d_H(V, hull) = {result.hausdorff_V_Y:.4f}, "
        f"d_H(V, printed) = {result.hausdorff_V_Y_printed:.4f}",
        fontsize=9,
    )
    fig.tight_layout()
    return fig


def plot_averaging_study(study: Any, *, ax: Any = None) -> Any:
    """Error of the averaged model against ε on log-log axes, with the fitted order.

    Parameters
    ----------
    study : AveragingStudy
        Result of :func:`~seahelm.studies.platonov.averaged_system.cpp_averaging_study`.
    ax : matplotlib Axes, optional
        Axes to draw into (default: new axes).

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(study.epsilons, study.errors, "o-", label=f"order {study.order:.2f}")
    ax.set_xlabel("ε = 1/A")
    ax.set_ylabel("max |x − x̄|")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return ax
