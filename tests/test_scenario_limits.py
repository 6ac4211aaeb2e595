"""Big batches are refused before anything is expanded or allocated, naming the key: more runs
than a batch holds, recordings larger than the machine's memory, step counts that cannot run.
(The machine's memory is patched small, so the tests do not depend on the machine.)"""

from __future__ import annotations

import numpy as np
import pytest

import seahelm.simulation.engine as engine
import seahelm.simulation.memory as memory
from seahelm.errors import ParameterError
from seahelm.scenario import ScenarioError, parse_scenario
from seahelm.ships import catalog
from seahelm.vessels.nomoto import NOMOTO2

BASE = """[vessel]
catalog = "mariner-nomoto2"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 600.0
dt = 0.1
"""


def test_more_runs_than_a_batch_holds():
    text = BASE + ('[batch.grid]\n"controller.params.kp" = [1.0, 2.0, 3.0]\n'
                   '"controller.params.kd" = [10.0, 20.0]\n'
                   '[batch.monte_carlo]\nruns = 200000\nseed = 1\n')
    with pytest.raises(ScenarioError, match=r"s.toml: \[batch\] 1,200,000 runs \(3 x 2 x 200000 "
                                            r"samples\) is more than one batch holds "
                                            r"\(1,000,000\); split the study"):
        parse_scenario(text, source="s.toml")


def _limit(monkeypatch, nbytes, source="this machine's memory"):
    from seahelm.resources import MemoryLimit

    monkeypatch.setattr(memory, "memory_limit", lambda: MemoryLimit(nbytes, source))
    monkeypatch.setattr(memory, "ASK_ABOVE", 0)


def test_recordings_beyond_memory_are_refused_before_expansion(monkeypatch):
    _limit(monkeypatch, 5_000_000)  # 5 MB
    text = BASE + '[batch.grid]\n"controller.params.kp" = [1.0, 2.0, 3.0, 4.0]\n'
    # 4 runs x 6001 records x 19 channels x 8 B = 3.6 MB, a peak of 2.5 x that > 80 % of 5 MB
    # (19: 5 states, servo, 7 outputs, the command, the reference, 4 disturbances)
    with pytest.raises(ScenarioError, match=r"s.toml: \[simulation.record_every\] `record_every`: "
                                            r"the recorded time series would need 0.00365 GB "
                                            r"\(a peak of about 2.5x that\), more than 80% of the "
                                            r"0.005 GB this process may use \(this machine's "
                                            r"memory\) \(4 run\(s\) x 6,001 records x 19 "
                                            r"channels x 8 B\)"):
        parse_scenario(text, source="s.toml")
    # recording every 10th step fits (0.29 MB)
    batch = parse_scenario(text.replace("dt = 0.1\n", "dt = 0.1\nrecord_every = 10\n"))
    assert batch.n_runs == 4


def test_the_engine_refuses_too_large_recordings_too(monkeypatch):
    _limit(monkeypatch, 10_000_000, "the cgroup's memory limit")
    with pytest.raises(ParameterError, match=r"`record_every`: the recorded time series would "
                                             r"need .* GB .*\(the cgroup's memory limit\) "
                                             r"\(1,000 run\(s\) x 1,001 records"):
        engine.simulate(NOMOTO2, catalog.get("mariner-nomoto2").params, np.zeros((1000, 5)),
                        t_final=100.0, dt=0.1)


def test_a_step_count_that_cannot_run():
    with pytest.raises(ScenarioError, match=r"s.toml: \[simulation.t_final\] 1e\+303 steps "
                                            r"\(t_final/dt = 1e\+300/0.001\) cannot run"):
        parse_scenario(BASE.replace("t_final = 600.0", "t_final = 1e300").replace(
            "dt = 0.1", "dt = 1e-3"), source="s.toml")


@pytest.mark.parametrize("edit, match", [
    (("heading_deg = 10.0", "heading_deg = 10.0\nheading = 0.2"),
     r"\[controller.reference.heading_deg\] give `heading` \[rad\] or `heading_deg` \[deg\], "
     r"not both"),
    (("[controller]", "[actuator.params]\nmax_angle_deg = 35.0\nmax_angle = 0.6\n[controller]"),
     r"\[actuator.params\] give `max_angle` \[rad\] or `max_angle_deg` \[deg\], not both"),
    (("[simulation]", '[batch.grid]\n"controller.params.kp" = [1.0, 1.0]\n[simulation]'),
     r"\[batch.grid\] grid values of `controller.params.kp` repeat \(1.0\)"),
    (("dt = 0.1", "dt = 0.1\nbounds = { yaw_rate = [1.0, -1.0] }"),
     r"\[simulation.bounds\] bounds of `yaw_rate`: low 1.0 must be < high -1.0"),
    (("heading_deg = 10.0", 'heading_deg = { kind = "step", time = 10.0, after = true }'),
     r"\[controller.reference.heading_deg\] signal 'step': `after` must be a number, got True"),
])
def test_values_that_used_to_be_silently_taken(edit, match):
    assert edit[0] in BASE
    with pytest.raises(ScenarioError, match=match):
        parse_scenario(BASE.replace(*edit), source="s.toml")


def test_a_negative_manoeuvre_rudder_is_an_error_not_the_other_side():
    text = ('[vessel]\ncatalog = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\n'
            'sides = "starboard"\nrudder_deg = -10.0\n')
    with pytest.raises(ScenarioError, match=r"\[maneuver\] `rudder_deg` must be > 0 \[deg\] "
                                            r"\(the side is `sides`\), got -10.0"):
        parse_scenario(text, source="s.toml")
