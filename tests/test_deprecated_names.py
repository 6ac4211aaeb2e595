"""One name per concept (issue 47 item 5): ``to_xarray`` is the name of "as an xarray
Dataset" (``to_dataset`` a deprecated alias), ``Problem`` and ``Ship`` the names of the batch
and the ship (``RunBatch`` and ``ManeuverShip`` deprecated aliases). Each old name still gives
the same object, with a :class:`DeprecationWarning` naming the new one; nothing in seahelm
uses the old names (importing its modules warns nothing)."""

from __future__ import annotations

import importlib
import subprocess
import sys
import warnings

import numpy as np
import pytest

from seahelm.ships import Ship
from seahelm.simulation.problem import Problem


@pytest.mark.parametrize("module, old, new, replacement", [
    ("seahelm", "RunBatch", Problem, "seahelm.Problem"),
    ("seahelm.simulation.batch", "RunBatch", Problem, "seahelm.Problem"),
    ("seahelm.analysis.maneuvers", "ManeuverShip", Ship, "seahelm.Ship"),
    ("seahelm.analysis.maneuvers.ships", "ManeuverShip", Ship, "seahelm.Ship"),
    ("seahelm.analysis.maneuvers.common", "ManeuverShip", Ship, "seahelm.Ship"),
])
def test_an_old_name_warns_and_is_the_new_object(module, old, new, replacement):
    mod = importlib.import_module(module)
    with pytest.warns(DeprecationWarning, match=rf"{module}\.{old} is deprecated: use "
                                                rf"{replacement}"):
        value = getattr(mod, old)
    assert value is new
    with pytest.warns(DeprecationWarning):
        exec(f"from {module} import {old} as got", {})  # noqa: S102 (the import form too)


def test_an_unknown_name_is_still_an_attribute_error():
    from seahelm.simulation import batch

    with pytest.raises(AttributeError, match="has no attribute 'RunBatches'"):
        batch.RunBatches  # noqa: B018


def test_the_old_names_are_not_in_the_public_lists():
    import seahelm
    import seahelm.analysis.maneuvers as maneuvers
    import seahelm.simulation.batch as batch

    assert "RunBatch" not in seahelm.__all__ and "RunBatch" not in batch.__all__
    assert "ManeuverShip" not in maneuvers.__all__


def test_importing_seahelm_uses_no_old_name():
    code = ("import warnings; warnings.simplefilter('error', DeprecationWarning); "
            "import seahelm, seahelm.cli.main, seahelm.scenario, seahelm.analysis.maneuvers, "
            "seahelm.sweep.chunks, seahelm.analysis.imo.probability; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def _rao():
    from seahelm.environment.rao import closed_form_rao
    from seahelm.vessels.particulars import Particulars

    ship = Particulars(length=175.0, beam=25.4, draft=8.5, block_coefficient=0.5617)
    return closed_form_rao(ship, 6.0, metacentric_height=0.5,
                           frequency=np.linspace(0.2, 1.2, 6), heading=np.radians([0, 90, 180]))


def _moments():
    from seahelm.analysis.seakeeping.frequency_domain import closed_form_moments
    from seahelm.environment.spectra import Jonswap
    from seahelm.vessels.particulars import Particulars

    ship = Particulars(length=175.0, beam=25.4, draft=8.5, block_coefficient=0.5617)
    return closed_form_moments(ship, Jonswap(significant_height=4.0, peak_period=10.0), [0.0],
                               np.radians([90.0]), metacentric_height=0.8)


@pytest.mark.parametrize("make", [_rao, _moments], ids=["RAO", "ResponseMoments"])
def test_to_dataset_is_a_deprecated_to_xarray(make):
    obj = make()
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        new = obj.to_xarray()
    with pytest.warns(DeprecationWarning, match=rf"{type(obj).__name__}\.to_dataset\(\) is "
                                                r"deprecated: use \.to_xarray\(\)"):
        old = obj.to_dataset()
    new.attrs.pop("created", None)
    old.attrs.pop("created", None)
    assert old.identical(new)


def test_the_sweep_polar_has_to_xarray():
    from seahelm.sweep.seakeeping import SweepSeakeeping

    assert callable(SweepSeakeeping.to_xarray)
    assert SweepSeakeeping.to_dataset.__doc__.startswith("Deprecated name of")
