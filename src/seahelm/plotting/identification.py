"""Figures of identification fits: measured and fitted output, and the residuals."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from .save import save_figure

__all__ = ["plot_nomoto_fit"]


def plot_nomoto_fit(fit: Any, records: Any, path: str | os.PathLike[str]) -> Path:
    """Measured and fitted heading (or yaw rate) of each record and the residuals below.

    Parameters
    ----------
    fit : NomotoFit
        The fit (:func:`seahelm.identification.nomoto_fit.fit_nomoto`).
    records : sequence of ManoeuvreRecord
        The records it was fitted to.
    path : str or os.PathLike
        Figure file (format from the suffix).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    import matplotlib.pyplot as plt

    n = len(records)
    fig, axes = plt.subplots(2, n, figsize=(5.5 * n, 5.2), squeeze=False, sharex="col",
                             height_ratios=(2.5, 1), layout="constrained")
    unit = "deg" if fit.output == "heading" else "deg/s"
    label = "heading ψ" if fit.output == "heading" else "yaw rate r"
    for k, (rec, res) in enumerate(zip(records, fit.residuals)):
        measured = rec.heading if fit.output == "heading" else rec.yaw_rate
        top, bottom = axes[0, k], axes[1, k]
        top.plot(rec.time, np.degrees(measured), ".", ms=2, color="0.5", label="measured")
        top.plot(rec.time, np.degrees(measured - res), color="C0",
                 label=f"Nomoto {fit.order} fit")
        top.plot(rec.time, np.degrees(rec.rudder_angle), color="C1", lw=0.8,
                 label="rudder angle δ [deg]")
        top.set_title(os.path.basename(rec.name), fontsize=9)
        top.set_ylabel(f"{label} [{unit}]")
        top.grid(alpha=0.3)
        bottom.plot(rec.time, np.degrees(res), color="C3", lw=0.8)
        bottom.axhline(0.0, color="0.3", lw=0.6)
        bottom.set_ylabel(f"residual [{unit}]")
        bottom.set_xlabel("time [s]")
        bottom.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8, loc="best")
    values = ", ".join(f"{s} = {v:.4g}" for s, v in zip(
        ("K" if fit.order == 1 else "K", *(("T",) if fit.order == 1 else ("T1", "T2", "T3"))),
        fit.values[:-1]))
    fig.suptitle(f"Nomoto {fit.order}, output-error fit\n{values}; δ0 = "
                 f"{math.degrees(fit.values[-1]):.3g} deg", fontsize=9)
    return save_figure(fig, path)
