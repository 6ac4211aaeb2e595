"""The polar seakeeping diagram from a time-domain sweep, with each cell's sampling uncertainty.

A sweep of a scenario with first-order wave motions (``[environment.waves]
first_order_motions = true``) over the wave direction (``environment.waves.direction_deg``, or
the ship's course ``controller.reference.heading_deg``) × a speed knob (any other grid key: the
shaft speed, a model's speed), with seeded runs per cell (``[batch.monte_carlo] runs``), stores
each run's RMS heave, pitch and roll, mean surge speed and mean wave heading relative to the
ship (:mod:`seahelm.analysis.seakeeping.time_domain`). Per cell, with R runs of mean squares
x_r = RMS_r²::

    m̂0 = (1/R) Σ x_r,      se(m̂0) = σ̂/√R,   σ̂² = Σ (x_r − m̂0)²/(R − 1)

m̂0 estimates the variance m0 = ∫∫|H|²S D dθ dω of the frequency domain without bias
(:mod:`seahelm.environment.first_order`); the runs are independent, so m̂0 is normal to within
the central limit theorem and m̂0 lies within 3 se of m0 with 99.7 %. RMS = √m̂0 with
se(RMS) = se(m̂0)/(2√m̂0) (first order); significant amplitude 2√m̂0. A cell's speed is the
mean of its runs' mean surge speeds, its heading the circular mean of their mean wave
headings (ε: 0 following, 180° head, 90° waves travelling to starboard) — the sea and the
autopilot make them differ a little from cell to cell.

:func:`frequency_domain_moments` gives the frequency-domain m0 of the same cells: the RAO
tables the time-domain pass uses (:func:`~seahelm.environment.rao.closed_form_rao` at the
cell's speed, interpolated as :meth:`RAO.__call__ <seahelm.environment.rao.RAO.__call__>`
does, or the scenario's ``rao_file`` at every speed), the scenario's sea and spreading,
integrated over the pass's frequency band (:func:`seahelm.analysis.seakeeping.
response_moments`); motions after the run or in the loop (``autopilot_sees_first_order``)
alike.

Statistics over the whole record: a run that starts away from its steady speed or heading
puts its transient into its cell (start the runs near their steady state).
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..errors import ParameterError, ValidityRangeWarning, deprecated_method

__all__ = ["SweepSeakeeping", "sweep_seakeeping", "frequency_domain_moments", "DOF_METRICS",
           "HEADING_KEYS", "DATASET_FORMAT"]

#: The ``format`` attribute of :meth:`SweepSeakeeping.to_xarray`.
DATASET_FORMAT = "seahelm-seakeeping-sweep-1"

#: Degree of freedom -> (the per-run metric, its factor to SI, the SI unit, description).
DOF_METRICS: dict[str, tuple[str, float, str, str]] = {
    "heave": ("rms_heave_m", 1.0, "m", "first-order heave"),
    "pitch": ("rms_pitch_deg", math.pi / 180.0, "rad", "first-order pitch"),
    "roll": ("rms_roll_wave_deg", math.pi / 180.0, "rad", "first-order roll"),
    "roll_total": ("rms_roll_deg", math.pi / 180.0, "rad",
                   "total roll (model roll + first-order roll)"),
}
#: Grid keys that set the wave heading relative to the ship.
HEADING_KEYS = ("environment.waves.direction_deg", "controller.reference.heading_deg",
                "controller.reference.heading")


@dataclasses.dataclass(frozen=True, eq=False)
class SweepSeakeeping:
    """RMS motions per (speed, heading) cell of a time-domain sweep (module docstring).

    Rows go by increasing speed, columns by increasing mean wave heading round the circle,
    starting after the largest gap between the headings (180°, 225°, ..., 360° for a sweep
    of the starboard side and 0°).

    Attributes
    ----------
    dofs : tuple of str
        ``heave``, ``pitch``, ``roll`` (first-order) and, where stored, ``roll_total``.
    speed : numpy.ndarray, shape (n_speed, n_heading)
        The cells' mean surge speeds [m/s].
    heading : numpy.ndarray, shape (n_speed, n_heading)
        Their mean wave headings relative to the ship, in [0, 2π) [rad].
    n_runs : numpy.ndarray of int, shape (n_speed, n_heading)
        Runs per cell with finite statistics (diverged runs are left out).
    mean_square : numpy.ndarray, shape (n_dof, n_speed, n_heading)
        m̂0 [u²] (u: m for heave, rad for the angles).
    standard_error : numpy.ndarray, shape (n_dof, n_speed, n_heading)
        σ̂/√R of m̂0 [u²].
    speed_key, heading_key : str or None
        The grid keys of the rows and columns (None: one speed).
    speed_values, heading_values : numpy.ndarray
        Their grid values, in the rows' and columns' order.
    description : dict
        The store, the scenario's title, the runs.
    frequency_domain : numpy.ndarray or None, shape (n_dof, n_speed, n_heading)
        The frequency-domain m0 of the cells (:func:`frequency_domain_moments`; NaN for
        ``roll_total``), when computed.
    """

    dofs: tuple[str, ...]
    speed: np.ndarray
    heading: np.ndarray
    n_runs: np.ndarray
    mean_square: np.ndarray
    standard_error: np.ndarray
    speed_key: str | None
    heading_key: str
    speed_values: np.ndarray
    heading_values: np.ndarray
    description: dict = dataclasses.field(default_factory=dict)
    frequency_domain: np.ndarray | None = None

    def _index(self, dof: str) -> int:
        if dof not in self.dofs:
            raise ParameterError(f"is not in the sweep; it has {', '.join(self.dofs)}",
                                 field="dof", value=dof)
        return self.dofs.index(dof)

    def rms(self, dof: str) -> np.ndarray:
        """√m̂0 [u] over (speed, heading).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        return np.sqrt(self.mean_square[self._index(dof)])

    def rms_standard_error(self, dof: str) -> np.ndarray:
        """se(RMS) = se(m̂0)/(2√m̂0) [u] (NaN where the RMS is 0).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        i = self._index(dof)
        rms = np.sqrt(self.mean_square[i])
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(rms > 0, self.standard_error[i] / (2.0 * rms), np.nan)

    def significant_amplitude(self, dof: str) -> np.ndarray:
        """2√m̂0 [u].

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        return 2.0 * self.rms(dof)

    def frequency_domain_rms(self, dof: str) -> np.ndarray:
        """√m0 of the frequency domain [u] (NaN without it).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        i = self._index(dof)
        if self.frequency_domain is None:
            return np.full(self.speed.shape, np.nan)
        return np.sqrt(self.frequency_domain[i])

    def deviation(self, dof: str) -> np.ndarray:
        """(m̂0 − m0)/se(m̂0): the time domain's departure from the frequency domain in
        standard errors (within ±3 with 99.7 % when they agree).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        i = self._index(dof)
        if self.frequency_domain is None:
            return np.full(self.speed.shape, np.nan)
        with np.errstate(divide="ignore", invalid="ignore"):
            return (self.mean_square[i] - self.frequency_domain[i]) / self.standard_error[i]

    @property
    def row_speed(self) -> np.ndarray:
        """Mean speed of each row [m/s] (the polar diagram's radii)."""
        return np.mean(self.speed, axis=1)

    @property
    def column_heading(self) -> np.ndarray:
        """Circular mean heading of each column [rad], increasing from the first column (in
        [0, 2π), the later ones + 2π where they pass 2π): the polar diagram's angles."""
        from scipy.stats import circmean

        h = circmean(self.heading, axis=0)
        h = np.where(np.abs(h - 2.0 * math.pi) < 1e-9, 0.0, h)
        return h + 2.0 * math.pi * (np.cumsum(np.append(0.0, np.diff(h)) < 0) > 0)

    to_dataset = deprecated_method("to_xarray", "one name for it across seahelm")

    def to_xarray(self) -> Any:
        """The cells as an :class:`xarray.Dataset` over (dof, speed_index, heading_index).

        Returns
        -------
        xarray.Dataset
            ``mean_square``, ``standard_error``, ``rms``, ``rms_standard_error``,
            ``significant_amplitude`` (and ``frequency_domain_m0``), ``speed``, ``heading``,
            ``n_runs``; SI units.
        """
        import xarray as xr

        dims = ("dof", "speed_index", "heading_index")
        units = ", ".join(f"{d}: {DOF_METRICS[d][2]}" for d in self.dofs)
        rms = np.sqrt(self.mean_square)
        data: dict[str, Any] = {
            "mean_square": (dims, self.mean_square, {"units": units + " (squared)"}),
            "standard_error": (dims, self.standard_error, {
                "units": units + " (squared)", "long_name": "sigma/sqrt(R) of the mean square"}),
            "rms": (dims, rms, {"units": units}),
            "rms_standard_error": (dims, np.stack([self.rms_standard_error(d)
                                                   for d in self.dofs]), {"units": units}),
            "significant_amplitude": (dims, 2.0 * rms, {"units": units}),
            "speed": (dims[1:], self.speed, {"units": "m/s", "long_name": "mean surge speed"}),
            "heading": (dims[1:], self.heading, {
                "units": "rad", "long_name": "mean wave heading relative to the ship (0 "
                "following, pi head, pi/2 waves travelling to starboard)"}),
            "n_runs": (dims[1:], self.n_runs),
        }
        if self.frequency_domain is not None:
            data["frequency_domain_m0"] = (dims, self.frequency_domain,
                                           {"units": units + " (squared)"})
        attrs = {"format": DATASET_FORMAT, "heading_key": self.heading_key,
                 "speed_key": self.speed_key or "",
                 **{k: str(v) for k, v in self.description.items()}}
        return xr.Dataset(data, coords={"dof": list(self.dofs)}, attrs=attrs)


# ---------------------------------------------------------------------------------------------
# From a store
# ---------------------------------------------------------------------------------------------


def _flat(source: Any) -> tuple[Any, str]:
    if isinstance(source, (str, Path)):
        from .store import open_sweep

        return open_sweep(source, flat=True), str(source)
    return source, str(source.attrs.get("scenario_source", "the sweep"))


def _dims(ds: Any, where: str) -> list[tuple[str, int]]:
    dims = json.loads(ds.attrs.get("sweep_dims", "[]") or "[]")
    if "complete" in ds:
        raise ParameterError(f"{where}: the sweep is not complete (`seahelm sweep` on the same "
                             "scenario and store finishes it)", field="store")
    return [(str(d), int(n)) for d, n in dims]


def _key(ds: Any, dim: str) -> str:
    return str(ds[dim].attrs.get("key", dim)) if dim in ds.variables else dim


def sweep_seakeeping(source: Any, *, frequency_domain: bool = True) -> SweepSeakeeping:
    """The RMS motions of a time-domain sweep per (speed, heading) cell (module docstring).

    Parameters
    ----------
    source : str, Path or xarray.Dataset
        A sweep store, or its flat view (:func:`~seahelm.sweep.open_sweep` with
        ``flat=True``; a report's per-run variables with the store's attributes).
    frequency_domain : bool, optional
        Also compute the frequency-domain m0 of the cells (:func:`frequency_domain_moments`;
        default True).

    Returns
    -------
    SweepSeakeeping

    Raises
    ------
    ParameterError
        Naming the scenario key: no first-order motions in the sweep
        (``environment.waves.first_order_motions``), no heading in its grid or one heading
        only, more than a heading and a speed key (``batch.grid``), fewer than 2 runs per cell
        (``batch.monte_carlo.runs``); an incomplete store (``store``).
    """
    ds, where = _flat(source)
    if DOF_METRICS["roll"][0] not in ds and DOF_METRICS["heave"][0] not in ds:
        raise ParameterError(
            f"{where}: the sweep has no first-order motions (no per-run `rms_heave_m`): a polar "
            "seakeeping diagram needs [environment.waves] first_order_motions = true (with "
            "irregular = true)", field="environment.waves.first_order_motions")
    dims = _dims(ds, where)
    names = [d for d, _ in dims]
    if "sample" not in names or dict(dims)["sample"] < 2:
        raise ParameterError(
            f"{where}: a cell's sampling uncertainty needs 2 or more seeded runs per cell: "
            "[batch.monte_carlo] runs = R (R >= 2; the seed draws each run's sea)",
            field="batch.monte_carlo.runs")
    grid = [d for d in names if d != "sample"]
    heading_dims = [d for d in grid if _key(ds, d) in HEADING_KEYS]
    if len(heading_dims) != 1:
        raise ParameterError(
            f"{where}: the grid must vary the wave heading by one key, "
            f"{' or '.join(HEADING_KEYS[:2])}; it has "
            + (", ".join(_key(ds, d) for d in heading_dims) or "none"), field="batch.grid")
    hdim = heading_dims[0]
    others = [d for d in grid if d != hdim]
    if len(others) > 1:
        raise ParameterError(f"{where}: a polar diagram has a heading and a speed key; the grid "
                             f"has {len(grid)}: {', '.join(_key(ds, d) for d in grid)}",
                             field="batch.grid")
    if dict(dims)[hdim] < 2:
        raise ParameterError(f"{where}: a polar diagram needs 2 or more wave headings; "
                             f"`{_key(ds, hdim)}` has one", field=f"batch.grid.{_key(ds, hdim)}")
    sdim = others[0] if others else None
    shape = [n for _, n in dims]
    order = [names.index(d) for d in ([sdim] if sdim else []) + [hdim, "sample"]]

    def cells(name: str) -> np.ndarray:
        a = np.asarray(ds[name].values, dtype=float).reshape(shape).transpose(order)
        return a if sdim else a[None]

    speed_runs = cells("mean_surge_speed_mps")
    eps_runs = np.radians(cells("mean_wave_heading_deg"))
    dofs = tuple(d for d, (m, *_) in DOF_METRICS.items() if m in ds)
    ms = np.stack([(cells(DOF_METRICS[d][0]) * DOF_METRICS[d][1]) ** 2 for d in dofs])
    ok = np.all(np.isfinite(ms), axis=0) & np.isfinite(speed_runs) & np.isfinite(eps_runs)
    n = ok.sum(axis=-1)
    if np.any(n < 2):
        raise ParameterError(f"{where}: a cell has fewer than 2 runs that did not diverge; its "
                             "uncertainty is unknown", field="batch.monte_carlo.runs")
    ms = np.where(ok, ms, np.nan)
    mean = np.nanmean(ms, axis=-1)
    se = np.nanstd(ms, axis=-1, ddof=1) / np.sqrt(n)
    speed = np.nanmean(np.where(ok, speed_runs, np.nan), axis=-1)
    from scipy.stats import circmean

    heading = circmean(np.where(ok, eps_runs, np.nan), axis=-1, nan_policy="omit")
    heading = np.where(np.abs(heading - 2.0 * math.pi) < 1e-9, 0.0, heading)
    rows = np.argsort(np.mean(speed, axis=1), kind="stable")
    col_mean = circmean(heading, axis=0)
    col_mean = np.where(np.abs(col_mean - 2.0 * math.pi) < 1e-9, 0.0, col_mean)
    cols = np.argsort(col_mean, kind="stable")
    # start after the largest gap round the circle: the headings a contour may join
    gaps = np.diff(np.append(col_mean[cols], col_mean[cols[0]] + 2.0 * math.pi))
    cols = np.roll(cols, -(int(np.argmax(gaps)) + 1) % cols.size)

    def coord(dim: str | None) -> np.ndarray:
        if dim is None:
            return np.full(1, np.nan)
        values = np.asarray(ds[dim].values).reshape(shape)
        return values[tuple(slice(None) if d == dim else 0 for d in names)]

    out = SweepSeakeeping(
        dofs=dofs, speed=speed[rows][:, cols], heading=heading[rows][:, cols],
        n_runs=n[rows][:, cols].astype(int), mean_square=mean[:, rows][:, :, cols],
        standard_error=se[:, rows][:, :, cols], speed_key=None if sdim is None
        else _key(ds, sdim), heading_key=_key(ds, hdim),
        speed_values=coord(sdim)[rows], heading_values=coord(hdim)[cols],
        description={"source": where, "title": str(ds.attrs.get("title", "")),
                     "runs": int(np.prod(shape))})
    if not frequency_domain:
        return out
    # parsed as the scenario file where it is found (a relative rao_file is beside it)
    scenario = Path(str(ds.attrs.get("scenario_source", "")))
    parse_as = str(scenario) if scenario.suffix == ".toml" and scenario.is_file() else where
    return dataclasses.replace(out, frequency_domain=frequency_domain_moments(
        out, str(ds.attrs.get("scenario_text", "")), parse_as))


def frequency_domain_moments(polar: SweepSeakeeping, text: str, source: str = "<string>"
                             ) -> np.ndarray:
    """The frequency-domain m0 of each cell of a time-domain sweep (module docstring).

    Parameters
    ----------
    polar : SweepSeakeeping
        The cells (their speeds and headings).
    text : str
        The sweep's scenario text (a store keeps it in ``scenario_text``).
    source : str, optional
        Its name in messages.

    Returns
    -------
    numpy.ndarray, shape (n_dof, n_speed, n_heading)
        m0 [u²]; NaN for ``roll_total`` (the model's roll is not a first-order response).

    Raises
    ------
    ParameterError
        If the scenario has no first-order motions.
    """
    from ..analysis.seakeeping.frequency_domain import response_moments
    from ..environment.directional_spreading import spreading_with_parameter
    from ..environment.rao import closed_form_rao
    from ..environment.rao_io import read_rao
    from ..environment.spectra import spectrum_from_wave_height
    from .chunks import prepared

    if not text:
        raise ParameterError(f"{source}: the sweep keeps no scenario text", field="store")
    with warnings.catch_warnings():  # (the sweep said the scenario's range warnings)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        job = prepared(text, source)
    post_pass = getattr(job, "post_pass", None)
    in_loop = getattr(job, "first_order", None)
    settings = (list(post_pass.specs) if post_pass is not None else  # (after the run)
                list(in_loop.settings) if in_loop is not None else None)  # (in the loop)
    if not settings:
        raise ParameterError(f"{source}: the scenario has no first-order motions",
                             field="environment.waves.first_order_motions")
    seas = {s.sea() for s in settings}
    if len(seas) != 1:
        raise ParameterError(f"{source}: the runs' seas differ in more than their direction; "
                             "the frequency-domain cells need one sea", field="batch.grid")
    spec = seas.pop()
    sea = spectrum_from_wave_height(spec.spectrum, spec.h3)
    spreading = (None if spec.spreading is None else
                 spreading_with_parameter(spec.spreading, spec.spreading_parameter))
    L, B, T, cb = spec.hull
    hull = SimpleNamespace(length=L, beam=B, draft=T, block_coefficient=cb)
    out = np.full((len(polar.dofs), *polar.speed.shape), np.nan)
    chosen = [d for d in polar.dofs if d in ("heave", "pitch", "roll")]
    table = read_rao(spec.rao_file) if spec.rao_file else None  # (at every speed)
    for i, j in np.ndindex(*polar.speed.shape):
        rao = table or closed_form_rao(hull, float(polar.speed[i, j]),
                                       metacentric_height=spec.gm)
        dofs = [d for d in chosen if d in rao.dofs]
        band = np.linspace(rao.frequency[0], rao.frequency[-1], 2000)
        m = response_moments(rao, sea, [float(polar.heading[i, j])], dofs=dofs,
                             spreading=spreading, frequency=band)
        for d in dofs:
            out[polar.dofs.index(d), i, j] = m.moment(d, 0)[0, 0]
    return out
