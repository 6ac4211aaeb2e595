"""The IMO check of an ensemble as a figure: the distribution of every criterion's value.

One panel per IMO quantity (advance, tactical diameter, initial turning, the zig-zags'
overshoots, the stopping track reach): histograms of the counted members' values, starboard
and port drawn as steps in one panel, the criterion's limit as a vertical line and the
probability of passing it (with its Wilson interval) in the panel's title; a member passes
where its value lies left of the line (MSC.137(76): value <= limit). The figure is
``imo-probabilities.png`` of ``seahelm imo SHIP --monte-carlo N --out DIR``; its data is
the Dataset of :func:`seahelm.analysis.imo.ensemble.ensemble_dataset`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["plot_imo_ensemble"]

#: Side -> (colour, line style) of a panel's histograms.
_SIDES = {"starboard": ("tab:green", "-"), "port": ("tab:red", "--"), "-": ("tab:blue", "-")}


def plot_imo_ensemble(ds: Any, *, fig: Any = None) -> Any:
    """Histograms of an ensemble's IMO values, one panel per quantity, limits marked.

    Parameters
    ----------
    ds : xarray.Dataset
        An ensemble check (:func:`seahelm.analysis.imo.ensemble.ensemble_dataset`, or
        ``imo-probabilities.nc`` opened).
    fig : matplotlib.figure.Figure, optional
        Drawn on (default: a new figure).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If ``ds`` is not the Dataset of an ensemble check.
    """
    import matplotlib.pyplot as plt

    from ..analysis.imo.ensemble import is_ensemble_dataset

    if not is_ensemble_dataset(ds):
        raise ValueError("not the Dataset of an IMO ensemble check (ensemble_dataset)")
    values = np.asarray(ds["value"].values, dtype=float)
    complete = np.asarray(ds["complete"].values, dtype=bool)
    quantities: dict[tuple[str, str], list[int]] = {}
    for k, (ability, quantity) in enumerate(zip(ds["ability"].values, ds["quantity"].values)):
        quantities.setdefault((str(ability), str(quantity)), []).append(k)
    n_panels = len(quantities)
    cols = 2 if n_panels > 1 else 1
    rows = max(1, math.ceil(n_panels / cols))
    if fig is None:
        fig = plt.figure(figsize=(10, 2.6 * rows + 0.8), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax, ((ability, quantity), ks) in zip(axes, quantities.items()):
        counted = values[complete][:, ks]
        finite = counted[np.isfinite(counted)]
        limit = float(ds["limit"].values[ks[0]])
        low = min([limit, *finite]) if finite.size else limit
        high = max([limit, *finite]) if finite.size else limit
        pad = 0.05 * (high - low) or 0.05 * max(abs(limit), 1.0)
        bins = np.linspace(low - pad, high + pad, 31)
        probabilities = []
        for k in ks:
            side = str(ds["side"].values[k])
            color, style = _SIDES.get(side, ("tab:gray", "-"))
            member = values[complete, k]
            ax.hist(member[np.isfinite(member)], bins=bins, histtype="step", color=color,
                    linestyle=style, linewidth=1.4,
                    label=side if side != "-" else None)
            probabilities.append(
                f"{'' if side == '-' else side + ' '}{float(ds['probability'].values[k]):.3f} "
                f"({float(ds['ci_low'].values[k]):.2f}..{float(ds['ci_high'].values[k]):.2f})")
        unit = str(ds["unit"].values[ks[0]])
        ax.axvline(limit, color="black", linewidth=1.2, label=f"limit {limit:.4g} {unit}")
        ax.set_xlabel(f"{quantity} [{unit}]")
        ax.set_ylabel("samples")
        ax.set_title(f"{ability}: {quantity}\nP(pass) " + ", ".join(probabilities), fontsize=9)
        ax.legend(fontsize=8, loc="best")
        ax.grid(True, alpha=0.3)
    for ax in axes[n_panels:]:
        ax.set_visible(False)
    title = str(ds.attrs.get("title") or "IMO MSC.137(76) of an ensemble")
    fig.suptitle(f"{title}\nall evaluated criteria: P(pass) = "
                 f"{float(ds.attrs['all_probability']):.3f} over {int(ds.attrs['n_counted'])} "
                 f"counted sample(s), {int(ds.attrs['n_excluded'])} excluded", fontsize=10)
    return fig
