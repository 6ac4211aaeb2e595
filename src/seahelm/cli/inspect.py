"""``seahelm inspect RESULT.nc`` (alias ``seahelm summary``): what a result file holds.

A simulation result (``result.nc`` of ``seahelm run``/``demo``, a manoeuvre's ``*-runs.nc``):

The run metadata (scenario, components, integrator, timing, seed, versions), the batch (its
dimensions with the key path each varies, Monte-Carlo draws), the status of every run (the
diverged ones with the time and the reason) and the summary table that ``seahelm run`` printed
when the file was written -- computed again from the file (:func:`seahelm.result_io.read_result`),
with the Monte-Carlo statistics. ``--json`` prints all of it as one JSON object, with every run.

A manoeuvre's metrics file (``*-metrics.nc`` of ``seahelm maneuver``/``imo``): its metadata
and the metrics of every run. The IMO check of an ensemble (``imo-probabilities.nc`` of
``seahelm imo --monte-carlo --out`` or an ``imo`` Monte-Carlo scenario): its metadata, the
drawn keys and the probability of passing each criterion, as the command printed it, with the
excluded samples and their reasons. A sweep store (the ``.zarr`` directory of ``seahelm
sweep``): its state (complete, or how many runs are written), its chunks, the scenario's title
and source, and the statistics of every metric (stored with the store when it completed,
computed from the written runs while it is incomplete). A replay (``replay.nc`` of ``seahelm
replay --out``): its settings and the measured and simulated metrics with the RMS position
errors, as the command printed them. Anything else is refused (exit 2).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from ..errors import ParameterError
from ..units import metric_label, to_display
from ._common import JsonFlag, console, handle_errors, input_file, print_json
from ._runs import (
    batch_columns,
    diverged_runs,
    diverged_table,
    monte_carlo_statistics,
    run_units,
    statistics_tables,
    status_counts,
    summary_table,
)

#: Metadata shown first, in this order, with units; other attributes follow.
_METADATA = (("title", ""), ("scenario_source", ""), ("model", ""), ("actuator", ""),
             ("controller", ""), ("integrator", ""), ("dt", "s"), ("controller_dt", "s"),
             ("t_final", "s"), ("record_every", "steps"), ("seed", ""),
             ("seahelm_version", ""), ("created", ""), ("wall_time_s", "s"),
             ("compile_time_s", "s"))
#: Runs of a manoeuvre's metrics file shown as columns (the JSON output has all).
MAX_METRIC_RUNS = 6
#: Attributes not shown in the human output (the JSON output has them).
_LONG = ("scenario_text", "state_labels", "param_types", "imo_criteria")


@handle_errors
def inspect(
    result: Annotated[Path, typer.Argument(help=(
        "Result file written by seahelm (NetCDF), or a sweep store (STORE.zarr)."))],
    json_out: JsonFlag = False,
) -> None:
    """Show a result file: run metadata, batch, per-run status and the summary table."""
    from ..analysis.imo.ensemble import is_ensemble_dataset
    from ..analysis.replay.dataset import is_replay_dataset
    from ..results import open_result_file
    from ..sweep.store import store_attrs

    if result.is_dir() and store_attrs(result) is not None:
        _show_store(result, json_out)
        return
    input_file("RESULT", result)
    ds = open_result_file(result)
    if "status" in ds and "time" in ds.dims and "state_labels" in ds.attrs:
        _show_runs(result, ds, json_out)
    elif is_ensemble_dataset(ds):
        _show_ensemble(result, ds, json_out)
    elif ds.attrs.get("maneuver") and "complete" in ds:
        _show_metrics(result, ds, json_out)
    elif is_replay_dataset(ds):
        _show_replay(result, ds, json_out)
    else:
        raise ParameterError(
            f"{result}: not a seahelm result file: neither a simulation result (result.nc of "
            "`seahelm run --out`, a manoeuvre's *-runs.nc), a manoeuvre's *-metrics.nc, "
            "an imo-probabilities.nc nor a replay.nc")


def _show_runs(result: Path, ds: Any, json_out: bool) -> None:
    from ..analysis.maneuvers import summarize
    from ..result_io import result_from_dataset

    res = result_from_dataset(ds)
    summary = summarize(res)
    units = run_units(res, summary)
    batch_keys = batch_columns(res, summary)
    stats = monte_carlo_statistics(res, summary)
    diverged = diverged_runs(res)
    metadata = {k: _plain(v) for k, v in ds.attrs.items()}
    batch = _batch(res)
    payload: dict[str, Any] = {
        "file": str(result),
        "metadata": metadata,
        "dims": dict(zip(res.dims, res.shape)),
        "time_samples": int(res.time.size),
        "batch": batch,
        **status_counts(res.status),
        "diverged": diverged,
        "runs": summary,
        "units": units,
    }
    if stats:
        payload["statistics"] = stats
    if json_out:
        print_json(payload)
        return

    meta = _metadata_table(result, metadata)
    dims = " × ".join(f"{d}={n}" for d, n in payload["dims"].items())
    meta.add_row("runs", f"{payload['n_runs']} ({dims}), {payload['time_samples']} time samples "
                         f"over {res.time[-1]:.6g} s")
    for axis in batch["axes"]:
        meta.add_row(f"dimension {axis['name']}", escape(
            f"{axis['key']} = {', '.join(f'{v:g}' for v in axis['values'])}"
            + (f" [{axis['units']}]" if axis["units"] else "")))
    for draw in batch["drawn"]:
        what = draw.get("distribution", "")
        meta.add_row("drawn", escape(f"{draw['name']}" + (f" ({what})" if what else "")
                                     + (f" [{draw['units']}]" if draw["units"] else "")))
    if "scenario_text" in metadata:
        meta.add_row("scenario_text", f"{len(str(metadata['scenario_text']).splitlines())} "
                                      "lines (--json shows it)")
    console.print(meta)
    console.print(f"status: {payload['n_runs']} run(s), {payload['n_ok']} ok, "
                  f"{payload['n_diverged']} diverged", highlight=False)
    if diverged:
        console.print(diverged_table(diverged))
    console.print(summary_table(summary, str(metadata.get("title") or result.name), batch_keys,
                                units=units))
    for table in statistics_tables(stats, units=units):
        console.print(table)


def _show_metrics(result: Path, ds: Any, json_out: bool) -> None:
    """A manoeuvre's metrics file: metadata, then one column of metrics per run (each
    labelled with its display unit and shown in it)."""
    from ..analysis.maneuvers import metrics_rows

    metadata = {k: _plain(v) for k, v in ds.attrs.items()}
    rows = metrics_rows(ds)
    if json_out:
        print_json({"file": str(result), "metadata": metadata, "n_runs": len(rows),
                    "runs": rows})
        return
    console.print(_metadata_table(result, metadata))
    shown = rows[:MAX_METRIC_RUNS]
    table = Table(title=escape(f"{metadata['maneuver']} metrics, {len(rows)} run(s)"),
                  title_justify="left")
    table.add_column("metric", no_wrap=True)
    for i in range(len(shown)):
        table.add_column(f"run {i}", justify="right", overflow="fold")
    for key in rows[0] if rows else ():  # (angles in degrees, fractions in %: seahelm.units)
        units = str(ds[key].attrs.get("units", "")) if key in ds.variables else ""
        table.add_row(escape(metric_label(key, units)),
                      *(escape(_cell(to_display(row.get(key, ""), units, key)[0]))
                        for row in shown))
    if len(rows) > MAX_METRIC_RUNS:
        table.caption = f"first {MAX_METRIC_RUNS} of {len(rows)} runs (--json has all)"
    console.print(table)


def _show_ensemble(result: Path, ds: Any, json_out: bool) -> None:
    """The IMO check of an ensemble (``imo-probabilities.nc``): metadata, the drawn keys and
    the probabilities table as ``seahelm imo --monte-carlo`` printed it."""
    from ..analysis.imo.ensemble import ensemble_payload
    from .imo import print_imo_probabilities

    metadata = {k: _plain(v) for k, v in ds.attrs.items()}
    payload = ensemble_payload(ds)
    drawn = [{"name": str(n), **{k: str(v) for k, v in var.attrs.items() if k != "kind"}}
             for n, var in ds.data_vars.items() if var.attrs.get("kind") == "batch_values"]
    if json_out:
        print_json({"file": str(result), "metadata": metadata, "drawn": drawn, **payload})
        return
    meta = _metadata_table(result, metadata)
    for draw in drawn:
        what = draw.get("distribution", "")
        meta.add_row("drawn", escape(f"{draw['name']}" + (f" ({what})" if what else "")
                                     + (f" [{draw['units']}]" if draw.get("units") else "")))
    console.print(meta)
    print_imo_probabilities(payload, str(metadata.get("title") or result.name))


def _show_replay(result: Path, ds: Any, json_out: bool) -> None:
    """A replay (``replay.nc`` of ``seahelm replay --out``): its settings, then the measured
    and simulated metrics and the RMS position errors, as ``seahelm replay`` printed them."""
    from ..analysis.replay.dataset import check_replay_dataset, replay_metrics

    check_replay_dataset(ds, result)
    metadata = {k: _plain(v) for k, v in ds.attrs.items()
                if not k.startswith(("measured_", "simulated_"))}
    metrics = replay_metrics(ds)
    n_time = int(ds.sizes.get("time", 0))
    if json_out:
        print_json({"file": str(result), "metadata": metadata, "time_samples": n_time,
                    "tracks": [str(t) for t in ds["track"].values],
                    "metrics": {k: {"measured": m, "simulated": s, "unit": u}
                                for k, (m, s, u) in metrics.items()}})
        return
    meta = _metadata_table(result, metadata)
    if n_time:
        time = ds["time"].values
        meta.add_row("tracks", escape(f"{', '.join(str(t) for t in ds['track'].values)}: "
                                      f"{n_time} samples over {time[-1] - time[0]:.6g} s"))
    console.print(meta)
    table = Table(title=escape(f"Replay of {metadata.get('record', result.name)} with "
                               f"{metadata.get('ship', '?')} ({metadata.get('kind', '?')})"),
                  title_justify="left")
    for name, justify in (("metric", "left"), ("measured", "right"), ("simulated", "right")):
        table.add_column(name, justify=justify)  # type: ignore[arg-type]
    for key, (m, s, unit) in metrics.items():
        (m_shown, shown_unit), (s_shown, _) = (to_display(v, unit, key) for v in (m, s))
        table.add_row(escape(metric_label(key, shown_unit)),
                      *(_cell(v) if math.isfinite(v) else "-" for v in (m_shown, s_shown)))
    for key, label in (("rms_error_60s_L", "RMS position error, first 60 s [L]"),
                       ("rms_error_L", "RMS position error, whole record [L]")):
        if key in metadata:
            table.add_row(label, "", _cell(float(metadata[key])))
    console.print(table)


def _metadata_table(result: Path, metadata: dict[str, Any]) -> Table:
    meta = Table(title=escape(f"{result}"), title_justify="left", show_header=False)
    meta.add_column("key")
    meta.add_column("value", overflow="fold")
    shown = set()
    for key, unit in _METADATA:
        if key == "seed" and metadata.get(key) == -1:
            meta.add_row(key, "none (nothing random in the runs)")
            shown.add(key)
        elif key in metadata:
            meta.add_row(key, escape(_text(metadata[key], unit)))
            shown.add(key)
    for key, value in metadata.items():
        if key not in shown and key not in _LONG:
            meta.add_row(key, escape(_text(value, "")))
    return meta


def _cell(value: Any) -> str:
    return f"{value:.5g}" if isinstance(value, float) else str(value)


def _batch(res: Any) -> dict[str, list[dict[str, Any]]]:
    """The grid axes (name, key path, values, units) and drawn values (name, units, attrs)."""
    layout = res.layout
    if layout is None:
        return {"axes": [], "drawn": []}
    axes = [{"name": a.name, "key": a.key, "values": a.values.tolist(), "units": a.units}
            for a in layout.axes if a.key]
    drawn = [{"name": v.name, "units": v.units, **{k: str(x) for k, x in v.attrs.items()
                                                   if k != "key"}}
             for v in layout.values]
    return {"axes": axes, "drawn": drawn}


def _plain(value: Any) -> Any:
    return value.item() if hasattr(value, "item") else value


def _text(value: Any, unit: str) -> str:
    if isinstance(value, float):
        text = f"{value:.6g}"
    else:
        text = str(value)
    return f"{text} {unit}" if unit and text else text


def _show_store(store: Path, json_out: bool) -> None:
    """A sweep store: state, chunks, scenario, statistics (those stored on completion)."""
    import json

    import numpy as np

    from ..sweep.run import fill_summary_units, summary_statistics
    from ..sweep.store import open_sweep
    from ._runs import sweep_summary_table

    ds = open_sweep(store, flat=True)
    attrs = dict(ds.attrs)
    n_runs = int(ds.sizes["run"])
    if "complete" in ds:
        written = np.asarray(ds["complete"].values, dtype=bool).reshape(n_runs, -1).all(axis=1)
        state = f"incomplete: {int(written.sum())} of {n_runs} runs written"
    else:
        written = np.ones(n_runs, dtype=bool)
        state = "complete"
    summary = fill_summary_units(
        json.loads(attrs["sweep_summary"]) if "sweep_summary" in attrs
        and state == "complete"  # (a stored summary is stale once a chunk is lost)
        else summary_statistics(ds.isel(run=np.flatnonzero(written))), ds)
    payload = {"store": str(store), "state": state, "n_runs": n_runs,
               "n_chunks": int(attrs.get("sweep_n_chunks", 0) or 0),
               "chunk_size": int(attrs.get("sweep_chunk_size", 0) or 0),
               "title": str(attrs.get("title", "")),
               "scenario_source": str(attrs.get("scenario_source", "")),
               "summary": summary}
    if json_out:
        print_json(json.loads(json.dumps(payload)))
        return
    console.print(escape(f"{store}: sweep store, {state}"), highlight=False)
    for key in ("title", "scenario_source"):
        if payload[key]:
            console.print(escape(f"  {key.replace('_', ' ')}: {payload[key]}"),
                          highlight=False)
    console.print(f"  {n_runs:,} run(s) in {payload['n_chunks']} chunk(s) of up to "
                  f"{payload['chunk_size']:,}", highlight=False)
    if "n_ok" in summary:
        console.print(f"  {summary['n_ok']:,} ok, {summary['n_failed']:,} failed",
                      highlight=False)
    table, more = sweep_summary_table(f"statistics over {summary['n_runs']:,} run(s)",
                                      summary)
    console.print(table)
    if more:
        console.print(f"  ... {more} more metric(s): --json", highlight=False)
