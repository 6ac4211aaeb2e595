"""Short text and HTML summaries of seahelm's objects, for the REPL and Jupyter.

A result, a ship or a problem holds arrays, compiled functions and long provenance strings;
their dataclass reprs printed all of it (a :class:`~seahelm.analysis.maneuvers.ManeuverResult`
gave 215 lines, a :class:`~seahelm.ships.Ship` its ``CPUDispatcher`` objects). These helpers
render what an object holds as a title and a few ``name: value`` rows instead: ``__repr__``
as aligned text, ``_repr_html_`` as a small table (as xarray's objects do in a notebook).
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence

__all__ = ["describe", "linear_model_summary", "names", "shorten", "sim_result_summary",
           "summary_html", "summary_text"]

#: Longest value shown on one row (characters); longer ones end in "…".
MAX_VALUE = 90


def shorten(text: object, limit: int = MAX_VALUE) -> str:
    """One line of at most ``limit`` characters.

    Parameters
    ----------
    text : object
        Anything; its ``str`` is taken, line breaks become spaces.
    limit : int
        Most characters kept (the last one an ellipsis when cut).

    Returns
    -------
    str
    """
    s = " ".join(str(text).split())
    return s if len(s) <= limit else s[: limit - 1] + "…"


def names(items: Sequence[str], most: int = 6) -> str:
    """``"a, b, c (+4 more)"``: the first ``most`` names and how many are left out.

    Parameters
    ----------
    items : sequence of str
        The names.
    most : int
        How many to list.

    Returns
    -------
    str
        ``"—"`` for none.
    """
    items = list(items)
    if not items:
        return "—"
    shown = ", ".join(items[:most])
    return shown + (f" (+{len(items) - most} more)" if len(items) > most else "")


def summary_text(title: str, rows: Iterable[tuple[str, object]]) -> str:
    """The title, then one aligned ``name  value`` line per row.

    Parameters
    ----------
    title : str
        First line: what the object is.
    rows : iterable of (str, object)
        Name and value of each row (values shortened to one line).

    Returns
    -------
    str
    """
    rows = [(k, shorten(v)) for k, v in rows]
    width = max((len(k) for k, _ in rows), default=0)
    return "\n".join([title] + [f"  {k:<{width}}  {v}" for k, v in rows])


def summary_html(title: str, rows: Iterable[tuple[str, object]]) -> str:
    """The same summary as a small HTML table (escaped), for Jupyter's ``_repr_html_``.

    Parameters
    ----------
    title : str
        The table's caption.
    rows : iterable of (str, object)
        Name and value of each row.

    Returns
    -------
    str
    """
    body = "".join(
        f"<tr><th style='text-align:left;padding-right:1em'>{html.escape(k)}</th>"
        f"<td style='text-align:left'>{html.escape(shorten(v, 200))}</td></tr>"
        for k, v in rows)
    return (f"<table class='seahelm-summary'><caption style='text-align:left;"
            f"font-weight:bold'>{html.escape(title)}</caption>{body}</table>")


def describe(value: object) -> str:
    """What an input is, in a few words: ``"—"``, ``"0.5"``, ``"array (4, 1, 1)"``,
    ``"rudder_command, propeller_rps"`` (a mapping's keys), ``"a function"``.

    Parameters
    ----------
    value : object
        A reference, disturbance, parameter set or any other input.

    Returns
    -------
    str
    """
    from collections.abc import Mapping

    if value is None:
        return "—"
    if isinstance(value, Mapping):
        return names([str(k) for k in value]) if value else "—"
    shape = getattr(value, "shape", None)
    if shape is not None and len(shape) > 0:
        return f"array {tuple(shape)}"
    if isinstance(value, (int, float)) or shape == ():
        return f"{float(value):g}"
    name = getattr(value, "name", None)
    if isinstance(name, str):
        return name
    if callable(value):
        return "a function"
    if isinstance(value, (list, tuple)):
        return f"{len(value)} item(s)"
    return shorten(type(value).__name__)


def sim_result_summary(result: object) -> tuple[str, list[tuple[str, object]]]:
    """Title and rows of a :class:`~seahelm.results.SimResult`'s summary.

    Parameters
    ----------
    result : SimResult
        The result (read by attribute: this module imports nothing of seahelm's).

    Returns
    -------
    tuple of (str, list of (str, object))
    """
    import numpy as np

    md = result.metadata
    n_ok = int(np.count_nonzero(result.status == 0))
    span = (f"t = {result.time[0]:g} … {result.time[-1]:g} s" if len(result.time)
            else "no samples")
    batch = ", ".join(f"{d}: {n}" for d, n in zip(result.dims, result.shape))
    title = (f"SimResult: {result.n_runs} run(s) ({batch}), {len(result.time)} samples, {span}")
    parts = [f"{k} {md[k]}" for k in ("model", "actuator", "controller", "integrator")
             if md.get(k)]
    if md.get("dt") is not None:
        parts.append(f"dt {md['dt']:g} s")
    rows: list[tuple[str, object]] = [
        ("status", f"{n_ok} ok, {result.n_runs - n_ok} diverged"),
        ("components", ", ".join(parts) or "—"),
        ("states", names(result.state_labels)),
        ("outputs", names(result.output_labels)),
        ("commands", names(result.command_labels)),
        ("references", names(result.reference_labels)),
        ("disturbances", names(result.disturbance_labels)),
    ]
    if result.extra:
        rows.append(("computed", names(list(result.extra))))
    rows.append(("parameters", ", ".join(f"{k}: {cls.__name__}"
                                         for k, (cls, _) in result.params.items()) or "—"))
    if md.get("wall_time_s") is not None:
        rows.append(("wall time", f"{md['wall_time_s']:.3g} s"
                     + (f" (+ compile {md['compile_time_s']:.3g} s)"
                        if md.get("compile_time_s") else "")))
    rows.append(("metadata", names(sorted(md), 5)))
    rows.append(("use", "to_xarray(), to_netcdf(path), plot(), result['heading']"))
    return title, rows


def linear_model_summary(model: object) -> tuple[str, list[tuple[str, object]]]:
    """Title and rows of a :class:`~seahelm.analysis.equilibria.linearisation.LinearModel`'s
    summary.

    Its matrices are not printed (``to_numpy()`` gives them): at a kink the model holds two
    one-sided models besides the mean, and its dataclass repr ran to 22 kB.

    Parameters
    ----------
    model : LinearModel
        The model (read by attribute).

    Returns
    -------
    tuple of (str, list of (str, object))
    """
    import numpy as np

    n, m, p = (len(getattr(model, f"{k}_labels")) for k in ("state", "input", "output"))
    where = f" ({model.side})" if model.side and model.side not in model.name else ""
    title = f"LinearModel{where}: {model.name or 'unnamed'}, {n} states, {m} inputs, {p} outputs"
    poles = np.linalg.eigvals(model.A) if n else np.zeros(0)
    at = [f"U {model.speed:.4g} m/s"] if np.isfinite(model.speed) else []
    rows: list[tuple[str, object]] = [
        ("states", names([f"{s} [{u}]" for s, u in zip(model.state_labels, model.state_units)],
                         8)),
        ("inputs", names([f"{s} [{u}]" for s, u in zip(model.input_labels, model.input_units)])),
        ("outputs", names(model.output_labels, 8)),
        ("point", ", ".join(at + [f"{s} {v:.4g}" for s, v in
                                  zip(model.input_labels, np.asarray(model.u0))]) or "—"),
        ("poles", ", ".join(f"{z:.3g}" for z in poles[:8])
         + (f" (+{poles.size - 8} more)" if poles.size > 8 else "") + " [1/s]" if n else "—"),
    ]
    if model.kinks:
        rows.append(("kink", f"{names(model.kinks)}: A…D the mean of {len(model.sides)} "
                             "one-sided models (.sides)"))
        if model.note:
            rows.append(("why", model.note))
    rows.append(("use", "A, B, C, D, poles, sides, select(...), to_numpy(), to_control()"))
    return title, rows
