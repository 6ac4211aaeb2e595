"""``esso_osaka.py --part identify``: the ``mmg-ls`` identification on the training files.

Fits the coefficients of :data:`seahelm.analysis.replay.mmg_multi_record.FREE_DEFAULT` of
``esso-osaka-3m`` on the training files of Wakita et al. (2022) (the data set's README, column
``Train-TZRB+`` by default: every file but the test ones) with the measured wind as a known
input, writes the identified ship file and its Laplace posterior samples, then predicts the
test files (column ``Test (TZRB)``) with :func:`seahelm.analysis.replay.replay` (the same code
as ``seahelm replay``, measured wind) for the published and the identified ship, and draws the
posterior's 95 % band around the measured tracks of the test files.

Writes into ``--out``: ``identify.inc`` (the coefficient table), ``identify-test.inc`` (the
test-file table), ``identify-band.png`` (the figure), ``timing-identify.inc``,
``esso-osaka-3m-identified.toml`` and ``esso-osaka-3m-posterior.csv`` (derived numbers only:
no record of the data set).
"""

from __future__ import annotations

import dataclasses
import math
import re
import time
from pathlib import Path
from typing import Any

import numpy as np

SHIP = "esso-osaka-3m"
#: Columns of the README's Wakita (2022) table.
COLUMNS = ("Train-TZB", "Train-TZRB", "Train-TZRB+", "Test (TZRB)")
BAND_DRAWS = 60
WINDOW = 60.0


def split(data: Path, train: str = "Train-TZRB+") -> tuple[list[Path], list[Path]]:
    """Training and test files of the Wakita (2022) table of the data set's README.

    Raises
    ------
    SystemExit
        With one line when the README has no such table or column.
    """
    readme = data / "README.md"
    if train not in COLUMNS[:3]:
        raise SystemExit(f"esso_osaka.py: error: --train {train!r}: one of "
                         f"{', '.join(COLUMNS[:3])}")
    text = readme.read_text(encoding="utf-8") if readme.is_file() else ""
    wakita = text.split("- [Miyauchi (2022)]")[0]
    rows = re.findall(r"^\|\s*`(data/[^`]+\.csv)`\s*\|(.*)\|\s*$", wakita, flags=re.M)
    if not rows:
        raise SystemExit(f"esso_osaka.py: error: --data {data}: README.md has no Wakita (2022) "
                         "train/test table")
    col = COLUMNS.index(train)
    picked: tuple[list[Path], list[Path]] = ([], [])
    for path, cells in rows:
        marks = [c.strip() for c in cells.split("|")]
        if len(marks) < 4:
            continue
        if marks[col].startswith("⭕"):
            picked[0].append(data / path)
        if marks[3].startswith("⭕"):
            picked[1].append(data / path)
    return picked


def _kind(path: Path) -> str:
    return {"turning": "turning", "zigzag": "zigzag"}.get(path.parent.name, "none")


def run(data: Path, out: Path, *, train: str = "Train-TZRB+", seed: int = 1,
        zigzag_angles: dict[str, int] | None = None) -> dict[str, Any]:
    """The identification, the test-file predictions and the band (module docstring)."""
    from seahelm.analysis.replay.mmg_multi_record import fit_mmg_ls, laplace_samples
    from seahelm.identification.records import read_records
    from seahelm.ships import get_ship
    from seahelm.ships.writing import ship_to_toml

    train_files, test_files = split(data, train)
    base = get_ship(SHIP)
    # the records named from the data set's root (not this machine's path to it)
    records = [dataclasses.replace(r, name=r.name.replace(str(data).rstrip("/") + "/",
                                                          "FRT-DS-ESSO/"))
               for f in train_files for r in read_records(f)]
    t0, c0 = time.perf_counter(), time.process_time()
    fit = fit_mmg_ls(records, base)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    ship = fit.ship(base, name=f"{SHIP}-identified")
    (out / f"{SHIP}-identified.toml").write_text(ship_to_toml(ship))
    draws = laplace_samples(fit, BAND_DRAWS, seed=seed, inflate=True)
    _write_samples(out / f"{SHIP}-posterior.csv", fit, draws, base, seed)
    rows = _predict(test_files, base, ship, zigzag_angles or {})
    band = _band(test_files, base, fit, draws)
    return {"fit": fit, "seconds": seconds, "cpu_seconds": cpu, "train": train_files,
            "test": test_files, "rows": rows, "band": band, "ship": ship}


def _write_samples(path: Path, fit: Any, draws: np.ndarray, base: Any, seed: int) -> None:
    from seahelm.identification.samples_file import write_samples

    units = {i.name: i.unit for i in type(base.params).info()}
    cols = {f"vessel.params.{n}": draws[:, j] for j, n in enumerate(fit.names)}
    write_samples(path, cols, units={k: units[k.rpartition(".")[2]] for k in cols}, comments=(
        f"seahelm Laplace posterior samples ({len(draws)}, seed {seed}; the stated covariance: "
        f"Laplace x {fit.inflation:.3g} for residuals correlated in time, plus the initial "
        f"states' errors) of the mmg-ls coefficients "
        f"of '{base.name}' identified from {len(fit.records)} records",
        "one row per sample; the other coefficients at the identified ship's values"),
        force=True)


def _predict(files: list[Path], base: Any, ship: Any, angles: dict[str, int]) -> list[dict]:
    from seahelm.identification.records import read_records
    from seahelm.analysis.replay import classify, replay

    rows = []
    for path in files:
        record = read_records(path)[0]
        kind = _kind(path)
        angle = None
        if kind == "zigzag" and classify(record)[1] is None:
            angle = math.radians(angles.get(path.stem, 20))
        row: dict[str, Any] = {"file": path.stem, "kind": path.parent.name}
        for label, s in (("published", base), ("identified", ship)):
            r = replay(record, s, kind=kind, wind="measured", check_angle=angle)
            row[label] = {"rms60": r.rms_error_window, "rms": r.rms_error,
                          "metrics": dict(r.metrics)}
        rows.append(row)
    return rows


def _band(files: list[Path], base: Any, fit: Any, draws: np.ndarray) -> dict[str, Any]:
    """The test files simulated whole from their first sample by the posterior draws, the
    identified and the published ship (measured wind): their tracks and the band's coverage
    of the measured track over the first minute."""
    from seahelm.analysis.replay.mmg_multi_record import build_segments, simulate_segments
    from seahelm.identification.records import read_records

    records = [read_records(f)[0] for f in files]
    segs = build_segments(records, base, segment=math.inf, sample=1.0, wind="measured")
    sets = [base.params, fit.params] + [fit.params.replace(**dict(zip(fit.names, map(float, d))))
                                        for d in draws]
    sim = simulate_segments(base, segs, sets)
    out: dict[str, Any] = {"names": [f.stem for f in files], "measured": segs.measured,
                           "mask": segs.mask, "published": sim[0], "identified": sim[1],
                           "draws": sim[2:], "coverage": {}}
    lo, hi = np.nanpercentile(sim[2:], [2.5, 97.5], axis=0)
    window = np.arange(segs.measured.shape[2]) * segs.sample <= WINDOW + 1e-9
    for i, name in enumerate(out["names"]):
        keep = window & segs.mask[i]
        inside = [(segs.measured[i, k, keep] >= lo[i, k, keep])
                  & (segs.measured[i, k, keep] <= hi[i, k, keep]) for k in range(3)]
        width = [float(np.mean(hi[i, k, keep] - lo[i, k, keep])) for k in range(3)]
        out["coverage"][name] = ([float(np.mean(x)) for x in inside], width)
    out["lo"], out["hi"] = lo, hi
    return out


def tables(result: dict[str, Any], fmt: Any, rst_table: Any) -> tuple[str, str]:
    """The coefficient table and the test-file table (reStructuredText)."""
    fit = result["fit"]
    se, stated = fit.standard_errors, fit.stated_errors
    coef = [[n, fmt(fit.start[n], 4), fmt(fit.values[j], 4), fmt(se[j], 2), fmt(stated[j], 2)]
            for j, n in enumerate(fit.names)]
    coef += [[n, fmt(fit.start[n], 4), "(start)", "–", why] for n, why in fit.fixed.items()]
    text_c = rst_table(
        f"mmg-ls coefficients identified from {len(result['train'])} training files "
        f"({fit.segments} segments of {fit.segment:g} s, measured wind): RMS of the scaled "
        f"residuals {fit.rms_start:.3g} (published) → {fit.rms_fit:.3g}",
        ["coefficient", "published", "identified", "std. error (Laplace)",
         f"stated (variance × {fit.inflation:.3g} + initial states)"], coef)
    rows = []
    for r in result["rows"]:
        p, i = r["published"], r["identified"]
        td = [m.get("tactical_diameter", (math.nan, math.nan)) for m in (p["metrics"],
                                                                         i["metrics"])]
        cov = result["band"]["coverage"].get(r["file"])
        rows.append([r["file"], fmt(p["rms60"]), fmt(i["rms60"]), fmt(p["rms"]), fmt(i["rms"]),
                     fmt(td[0][0] / 3.0), fmt(td[0][1] / 3.0), fmt(td[1][1] / 3.0),
                     "–" if cov is None else f"{100 * np.mean(cov[0][:2]):.0f} %",
                     "–" if cov is None else fmt(0.5 * np.mean(cov[1][:2]) / 3.0, 2)])
    text_t = rst_table(
        "Test files (not fitted), measured wind: RMS position error [L] over the first 60 s "
        "and the whole record, tactical diameter [L], the share of the first minute's "
        "measured positions inside the posterior's 95 % band and the band's mean half-width "
        "[L]",
        ["test file", "RMS 60 s publ.", "ident.", "RMS whole publ.", "ident.", "TD meas.",
         "TD publ.", "TD ident.", "in band", "half-width"], rows)
    return text_c, text_t


def figure(result: dict[str, Any], path: Path) -> None:
    """Measured track, published and identified prediction, posterior draws and their 95 %
    band (north and east against time) of each test file."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    band = result["band"]
    names = band["names"]
    fig, axes = plt.subplots(len(names), 2, figsize=(8.0, 1.75 * len(names)), squeeze=False)
    for i, name in enumerate(names):
        keep = band["mask"][i]
        t = np.arange(keep.size)[keep]
        for col, (k, label) in enumerate(((0, "x₀ (north) [m]"), (1, "y₀ (east) [m]"))):
            ax = axes[i, col]
            ax.fill_between(t, band["lo"][i, k, keep], band["hi"][i, k, keep], color="C0",
                            alpha=0.3, lw=0, label="95 % band (posterior)")
            ax.plot(t, band["measured"][i, k, keep], "k-", lw=1.0, label="measured")
            ax.plot(t, band["identified"][i, k, keep], "C0-", lw=0.8, label="identified")
            ax.plot(t, band["published"][i, k, keep], "C3--", lw=0.8, label="published")
            ax.axvline(WINDOW, color="0.6", lw=0.6)
            ax.set_ylabel(label, fontsize=7)
            ax.tick_params(labelsize=6)
            if col == 0:
                ax.set_title(name, fontsize=7, loc="left")
    axes[0, 0].legend(fontsize=6, loc="best")
    for ax in axes[-1]:
        ax.set_xlabel("t [s] from the record's first sample", fontsize=7)
    fig.suptitle("Esso Osaka 3 m, test files: measured wind, from the first sample", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)
