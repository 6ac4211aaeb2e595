"""``seahelm identify mmg`` for an ``mmg-ls`` ship: many records, the measured wind as input.

The branch of :func:`seahelm.cli.identify.mmg` taken when ``--ship`` is a low-speed MMG ship
(model ``mmg-ls``, e.g. ``esso-osaka-3m``): the output-error fit over record segments of
:func:`seahelm.analysis.replay.mmg_multi_record.fit_mmg_ls`, a ship file (``--out``) and Laplace
posterior samples (``--samples N --save-posterior FILE.csv``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ._common import console, print_json

__all__ = ["expand_logs", "identify_mmg_ls", "parse_free"]


def expand_logs(files: list[Path]) -> list[Path]:
    """The LOG arguments with every folder replaced by its ``*.csv`` and ``*.nc`` files (all
    depths, sorted); a folder without any is an error naming it."""
    from ..errors import ParameterError

    out: list[Path] = []
    for f in files:
        if f.is_dir():
            found = sorted(p for p in f.rglob("*") if p.suffix.lower() in (".csv", ".nc")
                           and p.is_file())
            if not found:
                raise ParameterError(f"`LOG` {f}: a folder without any *.csv or *.nc record")
            out += found
        else:
            out.append(f)
    return out


def parse_free(text: str | None) -> tuple[str, ...] | None:
    """``--free`` as coefficient names (checked against ``mmg-ls``'s parameters)."""
    from ..errors import ParameterError
    from ..vessels.mmg_low_speed import MMGLowSpeedParams

    if text is None:
        return None
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    known = {i.name for i in MMGLowSpeedParams.info()}
    bad = [n for n in names if n not in known or n.endswith("_model")]
    if bad or not names:
        raise ParameterError(f"`--free`: not coefficients of mmg-ls: "
                             f"{', '.join(bad) or repr(text)} (e.g. N_r,Y_v,a_H)")
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:  # (a coefficient twice: a singular fit, "standard error nan")
        raise ParameterError(f"`--free`: {', '.join(twice)} given more than once, got "
                             f"{text!r}")
    return names


def identify_mmg_ls(files: list[Path], base: Any, *, wind: str, free: tuple[str, ...] | None,
                    segment: float, out: Path | None, name: str | None, samples: int,
                    save_posterior: Path | None, seed: int | None, angles: str,
                    json_out: bool) -> None:
    """Run the fit and print or write its results (module docstring)."""
    from ..analysis.replay.mmg_multi_record import FREE_DEFAULT, fit_mmg_ls, laplace_samples
    from ..identification.records import read_records
    from ..errors import ParameterError
    from ._common import write_ship_file

    if not (segment > 0):
        raise ParameterError(f"`--segment` must be > 0 [s], got {segment!r}")
    records = read_records(files, angles=angles)  # type: ignore[arg-type]
    try:
        fit = fit_mmg_ls(records, base, names=free or FREE_DEFAULT, wind=wind,
                         segment=segment)
    except ParameterError as exc:
        raise ParameterError(f"`LOG`: {exc}") from None
    payload = fit.as_dict()
    if samples:
        draws = laplace_samples(fit, samples, seed=seed, inflate=True)
        payload["posterior_file"] = str(_write_posterior(save_posterior, fit, draws, base,
                                                         seed))
    if out is not None:
        payload["ship_file"] = str(write_ship_file(fit.ship(base, name=name), out))
    if json_out:
        print_json(payload)
        return
    _print(fit, base, payload)


def _write_posterior(path: Path | None, fit: Any, draws: Any, base: Any,
                     seed: int | None) -> Path:
    from ..identification.samples_file import write_samples

    assert path is not None  # checked by the caller (--samples needs --save-posterior)
    units = {i.name: i.unit for i in type(base.params).info()}
    cols = {f"vessel.params.{n}": draws[:, j] for j, n in enumerate(fit.names)}
    return write_samples(path, cols, units={k: units[k.rpartition(".")[2]] for k in cols},
                         comments=(
        f"seahelm Laplace posterior samples of the mmg-ls coefficients of '{base.name}' "
        f"({len(draws)} samples, " + (f"seed {seed}" if seed is not None else "unseeded")
        + f"; the stated covariance: Laplace x {fit.inflation:.3g} for residuals correlated in "
        "time, plus the initial states' errors)",
        f"identified by output error over {fit.segments} segments from "
        f"{', '.join(fit.records)}",
        "one row per sample; the other coefficients at the identified ship's values; use: "
        "seahelm imo SHIP.toml --draws FILE.csv"), force=True)


def _print(fit: Any, base: Any, payload: dict[str, Any]) -> None:
    from rich.markup import escape
    from rich.table import Table

    console.print(escape(
        f"mmg-ls coefficients of '{base.name}' by output error: {len(fit.records)} record(s), "
        f"{fit.segments} segments of {fit.segment:g} s, wind {fit.wind}; RMS of the scaled "
        f"residuals {fit.rms_start:.4g} -> {fit.rms_fit:.4g} ({fit.evaluations} evaluations, "
        f"{fit.seconds:.0f} s)"), highlight=False, soft_wrap=True)
    table = Table("coefficient", "value", "std. error", "stated", f"{base.name}")
    for j, n in enumerate(fit.names):
        table.add_row(n, f"{fit.values[j]:.5g}", f"{float(fit.standard_errors[j]):.3g}",
                      f"{float(fit.stated_errors[j]):.3g}", f"{fit.start[n]:.5g}")
    console.print(table)
    for n, why in fit.fixed.items():
        console.print(escape(f"  {n} not identified (kept at the base ship's value): {why}"),
                      highlight=False, soft_wrap=True)
    console.print(f"condition number of JᵀJ {fit.condition_number:.3g}; std. error: Laplace; "
                  f"stated: its variance x {fit.inflation:.3g} (residuals correlated in time) "
                  "plus the initial states' errors", highlight=False, soft_wrap=True)
    for key, what in (("posterior_file", "posterior samples"), ("ship_file", "ship")):
        if key in payload:
            console.print(escape(f"wrote {what} {payload[key]}"), highlight=False,
                          soft_wrap=True)
