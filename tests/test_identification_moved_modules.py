"""The identification modules moved into :mod:`seahelm.identification` (issue 47, item 1), and
the analysis modules regrouped into subpackages (item 2): the old paths users may import still
give the same objects, with a DeprecationWarning that names the new module, and no module lives
at the old path (no second home)."""
from __future__ import annotations

import importlib
import sys
import warnings
from pathlib import Path

import pytest

import seahelm.analysis
import seahelm.identification

MOVED = {
    "seahelm.analysis.nomoto_fit": "seahelm.identification.nomoto_fit",
    "seahelm.analysis.nomoto_fit_result": "seahelm.identification.nomoto_fit_result",
    "seahelm.analysis.nomoto_posterior": "seahelm.identification.nomoto_posterior",
    "seahelm.analysis.mmg_fit": "seahelm.identification.mmg_fit",
    "seahelm.analysis.mmg_posterior": "seahelm.identification.mmg_posterior",
    "seahelm.analysis.mmg_checks": "seahelm.identification.mmg_checks",
    "seahelm.analysis.linear_fit": "seahelm.identification.linear_fit",
    "seahelm.analysis.fit_statistics": "seahelm.identification.fit_result",
    "seahelm.analysis.records": "seahelm.identification.records",
    "seahelm.analysis.velocity_smoother": "seahelm.identification.velocity_smoother",
    "seahelm.analysis.samples_file": "seahelm.identification.samples_file",
    "seahelm.identification.criteria": "seahelm.identification.reduced.criteria",
    "seahelm.identification.fitting": "seahelm.identification.reduced.fitting",
    "seahelm.identification.reduced_forms": "seahelm.identification.reduced.forms",
    "seahelm.identification.segments": "seahelm.identification.reduced.segments",
    "seahelm.identification.steady_turns": "seahelm.identification.reduced.turns",
    "seahelm.identification.turn_log": "seahelm.identification.records",
    # analysis regrouped into subpackages (issue 47, item 2)
    "seahelm.analysis.imo_probability": "seahelm.analysis.imo.probability",
    "seahelm.analysis.imo_monte_carlo": "seahelm.analysis.imo.monte_carlo",
    "seahelm.analysis.imo_ensemble": "seahelm.analysis.imo.ensemble",
    "seahelm.analysis.imo_given_fit": "seahelm.analysis.imo.given_fit",
    "seahelm.analysis.response_statistics": "seahelm.analysis.seakeeping.response_statistics",
    "seahelm.analysis.wave_motion_metrics": "seahelm.analysis.seakeeping.time_domain",
    "seahelm.analysis.replay_dataset": "seahelm.analysis.replay.dataset",
    "seahelm.analysis.reversals": "seahelm.analysis.replay.reversals",
    "seahelm.analysis.record_segments": "seahelm.analysis.replay.segments",
    "seahelm.analysis.mmg_multi_record": "seahelm.analysis.replay.mmg_multi_record",
    "seahelm.analysis.turning": "seahelm.analysis.maneuvers.advance_transfer",
    "seahelm.analysis.course_keeping": "seahelm.analysis.maneuvers.course_keeping",
    "seahelm.analysis.steering_indices": "seahelm.analysis.steering.indices",
    "seahelm.analysis.autopilot_tuning": "seahelm.analysis.steering.autopilot_tuning",
    "seahelm.analysis.averaging": "seahelm.studies.platonov.averaging",
    "seahelm.analysis.nonsmooth": "seahelm.numerics.nonsmooth",
    "seahelm.analysis.dp_capability": "seahelm.analysis.dp.level1",
    "seahelm.analysis.dp_capability_level3": "seahelm.analysis.dp.level3",
}


def _forget(old: str) -> None:
    """Undo an earlier import of the old name in this process, so that it is made again."""
    sys.modules.pop(old, None)
    parent, _, leaf = old.rpartition(".")
    sys.modules[parent].__dict__.pop(leaf, None)


@pytest.mark.parametrize("old, new", sorted(MOVED.items()))
def test_the_old_path_imports_the_new_module_and_warns(old, new):
    _forget(old)
    with pytest.warns(DeprecationWarning, match=rf"{old} is deprecated: use {new} "):
        module = importlib.import_module(old)
    real = importlib.import_module(new)
    assert module is real
    assert sys.modules[old] is real
    # the module keeps its own identity: name and spec are the new module's
    assert real.__name__ == new and real.__spec__.name == new


@pytest.mark.parametrize("old", sorted(MOVED))
def test_no_module_lives_at_the_old_path(old):
    parent, _, leaf = old.rpartition(".")
    folder = Path(sys.modules[parent].__file__).parent
    assert not (folder / f"{leaf}.py").exists()
    assert not (folder / leaf).exists()


def test_from_import_of_a_name_gives_the_same_object():
    _forget("seahelm.analysis.mmg_fit")
    with pytest.warns(DeprecationWarning, match="seahelm.identification.mmg_fit"):
        from seahelm.analysis.mmg_fit import identify_mmg
    from seahelm.identification.mmg_fit import identify_mmg as new

    assert identify_mmg is new


def test_from_package_import_and_attribute_access_warn():
    _forget("seahelm.analysis.records")
    with pytest.warns(DeprecationWarning, match="seahelm.identification.records"):
        from seahelm.analysis import records
    assert records is importlib.import_module("seahelm.identification.records")
    _forget("seahelm.analysis.nomoto_fit")
    with pytest.warns(DeprecationWarning, match="seahelm.identification.nomoto_fit"):
        module = seahelm.analysis.nomoto_fit
    assert module is importlib.import_module("seahelm.identification.nomoto_fit")


def test_the_warning_points_at_the_importing_code():
    _forget("seahelm.analysis.linear_fit")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        import seahelm.analysis.linear_fit  # noqa: F401
    assert [Path(w.filename).name for w in caught] == [Path(__file__).name]


def test_the_renamed_steady_turns_of_the_reduced_model():
    # 'steady_turns' was two functions: the batched equilibria of any model
    # (seahelm.analysis.equilibria.batch_steady_turn.steady_turns, kept) and the steady turns of
    # Voitkunsky's model, now voitkunsky_turns
    from seahelm.identification.reduced import turns

    with pytest.warns(DeprecationWarning, match="voitkunsky_turns"):
        old = turns.steady_turns
    assert old is turns.voitkunsky_turns


def test_one_reader_module_for_every_record_format():
    # the turn log's reader was identification/turn_log.py, which analysis/records.py imported
    from seahelm.identification import records

    assert records._read_csv.__module__ == records.read_turn_log.__module__ == records.__name__
    _forget("seahelm.identification.turn_log")
    with pytest.warns(DeprecationWarning, match="seahelm.identification.records"):
        from seahelm.identification.turn_log import read_turn_log
    assert read_turn_log is records.read_turn_log


def test_unknown_names_are_still_attribute_errors():
    with pytest.raises(AttributeError, match="no attribute 'nomoto_fits'"):
        seahelm.analysis.nomoto_fits  # noqa: B018
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("seahelm.analysis.no_such_module")
    with pytest.raises(AttributeError, match="no attribute 'fitting2'"):
        seahelm.identification.fitting2  # noqa: B018
