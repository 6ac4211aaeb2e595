"""The order of a parallel run (tests/conftest.py): the long modules at the head of each
worker's first slice, nothing lost or repeated, every other test in its own order."""

from __future__ import annotations

from dataclasses import dataclass

from conftest import (
    FOLLOWERS,
    LONG_MODULES,
    order_for_workers,
    ordering_key,
    worksteal_shares,
)


@dataclass(frozen=True)
class Item:
    nodeid: str


def _items(spec: dict[str, int]) -> list[Item]:
    return [Item(f"tests/{m}.py::t{i}") for m, n in spec.items() for i in range(n)]


def test_the_shares_are_the_slices_worksteal_sends():
    # xdist: worker i gets len(pending) // (workers - i) of what is left
    assert worksteal_shares(10, 2) == [5, 5]
    assert worksteal_shares(11, 2) == [5, 6]
    assert worksteal_shares(10, 3) == [3, 3, 4]
    assert sum(worksteal_shares(4611, 2)) == 4611


def test_each_worker_starts_with_a_share_of_the_long_modules():
    items = _items({"a": 30, "long1": 3, "b": 30, "long2": 2, "c": 30, "long3": 1})
    seconds = {"tests/long1.py": 100.0, "tests/long2.py": 60.0, "tests/long3.py": 50.0}
    ordered = order_for_workers(items, 2, seconds)
    assert sorted(ordered, key=items.index) == items  # a permutation
    first, second = ordered[:48], ordered[48:]  # worksteal_shares(96, 2) == [48, 48]
    # the longest to worker 0; the next two (110 s) to worker 1
    assert [i.nodeid for i in first[:3]] == [f"tests/long1.py::t{i}" for i in range(3)]
    assert [i.nodeid for i in second[:3]] == (["tests/long2.py::t0", "tests/long2.py::t1",
                                               "tests/long3.py::t0"])
    rest = [i for i in ordered if "long" not in i.nodeid]
    assert rest == [i for i in items if "long" not in i.nodeid]


def test_a_follower_runs_right_after_its_long_module_on_its_worker():
    items = _items({"a": 20, "long1": 2, "b": 20, "f": 2, "long2": 2, "c": 20})
    seconds = {"tests/long1.py": 100.0, "tests/long2.py": 60.0}
    ordered = order_for_workers(items, 2, seconds, {"tests/long1.py": ("tests/f.py",)})
    assert sorted(ordered, key=items.index) == items
    assert [i.nodeid for i in ordered[:4]] == ["tests/long1.py::t0", "tests/long1.py::t1",
                                               "tests/f.py::t0", "tests/f.py::t1"]
    assert [i.nodeid for i in ordered[33:35]] == ["tests/long2.py::t0", "tests/long2.py::t1"]
    # without its leader a follower stays where it was
    alone = [i for i in items if "long1" not in i.nodeid]
    kept = order_for_workers(alone, 2, seconds, {"tests/long1.py": ("tests/f.py",)})
    assert [i for i in kept if "long" not in i.nodeid] == [i for i in alone
                                                           if "long" not in i.nodeid]


def test_the_tests_of_one_function_or_one_test_are_spread_over_the_workers():
    # the docs-command groups are one function's parameters: each its own entry
    items = ([Item(f"tests/a.py::t{i}") for i in range(20)]
             + [Item(f"tests/d.py::run[g{i}]") for i in range(4)] + [Item("tests/d.py::fast")]
             + [Item(f"tests/b.py::t{i}") for i in range(20)])
    seconds = {"tests/d.py::run[g0]": 100.0, "tests/d.py::run[g1]": 60.0,
               "tests/d.py::run": 30.0, "tests/b.py": 45.0}
    ordered = order_for_workers(items, 2, seconds, {"tests/d.py::run[g0]": ("tests/b.py",)})
    assert sorted(ordered, key=items.index) == items
    first, second = ordered[:22], ordered[22:]  # worksteal_shares(45, 2) == [22, 23]
    # g0 (100 s) and its follower b to worker 0; g1 (60 s), then g2 and g3 (the function's
    # entry, 30 s) to worker 1; the module's other test stays in the rest
    assert [i.nodeid for i in first[:21]] == (["tests/d.py::run[g0]"]
                                              + [f"tests/b.py::t{i}" for i in range(20)])
    assert [i.nodeid for i in second[:3]] == ["tests/d.py::run[g1]", "tests/d.py::run[g2]",
                                              "tests/d.py::run[g3]"]
    assert [i.nodeid for i in ordered if i.nodeid.startswith("tests/a.py")] == [
        f"tests/a.py::t{i}" for i in range(20)]
    assert ordering_key("tests/d.py::run[g1]", seconds) == "tests/d.py::run[g1]"
    assert ordering_key("tests/d.py::run[g3]", seconds) == "tests/d.py::run"
    assert ordering_key("tests/d.py::fast", seconds) is None


def test_a_selection_smaller_than_the_long_modules_is_still_all_there():
    items = _items({"long1": 5, "a": 1})
    ordered = order_for_workers(items, 2, {"tests/long1.py": 10.0})
    assert sorted(ordered, key=items.index) == items


def test_the_long_modules_exist():
    """Every entry names a module, a test function of it or (the docs-command groups, whose
    ids come from the docs) one of that function's parameters."""
    from pathlib import Path

    from test_docs_commands import docs_command_groups

    root = Path(__file__).resolve().parents[1]
    docs = {f"tests/test_docs_commands.py::test_every_command_runs_as_written_in_order[{i}]"
            for _, _, i in docs_command_groups()}
    named = [*LONG_MODULES, *FOLLOWERS, *(f for fs in FOLLOWERS.values() for f in fs)]
    missing = []
    for name in named:
        module, _, function = name.partition("::")
        if not (root / module).is_file():
            missing.append(name)
        elif "[" in function:
            if name not in docs:
                missing.append(name)
        elif function and f"\ndef {function}(" not in (root / module).read_text("utf-8"):
            missing.append(name)
    assert not missing, missing


# ------------------------------------------------------------------------------------------
# the unit tier
# ------------------------------------------------------------------------------------------
class MarkedItem:
    def __init__(self, nodeid):
        self.nodeid, self.marks = nodeid, []

    def add_marker(self, mark):
        self.marks.append(mark.name)


def test_every_test_outside_the_unit_modules_is_marked_slow():
    from conftest import mark_outside_the_unit_tier

    items = [MarkedItem("tests/test_a.py::t"), MarkedItem("tests/test_b.py::t[x]"),
             MarkedItem("tests/test_a.py::C::t")]
    mark_outside_the_unit_tier(items, frozenset({"tests/test_a.py"}), frozenset())
    assert [i.marks for i in items] == [[], ["slow"], []]
    items = [MarkedItem("tests/test_a.py::t[1]"), MarkedItem("tests/test_a.py::u")]
    mark_outside_the_unit_tier(items, frozenset({"tests/test_a.py"}),
                               frozenset({"tests/test_a.py::t"}))
    assert [i.marks for i in items] == [["slow"], []]


def test_the_unit_modules_exist_and_are_in_the_tier(request):
    from pathlib import Path

    from conftest import UNIT_MODULES

    root = Path(__file__).resolve().parents[1]
    assert len(UNIT_MODULES) >= 20
    assert not [m for m in UNIT_MODULES if not (root / m).is_file()]
    # this module is one of them, so this test runs in `make test-fast`
    assert request.node.get_closest_marker("slow") is None
    assert not UNIT_MODULES & {k.split("::", 1)[0] for k in LONG_MODULES}


def test_the_slow_tests_of_the_unit_modules_exist():
    from pathlib import Path

    from conftest import SLOW_UNIT_TESTS, UNIT_MODULES

    root = Path(__file__).resolve().parents[1]
    for test in SLOW_UNIT_TESTS:  # (read from the files: -m "not slow" deselects them)
        module, name = test.split("::")
        assert module in UNIT_MODULES, test
        assert f"\ndef {name}(" in (root / module).read_text(encoding="utf-8"), test


# ------------------------------------------------------------------------------------------
# SEAHELM_TEST_COMPILE_TIMES
# ------------------------------------------------------------------------------------------
def test_the_compile_times_name_what_compiled_and_for_how_long(tmp_path):
    import json

    import numba
    from numba.core import event

    from conftest import CompileTimes

    times = CompileTimes(str(tmp_path / "times.jsonl"))
    listener = times.listener()
    event.register("numba:compile", listener)
    try:
        def triple(x):
            return 3 * x

        assert numba.njit(triple)(2) == 6
    finally:
        event.unregister("numba:compile", listener)
    assert [name for name, _ in times.compiled] == [f"{__name__}.{triple.__qualname__}"]
    assert 0 < times.compiled[0][1] < 60

    class Item:
        nodeid = "tests/x.py::t"

    import sys
    import types

    hook = times.pytest_runtest_protocol(Item(), None)
    next(hook)  # (the test runs here: nothing compiled, a kernel loaded)
    sys.modules["seahelm_kernel_0123"] = types.ModuleType("seahelm_kernel_0123")
    try:
        next(hook)
    except StopIteration:
        pass
    finally:
        del sys.modules["seahelm_kernel_0123"]
    row = json.loads((tmp_path / "times.jsonl").read_text())
    assert row["test"] == "tests/x.py::t" and row["compiled"] == [] and row["compile"] == 0
    assert row["kernels"] == ["seahelm_kernel_0123"]
    assert row["seconds"] >= 0 and row["cpu"] >= 0


def test_the_kernel_census_names_a_tests_kernel_and_stops_it_uncompiled(tmp_path):
    import json

    import numpy as np
    import pytest

    import seahelm.simulation.closed_loop as closed_loop
    from conftest import KernelCensus
    from seahelm.actuators.servo import DIRECT
    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params

    class Item:
        nodeid = "tests/x.py::t"

    census, real = KernelCensus(str(tmp_path / "census.jsonl")), closed_loop.import_generated
    census.pytest_configure(None)
    closed_loop.compile_closed_loop.cache_clear()  # (a kernel this process built is cached)
    try:
        census.pytest_runtest_setup(Item())
        with pytest.raises(pytest.skip.Exception, match="kernel census"):
            simulate(NOMOTO1, Nomoto1Params(gain=0.2, time_constant=50.0, speed=5.0),
                     np.zeros(4), t_final=1.0, dt=0.5, actuator=DIRECT, controller=OPEN_LOOP,
                     reference=np.array([0.1]).reshape(1, 1, 1))
    finally:
        closed_loop.import_generated = real
    row = json.loads((tmp_path / "census.jsonl").read_text())
    assert row["test"] == "tests/x.py::t" and row["kernel"].startswith("seahelm_kernel_")
