"""The example scripts run as a user runs them, and print what they promise."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_kvlcc2_turning_example():
    proc = subprocess.run([sys.executable, str(EXAMPLES / "kvlcc2_turning.py")],
                          capture_output=True, text=True, timeout=900,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    m = re.search(r"advance ([\d.]+) L, transfer ([\d.]+) L, tactical diameter ([\d.]+) L",
                  proc.stdout)
    assert m, proc.stdout
    advance, transfer, tactical = map(float, m.groups())
    # KVLCC2 L7, 35°, w_P0 0.40, x'_P −0.48: advance and tactical diameter near 3.1 L (other
    # MMG implementations give 3.0–3.4 L); transfer is well under the tactical diameter
    assert 3.0 < advance < 3.4
    assert 3.0 < tactical < 3.5
    assert 0.3 * tactical < transfer < 0.6 * tactical


def test_kvlcc2_environment_example(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLES / "kvlcc2_environment.py"), str(tmp_path)],
                          capture_output=True, text=True, timeout=900,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    rows = {(m.group(1).strip(), m.group(2)): tuple(map(float, m.group(3, 4, 5))) for m in
            re.finditer(r"^(.{28}) +(stbd|port) +([\d.]+) +([\d.]+) +([\d.]+)$", proc.stdout,
                        re.M)}
    assert len(rows) == 6, proc.stdout
    calm_s, calm_p = rows[("calm water", "stbd")], rows[("calm water", "port")]
    cur_s, cur_p = rows[("current 0.1 m/s setting E", "stbd")], rows[
        ("current 0.1 m/s setting E", "port")]
    # a current across the approach leaves the advance (along north) as in calm water and
    # carries the circles east: the starboard transfer grows, the port one shrinks
    assert cur_s[0] == calm_s[0] and cur_p[0] == calm_p[0]
    assert cur_s[1] > calm_s[1] + 0.2 and cur_p[1] < calm_p[1] - 0.2
    # wind and waves from the east push the circles west: the other way round
    wind_s, wind_p = rows[("wind 3 m/s + waves from E", "stbd")], rows[
        ("wind 3 m/s + waves from E", "port")]
    assert wind_s[1] < calm_s[1] and wind_p[1] > calm_p[1]
    assert (tmp_path / "kvlcc2_environment.png").stat().st_size > 20_000
