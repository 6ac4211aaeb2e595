"""
Closed-form RAOs against a panel method: a box barge at zero speed
==================================================================

The heave and pitch RAOs of Jensen, Mansour & Olsen (2004) for a box of 100 × 20 × 5 m
(C_b = 1: the hull their closed form models exactly) beside capytaine's for the same box, read
from the database that seahelm ships (:func:`seahelm.environment.rao_io.box_barge_database`,
made by ``tools/capytaine/make_box_database.py``). Pitch is shown divided by k, the ratio to
the wave slope, which is 1 in long head or following waves. In beam seas the closed form is
drawn with both Smith factors: exp(−kT) (the default) and exp(−k_eT) (``smith="k_e"``, MSS's
transcription, 1 in beam seas); in head seas they coincide. The closed form's C_b = 1 is
outside the range Jensen et al. checked (0.5–0.9), hence the silenced warning.
"""

import math
import warnings

import matplotlib.pyplot as plt
import numpy as np

from seahelm.constants import GRAVITY
from seahelm.environment.rao import closed_form_rao
from seahelm.environment.rao_io import box_barge_database, read_rao
from seahelm.errors import ValidityRangeWarning
from seahelm.vessels.particulars import Particulars

bem = read_rao(box_barge_database())
box = Particulars(length=100.0, beam=20.0, draft=5.0, block_coefficient=1.0)
with warnings.catch_warnings():
    warnings.simplefilter("ignore", ValidityRangeWarning)
    closed = closed_form_rao(box, 0.0, frequency=bem.frequency, heading=bem.heading,
                             metacentric_height=4.1667)
    paper = closed_form_rao(box, 0.0, frequency=bem.frequency, heading=bem.heading,
                            metacentric_height=4.1667, smith="k_e")
w = bem.frequency
k = w * w / GRAVITY


def column(rao, dof, heading_deg):
    j = int(np.argmin(np.abs(np.degrees(rao.heading) - heading_deg)))
    return np.abs(rao.values[rao.dofs.index(dof), :, j])


fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharex=True)
panels = (("heave", 180.0, "heave, head seas [m/m]", 1.0),
          ("pitch", 180.0, "pitch / k, head seas [-]", 1.0 / k),
          ("heave", 90.0, "heave, beam seas [m/m]", 1.0))
for ax, (dof, heading, title, scale) in zip(axes, panels):
    ax.plot(w, column(bem, dof, heading) * scale, "k-", label="capytaine 3.0 (panels)")
    ax.plot(w, column(closed, dof, heading) * scale, "C1--",
            label="Jensen et al. (2004), exp(-kT)")
    if heading == 90.0:
        ax.plot(w, column(paper, dof, heading) * scale, "C0:", label="exp(-k_e T)")
        ax.legend()
    ax.axvline(math.sqrt(math.pi * GRAVITY / 100.0), color="0.7", lw=0.8)  # λ = 2L
    ax.set_title(title)
    ax.set_xlabel("wave frequency ω [rad/s]")
    ax.grid(alpha=0.3)
axes[0].legend()
fig.tight_layout()
plt.show()
