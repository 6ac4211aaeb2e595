"""
Sea-wave spectra and realisations (Sushchenko & Lutsko, 2010)
=============================================================

The paper's figure drawn with the corrected models: ordinate and slope spectra of the two
Rakhmanin–Firsov variants for sea states III, VI and IX, and slope realisations from the
corrected shaping filter and from the paper's printed eq. (7).
"""

from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.studies.sushchenko2010 import plot_paper_figure

spec = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0)
print(f"variance D_r = {spec.variance:.4f} m², zeroth moment of S₁ = {spec.moment(0):.4f} m²")

# %%
fig = plot_paper_figure(seed=1)
