"""Seakeeping statistics: a ship's linear response to a sea, in frequency and time domains.

:mod:`.frequency_domain`
    the response spectral moments m0, m2, m4 over speed × heading from RAO tables
    (:func:`response_moments`) or the closed-form RAOs of a ship's particulars
    (:func:`closed_form_moments`), as :class:`ResponseMoments`.
:mod:`.response_statistics`
    the short-term statistics of a Gaussian response from its moments: significant
    amplitude and height, periods, bandwidth, exceedance, most probable maximum.
:mod:`.time_domain`
    the per-run statistics of a time-domain record with first-order wave motions
    (:func:`wave_motion_metrics`: RMS heave, pitch and roll), what a sweep's polar diagram
    is drawn from.

The names below are the submodules' own objects, each imported on first use (a run's metrics
do not import the spectral integration). ``seahelm.analysis.response_statistics`` and
``seahelm.analysis.wave_motion_metrics`` are deprecated paths to these modules (issue 47).
"""

from ..._optional import lazy_exports

__all__, __getattr__, __dir__ = lazy_exports(__name__, {
    "frequency_domain": ("ResponseMoments", "response_moments", "closed_form_moments",
                         "response_unit", "default_frequencies", "DATASET_FORMAT"),
    "response_statistics": ("significant_amplitude", "significant_height",
                            "zero_crossing_period", "crest_period", "spectral_bandwidth",
                            "upcrossing_rate", "exceedance_probability",
                            "most_probable_maximum"),
    "time_domain": ("wave_motion_metrics", "METRICS"),
})
