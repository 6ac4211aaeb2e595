"""What a report is made of: the result files read into :class:`ReportData`.

A report covers one result file and the files seahelm wrote beside it for the same question:

* a simulation result (``result.nc`` of ``seahelm run``/``demo``): its runs;
* a manoeuvre's ``<name>-runs.nc`` or ``<name>-metrics.nc`` (``seahelm maneuver``): the runs
  and the metrics of that manoeuvre (whichever of the two files exists);
* either file of ``seahelm imo --out``: the turning and zig-zag runs and metrics, and the IMO
  criteria of ``imo-report.json`` (the pass/fail table the command printed);
* ``imo-probabilities.nc`` of ``seahelm imo --monte-carlo --out`` (or of an ``imo``
  Monte-Carlo scenario): the probability of passing each criterion of the IMO check;
* ``replay.nc`` of ``seahelm replay --out``: the measured and the simulated track and their
  metrics;
* ``encounters.nc`` of ``seahelm encounter --out``: an encounter study's outcomes, tracks,
  CPA over time and outcome rose.

* a sweep store (``seahelm sweep``, a Zarr directory): its state (chunks written), the
  summary statistics stored with it, the distribution of every metric over the runs and,
  when it holds time series, the first :data:`MAX_SWEEP_RUNS` runs for the plots; the store
  of an ``imo`` Monte-Carlo scenario also the probability of passing each criterion.

Everything is held as xarray Datasets (the runs in their flat ``run`` view), so that a section
of the report is a function of Datasets (:mod:`seahelm.report.sections`).
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["report_inputs", "RunSet", "ReportData", "load_report_data", "report_data_from_dataset",
           "combined_report_data"]

#: The manoeuvres whose files ``seahelm imo --out`` writes (with ``imo-report.json``).
IMO_MANEUVERS = ("turning-circle", "zigzag", "stopping")
#: The criteria file ``seahelm imo --out`` writes.
IMO_REPORT = "imo-report.json"
#: Runs of a sweep store with time series read for the plots (the statistics use every run).
MAX_SWEEP_RUNS = 200


@dataclasses.dataclass(frozen=True)
class RunSet:
    """One batch of runs and, for a manoeuvre, its metrics.

    Attributes
    ----------
    name : str
        ``"result"`` for a simulation, else the manoeuvre (``"turning-circle"``, ``"zigzag"``,
        ...).
    runs : xarray.Dataset or None
        The runs in their flat view (dims ``run`` and ``time``); None for a manoeuvre computed
        without time series (the reverse spiral).
    metrics : xarray.Dataset or None
        A manoeuvre's metrics over its batch dims (None for a simulation).
    shaped : xarray.Dataset or None
        The runs as written (the batch's own dims), for the summary metrics.
    n_source : int or None
        The runs of the source when ``runs`` holds only some of them (a sweep store's first
        :data:`MAX_SWEEP_RUNS`); None when it holds all.
    """

    name: str
    runs: "xr.Dataset | None"
    metrics: "xr.Dataset | None" = None
    shaped: "xr.Dataset | None" = None
    n_source: int | None = None

    @property
    def n_runs(self) -> int:
        """Number of runs held (0 without time series)."""
        return 0 if self.runs is None else int(self.runs.sizes["run"])

    @functools.cached_property
    def summary(self) -> list[dict[str, Any]]:
        """The per-run summary metrics of the runs, as ``seahelm run`` prints them
        (:func:`seahelm.analysis.maneuvers.summarize`; empty without time series)."""
        if self.shaped is None:
            return []
        from ..analysis.maneuvers import summarize
        from ..result_io import result_from_dataset

        return summarize(result_from_dataset(self.shaped))


@dataclasses.dataclass(frozen=True)
class ReportData:
    """Everything a report shows.

    Attributes
    ----------
    title : str
        The page title (the scenario's title, the manoeuvre and ship, or the file name).
    sets : tuple of RunSet
        The batches, in the order shown.
    imo : xarray.Dataset or None
        The IMO MSC.137(76) criteria over a ``row`` dim (``ability``, ``criterion``,
        ``side``, ``value``, ``limit``, ``margin``, ``unit``, ``status``, ``note``), with the
        ship, L, V, L/V, verdict and notes in ``attrs``; None when the input is not an IMO check.
    sources : tuple of str
        The files read.
    sweep : xarray.Dataset or None
        A sweep store's per-run variables (no time series) in its flat ``run`` view, with the
        store's attributes (``sweep_summary`` when complete); None for other inputs.
    imo_ensemble : xarray.Dataset or None
        The IMO check of an ensemble (``imo-probabilities.nc``,
        :mod:`seahelm.analysis.imo.ensemble`); None for other inputs.
    seakeeping : xarray.Dataset or None
        Seakeeping statistics over (dof, speed, heading) (``seakeeping.nc``,
        :mod:`seahelm.analysis.seakeeping`); None for other inputs.
    replay : xarray.Dataset or None
        A replay's measured and simulated tracks and metrics (``replay.nc`` of ``seahelm
        replay --out``, :mod:`seahelm.analysis.replay.dataset`); None for other inputs.
    encounters : xarray.Dataset or None
        An encounter study (``encounters.nc`` of ``seahelm encounter --out``,
        :meth:`seahelm.encounters.result.EncounterResult.to_xarray`); None for other inputs.
    dp_capability : xarray.Dataset or None
        A DP capability rose (``seahelm dp capability --out``, level 1 or 3,
        :mod:`seahelm.report.dp_capability`); None for other inputs.
    """

    title: str
    sets: tuple[RunSet, ...]
    imo: "xr.Dataset | None" = None
    sources: tuple[str, ...] = ()
    sweep: "xr.Dataset | None" = None
    imo_ensemble: "xr.Dataset | None" = None
    seakeeping: "xr.Dataset | None" = None
    replay: "xr.Dataset | None" = None
    encounters: "xr.Dataset | None" = None
    dp_capability: "xr.Dataset | None" = None

    @property
    def n_runs(self) -> int:
        """Runs the report covers: a sweep store's (not only those read for the plots), an IMO
        ensemble's samples (it said 0 runs for 500 samples), else those of all sets."""
        if self.sweep is not None:
            return int(self.sweep.sizes["run"])
        if self.replay is not None:  # (one replay: a measured and a simulated track)
            return 1
        if self.encounters is not None:
            return int(self.encounters.sizes["encounter"])
        if self.dp_capability is not None:  # (level 3: its simulated runs)
            held = self.dp_capability.get("held")
            return int((held if held is not None else self.dp_capability["wind_speed"]).size)
        if self.imo_ensemble is not None and "sample" in self.imo_ensemble.sizes:
            return int(self.imo_ensemble.sizes["sample"])
        return sum(s.n_runs for s in self.sets)


def is_dp_capability_dataset(ds: Any) -> bool:
    """A dataset written by ``seahelm dp capability --out`` (either level).

    Parameters
    ----------
    ds : xarray.Dataset
    """
    from ..output_files import WRITTEN_BY_ATTR

    return (str(ds.attrs.get(WRITTEN_BY_ATTR, "")).startswith("seahelm dp capability")
            and "wind_speed" in ds and set(ds["wind_speed"].dims) == {"case", "direction"})


def _is_runs(ds: "xr.Dataset") -> bool:
    return "status" in ds and "time" in ds.dims and "state_labels" in ds.attrs


def _is_metrics(ds: "xr.Dataset") -> bool:
    return bool(ds.attrs.get("maneuver")) and "complete" in ds


def _check_runs(ds: "xr.Dataset", path: Path) -> None:
    if any(size == 0 for dim, size in ds.sizes.items()):
        empty = ", ".join(f"{d}={n}" for d, n in ds.sizes.items() if n == 0)
        raise ParameterError(f"{path}: the result holds no runs or no time samples ({empty})")


def _flat(ds: "xr.Dataset") -> "xr.Dataset":
    from ..result_layout import flatten_runs

    return flatten_runs(ds)


def report_data_from_dataset(ds: "xr.Dataset", *, title: str | None = None,
                             sources: tuple[str, ...] = ()) -> ReportData:
    """The report data of a simulation result Dataset (shaped or flat view), without reading
    files (``seahelm run``/``demo`` report the result they hold in memory).

    Parameters
    ----------
    ds : xarray.Dataset
        A Dataset of :meth:`SimResult.to_xarray` or :func:`~seahelm.results.load_result`.
    title : str, optional
        Page title (default: the scenario's title).
    sources : tuple of str, optional
        The files the Dataset was written to, named on the page.

    Returns
    -------
    ReportData

    Raises
    ------
    ParameterError
        If ``ds`` is not a seahelm simulation result or holds no runs.
    """
    if not _is_runs(ds):
        raise ParameterError("not a seahelm simulation result (it needs `status` over the runs, "
                             "a `time` dimension and the `state_labels` attribute)")
    _check_runs(ds, Path("<dataset>"))
    name = str(ds.attrs.get("maneuver") or "result")
    return ReportData(title=title or str(ds.attrs.get("title") or name),
                      sets=(RunSet(name, _flat(ds), None, ds),), sources=tuple(sources))


def load_report_data(path: str | Path) -> ReportData:
    """Read a result file and its companions (see the module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
        ``result.nc``, ``<manoeuvre>-runs.nc``, ``<manoeuvre>-metrics.nc`` or a sweep store.

    Returns
    -------
    ReportData

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ParameterError
        If ``path`` is not a seahelm result file or sweep store, or holds no runs.
    """
    from ..results import open_result_file

    path = Path(path)
    if path.is_dir() or path.suffix == ".zarr":
        return _sweep_data(path)
    ds = open_result_file(path)
    from ..analysis.imo.ensemble import is_ensemble_dataset

    if is_ensemble_dataset(ds):
        return ReportData(title=str(ds.attrs.get("title") or path.name), sets=(),
                          sources=(str(path),), imo_ensemble=ds)
    from ..analysis.seakeeping.frequency_domain import DATASET_FORMAT

    if ds.attrs.get("format") == DATASET_FORMAT:
        return ReportData(title=str(ds.attrs.get("title") or path.name), sets=(),
                          sources=(str(path),), seakeeping=ds)
    from ..analysis.replay.dataset import check_replay_dataset, is_replay_dataset

    if is_replay_dataset(ds):
        check_replay_dataset(ds, path)
        return ReportData(title=f"Replay of {ds.attrs.get('record', path.name)} with "
                                f"{ds.attrs.get('ship', '?')}", sets=(),
                          sources=(str(path),), replay=ds)
    from ..encounters.result import EncounterResult, is_encounter_dataset

    if is_encounter_dataset(ds):
        if any(ds.sizes[d] == 0 for d in ("encounter", "time")):
            raise ParameterError(f"{path}: the encounter result holds no encounters or no "
                                 "time samples")
        try:
            EncounterResult.from_xarray(ds)
        except ParameterError as exc:
            raise ParameterError(f"{path}{exc}") from None
        return ReportData(title=f"Encounters: {ds.sizes['encounter']} of "
                                f"{', '.join(str(v) for v in ds['vessel'].values)}",
                          sets=(), sources=(str(path),), encounters=ds)
    if is_dp_capability_dataset(ds):
        return ReportData(title=f"DP capability level {int(ds.attrs.get('level', 1))}: "
                                f"{ds.attrs.get('vessel', path.name)}", sets=(),
                          sources=(str(path),), dp_capability=ds)
    if _is_runs(ds):
        _check_runs(ds, path)
        maneuver = ds.attrs.get("maneuver")
        if not maneuver:
            return ReportData(title=str(ds.attrs.get("title") or path.name),
                              sets=(RunSet("result", _flat(ds), None, ds),),
                              sources=(str(path),))
    elif _is_metrics(ds):
        maneuver = ds.attrs["maneuver"]
    else:
        raise ParameterError(
            f"{path}: not a seahelm result file: neither a simulation result (result.nc of "
            "`seahelm run --out`, a manoeuvre's *-runs.nc), a manoeuvre's *-metrics.nc, "
            "an imo-probabilities.nc, a seakeeping.nc, a replay.nc, an encounters.nc nor a "
            "dp capability file")
    directory = path.parent
    imo_file = directory / IMO_REPORT
    names = [str(maneuver)]
    imo = None
    if str(maneuver) in IMO_MANEUVERS and imo_file.is_file():
        imo = _imo_dataset(imo_file)
        if imo is not None:
            names = list(IMO_MANEUVERS)
    sets = []
    sources = []
    for name in names:
        run_set, read = _maneuver_set(directory, name, path, ds)
        if run_set is not None:
            sets.append(run_set)
            sources.extend(read)
    if imo is not None:
        sources.append(str(imo_file))
        title = (f"IMO MSC.137(76) check: {imo.attrs['ship']} "
                 f"({'passes' if imo.attrs['passed'] else 'fails'})")
    else:
        title = _maneuver_title(str(maneuver), sets)
    return ReportData(title=title, sets=tuple(sets), imo=imo, sources=tuple(sources))


def _maneuver_set(directory: Path, name: str, given: Path, given_ds: "xr.Dataset"
                  ) -> tuple[RunSet | None, list[str]]:
    """The runs and metrics files of manoeuvre ``name`` in ``directory`` (either may be
    missing; the one given is used as read)."""
    from ..results import open_result_file

    found: dict[str, "xr.Dataset"] = {}
    read = []
    for kind in ("runs", "metrics"):
        candidate = directory / f"{name}-{kind}.nc"
        if candidate.resolve() == given.resolve():
            found[kind] = given_ds
            read.append(str(given))
        elif candidate.is_file():
            ds = open_result_file(candidate)
            if (_is_runs(ds) if kind == "runs" else _is_metrics(ds)) and \
                    ds.attrs.get("maneuver") == name:
                found[kind] = ds
                read.append(str(candidate))
    if not found:
        return None, read
    runs = found.get("runs")
    if runs is not None:
        _check_runs(runs, directory / f"{name}-runs.nc")
    return RunSet(name, None if runs is None else _flat(runs), found.get("metrics"),
                  runs), read


def _maneuver_title(maneuver: str, sets: list[RunSet]) -> str:
    ship = ""
    for s in sets:
        for ds in (s.metrics, s.shaped):
            if ds is not None and "ship_name" in ds.coords:
                ship = str(ds["ship_name"].values.ravel()[0])
                break
        if ship:
            break
    return f"{maneuver.replace('-', ' ')}" + (f", {ship}" if ship else "")


def _imo_dataset(path: Path) -> "xr.Dataset | None":
    """The criteria of ``imo-report.json`` as a Dataset over ``row`` (None if the file
    is not the report of ``seahelm imo``)."""
    import numpy as np
    import xarray as xr

    try:
        report = json.loads(path.read_text())
        criteria = report["criteria"]
        keys = ("ability", "criterion", "side", "value", "limit", "margin", "unit", "status",
                "note")
        rows = [{k: c[k] for k in keys} for c in criteria]
    except (OSError, ValueError, KeyError, TypeError):
        return None

    def num(v: Any) -> float:
        return math.nan if v is None else float(v)

    data = {k: ("row", np.array([num(r[k]) for r in rows]) if k in
                ("value", "limit", "margin") else np.array([str(r[k]) for r in rows]))
            for k in keys}
    attrs = {"ship": str(report.get("ship", "")), "length_m": num(report.get("length_m")),
             "speed_mps": num(report.get("speed_mps")),
             "L_over_V_s": num(report.get("L_over_V_s")), "passed": bool(report.get("passed")),
             "notes": "\n".join(str(n) for n in report.get("notes", []))}
    return xr.Dataset(data, attrs=attrs)


def _sweep_data(path: Path) -> ReportData:
    """The report data of a sweep store (module docstring)."""
    from ..sweep.store import open_sweep, store_attrs

    if store_attrs(path) is None:
        raise ParameterError(f"{path}: not a sweep store of `seahelm sweep` (no zarr.json with "
                             "sweep attributes) and not a result file")
    flat = open_sweep(path, flat=True)
    if flat.sizes.get("run", 0) == 0:
        raise ParameterError(f"{path}: the sweep store holds no runs")
    per_run = flat[[v for v in flat.data_vars if "time" not in flat[v].dims]].load()
    from ..sweep.run import store_metric_units

    for name, unit in store_metric_units(flat).items():  # (an older store: by their names)
        per_run[name].attrs.setdefault("units", unit)
    title = str(flat.attrs.get("title") or flat.attrs.get("sweep_title") or path.name)
    sets: tuple[RunSet, ...] = ()
    if "time" in flat.dims and "status" in flat and "state_labels" in flat.attrs:
        n = min(MAX_SWEEP_RUNS, int(flat.sizes["run"]))
        if "complete" in flat:
            done = np.flatnonzero(np.asarray(flat["complete"].values).reshape(
                flat.sizes["run"], -1).all(axis=1))[:n]
        else:
            done = np.arange(n)
        if done.size:
            runs = flat.isel(run=done).load()
            total = int(flat.sizes["run"])
            sets = (RunSet("result", runs, None, None,
                           n_source=total if total > done.size else None),)
    return ReportData(title=f"Sweep: {title}", sets=sets, sources=(str(path),), sweep=per_run)


def combined_report_data(paths: "list[str | Path]") -> ReportData:
    """The report data of several result files on one page (``seahelm report A.nc B.nc``):
    each file's batches side by side, named by the file (its name, or its folder and name
    where two names are the same).

    Parameters
    ----------
    paths : list of str or pathlib.Path
        Result files (as :func:`load_report_data` reads them); one gives that file's data.

    Returns
    -------
    ReportData

    Raises
    ------
    ParameterError
        If one of them is a sweep store, an ``imo-probabilities.nc`` or a ``seakeeping.nc``
        (reported alone), two
        hold IMO checks, or two are the same result (a manoeuvre's runs and metrics files are
        read together already), or as :func:`load_report_data`.
    FileNotFoundError
        If a path does not exist.
    """
    import dataclasses as dc

    paths = [Path(p) for p in paths]
    datas = [load_report_data(p) for p in paths]
    if len(datas) == 1:
        return datas[0]
    for path, data in zip(paths, datas):
        if data.sweep is not None or data.imo_ensemble is not None \
                or data.seakeeping is not None or data.replay is not None \
                or data.encounters is not None or data.dp_capability is not None:
            raise ParameterError(f"{path}: a sweep store, an imo-probabilities.nc, a "
                                 "seakeeping.nc, a replay.nc or an encounters.nc is reported "
                                 "alone, not with other results")
    seen: dict[str, Path] = {}
    for path, data in zip(paths, datas):
        for source in data.sources:
            key = str(Path(source).resolve())
            if key in seen:
                raise ParameterError(f"{path} and {seen[key]} are the same result (both read "
                                     f"{source}); give it once")
            seen[key] = path
    imos = [d.imo for d in datas if d.imo is not None]
    if len(imos) > 1:
        raise ParameterError("two IMO checks: a report holds one (give their files apart)")
    stems = [p.stem for p in paths]
    names = [s if stems.count(s) == 1 else f"{p.parent.name}/{s}"
             for s, p in zip(stems, paths)]
    sets = []
    for name, data in zip(names, datas):
        for run_set in data.sets:
            label = name if len(data.sets) == 1 else f"{name}: {run_set.name}"
            sets.append(dc.replace(run_set, name=label))
    return ReportData(title="; ".join(dict.fromkeys(d.title for d in datas)), sets=tuple(sets),
                      imo=imos[0] if imos else None,
                      sources=tuple(s for d in datas for s in d.sources))


def report_inputs(path: str | Path) -> list[Path]:
    """Every file (or store) :func:`load_report_data` may read for ``path``, so that a report
    is never written over one of them.

    For a sweep store, the store; for a file, it and the manoeuvre files (``*-runs.nc``,
    ``*-metrics.nc``) and ``imo-report.json`` beside it (a manoeuvre's file is reported with
    its pair and its IMO set; which one a file is shows only once it is read).

    Parameters
    ----------
    path : str or pathlib.Path
        What ``seahelm report`` was given.

    Returns
    -------
    list of pathlib.Path
    """
    p = Path(path)
    if p.is_dir():
        return [p]
    folder = p.parent
    return [p, *sorted(folder.glob("*-runs.nc")), *sorted(folder.glob("*-metrics.nc")),
            folder / IMO_REPORT]
