"""Regenerate the tables and figures of the docs page "Validation against measurements".

The free-running model tests of the Esso Osaka 3 m model (FRT-DS-ESSO, Osaka University;
Wakita et al. 2022, Miyauchi et al. 2022; CC BY-NC 4.0 — not part of seahelm: clone it
yourself) replayed with the published low-speed MMG model (catalog ship ``esso-osaka-3m``):

* every record (turning, zig-zag, random, berthing) from its first sample with its measured
  rps and rudder, in still air and with the measured wind (Fujiwara's loads): the turning and
  zig-zag metrics measured vs simulated and the RMS position error;
* the clean propeller reversals of the random and berthing records
  (:mod:`seahelm.analysis.reversals`): time and head reach to u ≤ 0, measured vs simulated.

Usage::

    git clone https://github.com/NAOE-5thLab/FRT-DS-ESSO /some/where/FRT-DS-ESSO
    python validation/esso_osaka.py --data /some/where/FRT-DS-ESSO

writes ``docs/_static/esso-osaka/*.inc`` (the tables the page includes) and ``*.png`` (the
figures), and prints the tables. ``--out DIR`` writes elsewhere. Exit 2 with one line for a
``--data`` folder that is not the data set.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

KINDS = ("turning", "zigzag", "random", "berthing")
SHIP = "esso-osaka-3m"
WIND_LOADS = "fujiwara"
TURN_METRICS = ("advance", "transfer", "tactical_diameter", "steady_diameter", "speed_loss")
ZIGZAG_METRICS = ("overshoot_1", "overshoot_2", "period")
#: The zig-zags' nominal rudder/check angles [deg] (the data set's README), used where the
#: check angle cannot be read from the record's rudder.
ZIGZAG_NOMINAL = {"zigzag_31-Jul-2020_13_04_24": 20, "zigzag_31-Jul-2020_13_14_21": 30,
                  "zigzag_31-Jul-2020_13_22_52": 15, "zigzag_31-Jul-2020_13_29_19": 15,
                  "zigzag_31-Jul-2020_13_42_53": 30, "zigzag_31-Jul-2020_13_50_28": 30,
                  "zigzag_31-Jul-2020_13_57_45": 20, "zigzag_31-Jul-2020_14_03_39": 20,
                  "zigzag_31-Jul-2020_14_10_05": 20}
HERE = Path(__file__).resolve().parent
DEFAULT_OUT = HERE.parent / "docs" / "_static" / "esso-osaka"


def _files(data: Path) -> dict[str, list[Path]]:
    """The data set's CSV files by kind; SystemExit(2) with one line if it is not the set."""
    root = data / "data"
    found = {k: sorted((root / k).glob("*.csv")) for k in KINDS}
    if not root.is_dir() or not all(found.values()):
        missing = [k for k, v in found.items() if not v]
        raise SystemExit(f"esso_osaka.py: error: --data {data}: not a clone of FRT-DS-ESSO "
                         f"(no data/{missing[0] if missing else ''}/*.csv)")
    from seahelm.identification.records import RECORD_FORMATS

    header = open(found["turning"][0]).readline().strip().split(",")
    need = list(RECORD_FORMATS["FRT-DS-ESSO"][0])
    absent = [h for h in need if h not in header]
    if absent:
        raise SystemExit(f"esso_osaka.py: error: --data {data}: {found['turning'][0].name} "
                         f"row 1 lacks column `{absent[0]}` (not the FRT-DS-ESSO format)")
    return found


def _fmt(x: float, digits: int = 3) -> str:
    return "–" if not math.isfinite(x) else f"{x:.{digits}g}"


def _rst_table(title: str, head: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
              for i, h in enumerate(head)]
    line = " ".join("=" * w for w in widths)
    out = [f".. table:: {title}", "", "   " + line,
           "   " + " ".join(h.ljust(w) for h, w in zip(head, widths)), "   " + line]
    out += ["   " + " ".join(c.ljust(w) for c, w in zip(r, widths)) for r in rows]
    out += ["   " + line, ""]
    return "\n".join(out)


def replay_all(files: dict[str, list[Path]]) -> tuple[list[dict], float]:
    from seahelm.identification.records import read_records
    from seahelm.analysis.replay import replay

    from seahelm.analysis.replay import classify
    from seahelm.errors import ParameterError

    rows, t0 = [], time.perf_counter()
    for kind in KINDS:
        for path in files[kind]:
            record = read_records(path)[0]
            chosen = kind if kind in ("turning", "zigzag") else "none"
            angle = None
            if chosen == "zigzag" and classify(record)[1] is None:
                angle = math.radians(ZIGZAG_NOMINAL.get(path.stem, 20))
            loops = (False, True) if chosen == "zigzag" else (False,)
            for closed in loops:
                for wind in ("none", "measured"):
                    row = {"kind": kind, "file": path.name, "wind": wind, "closed": closed}
                    try:
                        r = replay(record, SHIP, kind=chosen, wind=wind, wind_loads=WIND_LOADS,
                                   check_angle=angle, closed_loop=closed)
                    except ParameterError as exc:  # e.g. a record too short for its manoeuvre
                        row["error"] = str(exc).splitlines()[0].replace(str(path), path.name)
                        rows.append(row)
                        continue
                    row.update(rms60=r.rms_error_window, rms=r.rms_error,
                               metrics=dict(r.metrics))
                    rows.append(row)
    return rows, time.perf_counter() - t0


def stops_all(files: dict[str, list[Path]]) -> tuple[list, list, float]:
    from seahelm.identification.records import read_records
    from seahelm.analysis.reversals import find_reversals, replay_stop

    found, out, t0 = [], [], time.perf_counter()
    for kind in ("random", "berthing"):
        for path in files[kind]:
            record = read_records(path)[0]
            for rev in find_reversals(record):
                found.append((path.name, rev))
                for wind in ("none", "measured"):
                    out.append((path.name, replay_stop(record, rev, SHIP, wind=wind,
                                                       wind_loads=WIND_LOADS)))
    return found, out, time.perf_counter() - t0


def _metric_tables(rows: list[dict]) -> str:
    text = []
    for kind, names, scale in (("turning", TURN_METRICS, 3.0), ("zigzag", ZIGZAG_METRICS, 1.0)):
        head = ["record", "wind"]
        for n in names:
            head += [f"{n} meas.", "sim."]
        table, notes = [], []
        for r in rows:
            if r["kind"] != kind:
                continue
            how = r["wind"] + (", closed loop" if r.get("closed") else "")
            if "error" in r:
                notes.append(f"* {r['file']} ({how}): {r['error']}")
                continue
            cells = [r["file"].replace(".csv", ""), how]
            for n in names:
                m, s = r["metrics"].get(n, (math.nan, math.nan))
                k = 1.0
                if n in ("advance", "transfer", "tactical_diameter", "steady_diameter"):
                    k = 1.0 / scale  # in ship lengths
                elif n.startswith("overshoot"):
                    k = 180.0 / math.pi
                cells += [_fmt(m * k), _fmt(s * k)]
            table.append(cells)
        unit = ("lengths in L = 3 m, speed loss 1 − U_end/U_0" if kind == "turning"
                else "overshoots [deg], period [s]")
        text.append(_rst_table(f"{kind}: measured vs simulated ({unit})", head, table))
        if notes:
            text.append("Not replayed:\n\n" + "\n".join(sorted(set(notes))) + "\n")
    rms = [[r["kind"], r["file"].replace(".csv", ""),
            r["wind"] + (", closed loop" if r.get("closed") else ""),
            _fmt(r.get("rms60", math.nan)), _fmt(r.get("rms", math.nan))]
           for r in rows if "error" not in r]
    text.append(_rst_table("RMS position error [L], first 60 s and whole record",
                           ["kind", "record", "wind", "first 60 s", "whole"], rms))
    return "\n".join(text)


def _pct(x: float) -> str:
    return "not stopped" if not math.isfinite(x) else f"{100 * x:+.0f} %"


def _stop_table(found: list, out: list) -> str:
    head = ["record", "t_start [s]", "u_0 [m/s]", "n astern", "wind", "time meas. [s]",
            "sim.", "error", "reach meas. [m]", "sim.", "error"]
    rows = []
    for name, c in out:
        rv = c.reversal
        rows.append([name.replace(".csv", ""), _fmt(rv.start_time, 5), _fmt(rv.start_speed),
                     _fmt(rv.astern_rps), c.wind, _fmt(rv.time_to_stop), _fmt(c.time_to_stop),
                     _pct(c.time_error), _fmt(rv.head_reach), _fmt(c.head_reach),
                     _pct(c.reach_error)])
    text = [_rst_table("Stops after a propeller reversal: measured vs simulated", head, rows)]
    summary = []
    for wind in ("none", "measured"):
        te = np.array([c.time_error for _n, c in out if c.wind == wind])
        re_ = np.array([c.reach_error for _n, c in out if c.wind == wind])
        ok_t = np.isfinite(te)
        summary.append([wind, str(te.size), str(int(np.sum(~ok_t))),
                        f"{100 * np.nanmean(te):+.0f} %",
                        f"{int(np.sum(np.abs(te[ok_t]) <= 0.25))}/{te.size}",
                        f"{100 * np.nanmean(re_):+.0f} %",
                        f"{int(np.sum(np.abs(re_[np.isfinite(re_)]) <= 0.25))}/{re_.size}"])
    text.append(_rst_table(
        "Stops: mean error (of the simulated ships that stopped within twice the measured "
        "time) and count within ±25 % (a ship not stopped counts as outside)",
        ["wind", "stops", "not stopped", "time: mean error", "within ±25 %",
         "reach: mean error", "within ±25 %"], summary))
    return "\n".join(text)


def _figures(out_dir: Path, stops: list) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(8, 3.4))
    for ax, attr, label in ((axes[0], "time_to_stop", "time to u ≤ 0 [s]"),
                            (axes[1], "head_reach", "head reach [m]")):
        for wind, marker in (("none", "o"), ("measured", "^")):
            m = [getattr(c.reversal, attr) for _n, c in stops if c.wind == wind]
            s = [getattr(c, attr) for _n, c in stops if c.wind == wind]
            ax.plot(m, s, marker, ms=4, label=f"wind {wind}")
        values = [getattr(c.reversal, attr) for _n, c in stops] + [
            getattr(c, attr) for _n, c in stops if math.isfinite(getattr(c, attr))]
        top = max(values + [1.0]) * 1.1
        ax.plot([0, top], [0, top], "k-", lw=0.8)
        ax.fill_between([0, top], [0, 0.75 * top], [0, 1.25 * top], color="0.9")
        ax.set_xlim(0, top)
        ax.set_ylim(0, top)
        ax.set_xlabel(f"measured {label}")
        ax.set_ylabel("simulated")
    axes[0].legend(fontsize=7)
    fig.suptitle("Esso Osaka 3 m: stops after a propeller reversal (band ±25 %)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out_dir / "stops.png", dpi=90)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="esso_osaka.py", description=__doc__.splitlines()[0])
    parser.add_argument("--data", required=True, type=Path, help="clone of FRT-DS-ESSO")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="output folder")
    parser.add_argument("--part", choices=("all", "stops", "replays", "identify"),
                        default="all", help="what to regenerate (default all)")
    parser.add_argument("--train", default="Train-TZRB+",
                        help="--part identify: the training column of the README's Wakita "
                             "(2022) table (Train-TZB, Train-TZRB, Train-TZRB+)")
    args = parser.parse_args(argv)
    try:
        files = _files(args.data)
    except SystemExit as exc:
        print(exc, file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    if args.part in ("all", "stops"):
        found, stops, t_stops = stops_all(files)
        text = _stop_table(found, stops)
        (args.out / "stops.inc").write_text(text)
        print(text, flush=True)
        print(f"stops: {len(found)} reversals, {len(stops)} replays in {t_stops:.1f} s",
              flush=True)
        (args.out / "timing-stops.inc").write_text(
            f"The {len(stops)} stop replays took {t_stops:.0f} s on the machine that made this "
            "page (warm kernel cache; 2 cores shared with other work).\n")
        _figures(args.out, stops)
    if args.part in ("all", "replays"):
        rows, t_all = replay_all(files)
        text = _metric_tables(rows)
        (args.out / "replays.inc").write_text(text)
        print(text)
        print(f"replays: {len(rows)} in {t_all:.1f} s")
        (args.out / "timing-replays.inc").write_text(
            f"The {len(rows)} replays (41 records with and without wind; the zig-zags also "
            f"closed loop) took {t_all:.0f} s "
            "on the machine that made this page (warm kernel cache; 2 cores shared with "
            "other work).\n")
    if args.part in ("all", "identify"):
        try:
            _identify(args)
        except SystemExit as exc:  # a README without the train/test table, a bad --train
            print(exc, file=sys.stderr)
            return 2
    return 0


def _identify(args: argparse.Namespace) -> None:
    """``--part identify`` (validation/esso_osaka_identify.py)."""
    sys.path.insert(0, str(HERE))
    import esso_osaka_identify as ident

    result = ident.run(args.data, args.out, train=args.train, zigzag_angles=ZIGZAG_NOMINAL)
    coef, test = ident.tables(result, _fmt, _rst_table)
    (args.out / "identify.inc").write_text(coef)
    (args.out / "identify-test.inc").write_text(test)
    print(coef)
    print(test)
    for name, (inside, width) in result["band"]["coverage"].items():
        print(f"{name}: first 60 s inside the 95 % band: north {100 * inside[0]:.0f} %, east "
              f"{100 * inside[1]:.0f} %, heading {100 * inside[2]:.0f} %; mean band width "
              f"{width[0]:.3g} m, {width[1]:.3g} m, {math.degrees(width[2]):.3g} deg")
    ident.figure(result, args.out / "identify-band.png")
    fit = result["fit"]
    line = (f"The identification ({len(result['train'])} training files, {fit.segments} "
            f"segments, {fit.evaluations} evaluations of the batched simulation) took "
            f"{result['cpu_seconds']:.0f} s of CPU time ({result['seconds']:.0f} s wall "
            "time) on the machine that made this page (warm kernel cache; 2 cores shared "
            "with other work).\n")
    (args.out / "timing-identify.inc").write_text(line)
    print(line, end="")


if __name__ == "__main__":
    sys.exit(main())
