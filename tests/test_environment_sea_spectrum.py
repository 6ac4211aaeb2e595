"""The sea given by Hs, Tp and γ (issue 47 item 4: the per-spectrum parameter rules that were
in ``cli/seakeeping.py``): each parameter is taken by the spectra whose class declares it,
required where it has no default, within :data:`SEA_BOUNDS`; errors name the parameter."""

from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from seahelm.environment.spectra import (
    Bretschneider,
    Jonswap,
    PiersonMoskowitz,
    sea_spectrum,
)
from seahelm.errors import ParameterError


@pytest.mark.parametrize("name, kwargs, want", [
    ("jonswap", dict(peak_period=10.0), Jonswap(significant_height=4.0, peak_period=10.0)),
    ("jonswap", dict(peak_period=10.0, gamma=2.0),
     Jonswap(significant_height=4.0, peak_period=10.0, gamma=2.0)),
    ("bretschneider", dict(peak_period=9.0), Bretschneider(significant_height=4.0,
                                                           peak_period=9.0)),
    ("ittc", dict(peak_period=9.0), Bretschneider(significant_height=4.0, peak_period=9.0)),
    ("pierson-moskowitz", {}, PiersonMoskowitz(significant_height=4.0)),
])
def test_each_spectrum_takes_its_parameters(name, kwargs, want):
    assert sea_spectrum(name, significant_height=4.0, **kwargs) == want


@pytest.mark.parametrize("name, kwargs, field, match", [
    ("pierson-moskowitz", dict(peak_period=10.0), "peak_period",
     r"is not taken by pierson-moskowitz \(of Hs, Tp, γ it takes Hs\)"),
    ("bretschneider", dict(peak_period=9.0, gamma=2.0), "gamma",
     r"is not taken by bretschneider \(of Hs, Tp, γ it takes Hs, Tp\)"),
    ("jonswap", {}, "peak_period", r"is required for jonswap \[s\]"),
    ("jonswap", dict(peak_period=1e300), "peak_period", r"must be in \[0.1, 1000\] \[s\]"),
    ("jonswap", dict(peak_period=10.0, gamma=0.5), "gamma", r"must be in \[1, 20\] \[-\]"),
    ("jonswap", dict(peak_period=10.0, gamma=math.nan), "gamma", r"got nan"),
])
def test_what_a_spectrum_does_not_take_or_needs_is_named(name, kwargs, field, match):
    with pytest.raises(ParameterError, match=match) as info:
        sea_spectrum(name, significant_height=4.0, **kwargs)
    assert info.value.field == field


@pytest.mark.parametrize("hs", [0.0, -1.0, 101.0, math.inf])
def test_the_significant_height_bounds(hs):
    with pytest.raises(ParameterError, match=r"must be in \(0, 100\] \[m\]") as info:
        sea_spectrum("pierson-moskowitz", significant_height=hs)
    assert info.value.field == "significant_height"


def test_an_unknown_spectrum_lists_the_valid_ones():
    with pytest.raises(ParameterError, match="unknown spectrum 'jonswop'; valid: .*'jonswap'"):
        sea_spectrum("jonswop", significant_height=4.0)


def test_the_command_names_the_option():
    """`seahelm seakeeping --spectrum bretschneider --gamma 2`: γ was dropped silently."""
    from seahelm.cli.main import app

    res = CliRunner().invoke(app, ["seakeeping", "kvlcc2-l7", "--hs", "4", "--tp", "10",
                                   "--spectrum", "bretschneider", "--gamma", "2"])
    assert res.exit_code == 2
    assert "`--gamma` is not taken by bretschneider" in res.stderr


def test_the_commands_choices_come_from_the_registry():
    """`seahelm seakeeping --spectrum` offers the registry's spectra given by Hs (it was a
    copied list); importing the spectra costs no scipy."""
    import subprocess
    import sys
    import typing

    from seahelm.cli import seakeeping
    from seahelm.environment.spectra import SPECTRA, sea_spectrum_names

    assert typing.get_args(seakeeping.SpectrumName) == sea_spectrum_names()
    assert set(sea_spectrum_names()) == {"jonswap", "bretschneider", "ittc",
                                         "pierson-moskowitz"}
    assert set(sea_spectrum_names()) < set(SPECTRA)
    code = ("import sys, seahelm.environment.spectra; "
            "print(','.join(m for m in ('scipy', 'numba') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == ""
