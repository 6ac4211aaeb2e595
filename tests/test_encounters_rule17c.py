"""The Rule 17(c) verdict (``altered_to_port``): a vessel standing on in a crossing situation
that turns to port for a vessel on its own port side is flagged; a turn to starboard is not;
a head-on (or overtaken) vessel turning to port is not counted. Hand-made states are fed to the
recorder (no simulation), so the headings are exactly the ones stated."""

from __future__ import annotations

import math
import types

import numpy as np

from seahelm.encounters import ColregSectors, FujiiDomain, VerdictRules
from seahelm.encounters.chunked import concat_results
from seahelm.encounters.geometry import Situation
from seahelm.encounters.result import EncounterResult, Recorder

SPEED = 8.0  # [m/s]
TURN = math.radians(20.0)  # own ship's alteration in the second record (> the 5° action)

# (target north, east, heading; own ship's heading change): the own ship at the origin
# heading north; headings clockwise from north, so a turn to port is negative.
CASES = [
    (3000.0, -3000.0, math.pi / 2, -TURN),   # 0 crossing, target on the port bow: to port
    (3000.0, -3000.0, math.pi / 2, +TURN),   # 1 the same: to starboard
    (6000.0, 0.0, math.pi, -TURN),           # 2 head-on: to port (target then to starboard)
    (-1500.0, 300.0, 0.0, -TURN),            # 3 overtaken from astern: to port
    (3000.0, -3000.0, math.pi / 2, -math.radians(3.0)),  # 4 crossing: 3° to port (no action)
    (4000.0, -50.0, math.pi / 2, -TURN),     # 5 crossing from just to port, drawn to starboard
]
#: encounter 5's target in the second record: on the starboard bow, ahead of the own ship
DRAWN = (3900.0, 600.0)


def _result() -> EncounterResult:
    ne = len(CASES)
    enc = types.SimpleNamespace(n_encounters=ne, n_vessels=2, record_every=1,
                                domain=FujiiDomain(), sectors=ColregSectors(),
                                verdict_rules=VerdictRules(), lengths=np.array([320.0, 320.0]),
                                names=("own", "target"))
    rec = Recorder(enc, 1)
    route = np.zeros((ne, 2))
    route[:, 1] = [c[2] for c in CASES]
    for k, time in ((0, 0.0), (1, 60.0)):
        truth = np.zeros((ne, 2, 6))
        truth[:, 0, 3] = SPEED  # (own ship: at the origin, course over ground north)
        truth[:, 0, 4] = [c[3] * k for c in CASES]  # heading: the route's, then altered
        for e, (n, east, heading, _) in enumerate(CASES):
            truth[e, 1] = [n, east, heading, SPEED if e != 3 else 1.5 * SPEED, heading, 0.0]
        if k == 1:
            truth[5, 1, :2] = DRAWN
        rec.add(k, time, truth.reshape(ne * 2, 6), np.zeros((ne, 2)), route,
                np.zeros(ne * 2))
    return rec.finish(np.zeros((ne, 2), dtype=np.int8))


def test_the_geometries_are_the_situations_stated():
    assert _result().situation[:, 0].tolist() == [
        Situation.CROSSING_STAND_ON, Situation.CROSSING_STAND_ON, Situation.HEAD_ON,
        Situation.OVERTAKEN, Situation.CROSSING_STAND_ON, Situation.CROSSING_STAND_ON]


def test_a_port_turn_for_a_port_side_crosser_is_flagged_a_starboard_turn_is_not():
    v = _result().verdicts
    assert v["altered_to_port"][:, 0, 0].tolist() == [True, False, False, False, False, False]
    np.testing.assert_allclose(v["port_alteration"][:, 0, 0],
                               [TURN, 0.0, 0.0, TURN, math.radians(3.0), 0.0], atol=1e-12)
    # (none kept course, beyond the 5° of `keep`, but only the port turn breaks 17(c); in 5
    # the target had drawn to the starboard bow when the own ship turned to port)
    assert v["kept_course"][:, 0, 0].tolist() == [False, False, False, False, True, False]
    # the targets did not turn (give-way in 0, 1, 4; head-on, overtaking: never counted)
    assert not v["altered_to_port"][:, 0, 1].any()


def test_the_summary_counts_crossing_stand_on_encounters_only():
    rows = {r["situation"]: r for r in _result().summary()}
    assert rows["crossing-stand-on"]["own_altered_to_port"] == 1 / 4
    assert rows["head-on"]["own_altered_to_port"] is None
    assert rows["overtaken"]["own_altered_to_port"] is None
    assert rows["all"]["own_altered_to_port"] == 1 / 4  # (of the 4 crossing stand-on)


def test_the_verdict_survives_a_file_and_chunks():
    res = _result()
    back = EncounterResult.from_xarray(res.to_xarray())
    assert back.verdicts["altered_to_port"].tolist() == res.verdicts["altered_to_port"].tolist()
    joined = concat_results([res, res])
    assert joined.verdicts["altered_to_port"][:, 0, 0].sum() == 2


def test_a_file_written_before_the_verdict_still_reads():
    ds = _result().to_xarray().drop_vars(["verdict_altered_to_port",
                                          "verdict_port_alteration"])
    back = EncounterResult.from_xarray(ds)
    assert "altered_to_port" not in back.verdicts
    rows = {r["situation"]: r for r in back.summary()}
    assert rows["crossing-stand-on"]["own_altered_to_port"] is None
    assert rows["crossing-stand-on"]["own_kept_course"] == 1 / 4


def test_the_outcome_table_json_and_report_carry_the_verdict():
    import json

    from typer.testing import CliRunner

    from seahelm.cli.main import app
    from seahelm.report.encounters import outcome_rows

    args = ["encounter", "--monte-carlo", "6", "--overtaking", "0", "--t-final", "600",
            "--detection", "4000", "--seed", "5", "--avoidance", "rule-based"]
    res = CliRunner().invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.output)["methods"]["rule-based"]
    assert all("own_altered_to_port" in r for r in rows)
    table = CliRunner().invoke(app, args, env={"COLUMNS": "200"})
    assert table.exit_code == 0 and "stand-on to port (17c)" in table.output
    # the report's table: the column after "stand-on kept course"
    assert all(len(r) == 9 for r in outcome_rows(_result()))
    by = {r[0]: r[7] for r in outcome_rows(_result())}
    assert by["crossing-stand-on"] == "25.0 %" and by["head-on"] == "—"
