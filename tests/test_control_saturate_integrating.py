"""The heading autopilots' anti-windup written once (:func:`seahelm.control.pid.saturate_integrating`).

Conditional integration (Åström & Hägglund 2006, §3.5): the integral of the error grows unless
the command is saturated and the error pushes it further out; ``pid-heading`` and
``lq-heading`` both call the one function.
"""

from __future__ import annotations

import pytest

from seahelm.control import lq_heading, pid
from seahelm.control.pid import saturate_integrating


@pytest.mark.parametrize("u_unsat, error, expected", [
    (0.1, 0.5, (0.1, 2.0 + 0.5 * 0.25)),    # inside the limits: integrates
    (0.7, 0.5, (0.3, 2.0)),                 # saturated, the error pushes further out: holds
    (-0.7, -0.5, (-0.3, 2.0)),              # the same on the other side
    (0.7, -0.5, (0.3, 2.0 - 0.5 * 0.25)),   # saturated, the error pulls back in: integrates
    (0.3, 0.5, (0.3, 2.0 + 0.5 * 0.25)),    # at the limit exactly: not saturated
])
def test_saturate_integrating(u_unsat, error, expected):
    assert saturate_integrating.py_func(u_unsat, 0.3, error, 2.0, 0.25) == expected
    assert saturate_integrating(u_unsat, 0.3, error, 2.0, 0.25) == expected


def test_both_heading_autopilots_use_it():
    for step in (pid.pid_heading_step, lq_heading.lq_heading_step):
        names = step.py_func.__code__.co_names
        assert "saturate_integrating" in names and "min" not in names
    assert lq_heading.LQ_HEADING.init is pid.PID_HEADING.init
