"""Controllers declare the units of their commands and states (issue 47 item 4): every
registered controller (but the pass-through open loop) has one unit per command and per state,
and a command's unit is the one the registered actuators and models declare for the channel it
feeds (the wiring's rule: ``X_command`` feeds ``X_command`` or ``X``), wherever they declare
one; the units show in :meth:`~seahelm.control.base.Controller.signals`."""

from __future__ import annotations

import dataclasses

import pytest

from seahelm.control.base import Controller
from seahelm.registry import CONTROLLERS, _declared_units, get_controller

NAMES = sorted(n for n in CONTROLLERS if not get_controller(n).passthrough)


@pytest.mark.parametrize("name", NAMES)
def test_every_command_and_state_has_a_unit(name):
    c = get_controller(name)
    assert len(c.command_units) == len(c.command_labels) > 0
    assert len(c.state_units) == len(c.state_labels)
    rows = {(kind, n): u for kind, n, u in c.signals()}
    for n, u in zip(c.command_labels, c.command_units):
        assert rows[("command", n)] == u
    for n, u in zip(c.state_labels, c.state_units):
        assert rows[("state", n)] == u


@pytest.mark.parametrize("name", NAMES)
def test_a_command_unit_is_that_of_the_channel_it_feeds(name):
    declared = _declared_units()
    c = get_controller(name)
    checked = 0
    for n, unit in zip(c.command_labels, c.command_units):
        fed = set().union(*(declared.get(("command", k), ()) for k in
                            (n, n.removesuffix("_command"))))
        if len(fed) == 1:  # (where the components agree on one unit)
            assert unit == next(iter(fed)), (n, unit, fed)
            checked += 1
    assert checked >= 1


def test_a_relabelled_copy_has_its_units_undeclared():
    """(dataclasses.replace of the labels alone, as tests and users do to rewire a
    controller: the old units no longer name its signals.)"""
    base = get_controller("pid-heading")
    two = dataclasses.replace(base, command_labels=("a", "b"))
    assert two.command_units == () and two.state_units == base.state_units
    assert [u for kind, _, u in two.signals() if kind == "command"] == ["", ""]
    more = dataclasses.replace(base, state_labels=("x", "y"))
    assert more.state_units == () and more.command_units == ("rad",)
    assert isinstance(more, Controller)
