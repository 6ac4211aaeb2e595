"""Property-based tests (hypothesis) of the small pieces everything else relies on."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from seahelm.constants import wrap_angle
from seahelm.control.base import wrap_pi
from seahelm.parameters import Params
from seahelm.simulation.signals import Steps
from seahelm.vessels.nomoto import NOMOTO2, Nomoto2Params

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)


@example(np.nextafter(-math.pi, -math.inf))
@example(-math.pi)
@example(math.pi)
@example(3 * math.pi)
@given(finite)
def test_wrap_angle_lands_in_half_open_interval_and_keeps_the_direction(a):
    w = float(wrap_angle(a))
    assert -math.pi <= w < math.pi
    turns = (a - w) / (2 * math.pi)
    assert abs(turns - round(turns)) < 1e-6


wrap_pi(0.0)  # compile outside hypothesis' deadline


@example(np.nextafter(-math.pi, -math.inf))
@example(-math.pi)
@example(math.pi)
@settings(deadline=None)
@given(finite)
def test_compiled_wrap_equals_numpy_wrap(a):
    assert wrap_pi(a) == float(wrap_angle(a))


positive = st.floats(min_value=1e-3, max_value=1e3)


@settings(max_examples=50, deadline=None)
@given(gain=positive, t1=positive, t2=positive, t3=st.floats(min_value=0.0, max_value=1e3),
       speed=st.floats(min_value=0.0, max_value=30.0, exclude_min=True))  # U > 0
def test_params_round_trip_through_arrays(gain, t1, t2, t3, speed):
    p = Nomoto2Params(gain=gain, t1=t1, t2=t2, t3=t3, speed=speed)
    assert Nomoto2Params.from_array(p.to_array()) == p
    assert isinstance(p, Params)
    # packed once per (frozen) instance; every call gets its own writeable copy
    a = p.to_array()
    a[:] = -1.0
    again = p.to_array()
    assert again.flags.writeable and again is not a
    assert np.array_equal(again[:5], [gain, t1, t2, t3, speed])


@settings(max_examples=25, deadline=None)
@given(arrays(np.float64, (4, 5), elements=st.floats(-2, 2)),
       arrays(np.float64, (4, 1), elements=st.floats(-0.6, 0.6)))
def test_batched_derivative_equals_row_by_row(x, u):
    p = Nomoto2Params(gain=0.185, t1=118.0, t2=7.8, t3=18.5, speed=7.7)
    batched = NOMOTO2.derivative(0.0, x, u, p)
    for i in range(4):
        np.testing.assert_array_equal(batched[i], NOMOTO2.derivative(0.0, x[i], u[i], p))


@given(st.lists(st.floats(0, 1000), min_size=1, max_size=6, unique=True),
       st.floats(-10, 2000))
def test_steps_signal_takes_the_last_value_switched_on(times, t):
    times = sorted(times)
    values = list(range(len(times)))
    sig = Steps(tuple(times), tuple(float(v) for v in values))
    expected = values[max(sum(tt <= t for tt in times) - 1, 0)]
    assert float(sig(np.array([t]))[0]) == expected


@settings(max_examples=50, deadline=None)
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-3, 3),
                 st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=3)))
def test_scalar_fast_paths_of_the_checks_agree_with_the_array_checks(value):
    """check_finite/check_positive decide a Python float without numpy: the same verdict."""
    import pytest

    from seahelm._validate import check_finite, check_positive
    from seahelm.errors import ParameterError

    arr = np.asarray(value, dtype=float)
    for check, ok in ((check_finite, np.isfinite(arr).all()),
                      (check_positive, np.isfinite(arr).all() and (arr > 0).all())):
        if ok:
            check("x", value, "m")
        else:
            with pytest.raises(ParameterError, match="`x` must be"):
                check("x", value, "m")


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6),
                 st.booleans(), st.floats(width=32).map(np.float32),
                 st.floats().map(np.float64), st.integers(-5, 5).map(np.int64)))
@example(0.0)  # the exclusive lower bound itself
@example(1e-300)
@example(math.pi / 2)  # the inclusive upper bound
@example(float("nan"))
def test_params_fast_check_accepts_and_refuses_what_the_full_check_does(value):
    """A field's value passes the construction's quick path only where the full check
    (_check_number: a number, not a flag, finite, in the field's range) passes it."""
    from seahelm.control.zigzag import ZigZagParams
    from seahelm.errors import ParameterError
    from seahelm.parameters import _check_number

    field = ZigZagParams.__dataclass_fields__["rudder_amplitude"]  # (0, pi/2], low exclusive
    try:
        _check_number(field, "rudder_amplitude", value)
        full = True
    except ParameterError:
        full = False
    try:
        ZigZagParams(rudder_amplitude=value)
        built = True
    except ParameterError as exc:
        built = False
        assert exc.field == "rudder_amplitude"
    assert built == full
