"""Bad input to ``seahelm identify mmg`` of an mmg-ls ship (the bad-input campaign)."""

from __future__ import annotations

import pytest

from seahelm.cli.identify_mmg_ls import parse_free
from seahelm.errors import ParameterError


def test_a_coefficient_freed_twice_is_refused_by_name():
    # was: the fit ran with a duplicated column and failed with "`LOG`: `names` the records
    # identify none of N_r: N_r: standard error nan exceeds the value"
    with pytest.raises(ParameterError, match=r"\A`--free`: N_r given more than once, got "
                                             r"'N_r,Y_v,N_r'\Z"):
        parse_free("N_r,Y_v,N_r")
    assert parse_free("N_r, Y_v") == ("N_r", "Y_v")
