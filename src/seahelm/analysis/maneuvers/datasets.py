"""Metrics Datasets of manoeuvres built without xarray's per-object overhead.

A single run's metrics are twenty 0-d variables; building them the ordinary way (each
``xr.Variable`` through its constructor, the Dataset through its merge and alignment) took a
good part of a short turning circle (issue 46 item 6). :func:`_variable` fills a Variable's
slots directly and :func:`_indexless_dataset` puts ready variables in place, each after
checking what it assumes of this xarray, with the ordinary construction as the fallback
(``tests/test_maneuver_metrics_variables.py`` and ``tests/test_analysis_maneuvers.py`` compare
the two).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__: list[str] = []


def _variable(dims: tuple[str, ...], arr: Any, attrs: Mapping[str, Any], *,
              own: bool = False) -> "xr.Variable":
    """``xr.Variable(dims, arr, attrs)`` of a plain numeric, boolean or string array.

    What xarray makes of such an array is the array itself (its conversions concern objects,
    dates and other array types): its fast path is taken, and where this xarray's Variable is
    the four slots that constructor fills (:func:`_raw_variables`, checked once against the
    constructor), they are filled directly — a fifth of the constructor's microsecond, which
    twenty metrics of a single run paid each.
    """
    variable = _variable_class()
    if type(arr) is not np.ndarray or arr.dtype.kind not in "biufU":
        return variable(dims, arr, attrs)
    if len(dims) != arr.ndim or not _raw_variables():
        return variable(dims, arr, attrs, fastpath=True)
    var = _NEW_VARIABLE(variable)
    var._data, var._dims = arr, tuple(dims)
    # (``own``: ``attrs`` is a fresh dict of the caller's, kept rather than copied)
    var._attrs = (attrs if own and type(attrs) is dict else dict(attrs)) if attrs else None
    var._encoding = None
    return var


_NEW_VARIABLE = object.__new__


@functools.cache
def _xarray() -> Any:
    """The xarray module, imported when first needed (xarray is imported lazily; an import
    statement at every call cost a fifth of :func:`_variable`, for each of twenty metrics)."""
    import xarray as xr

    return xr


@functools.cache
def _variable_class() -> type:
    """``xarray.Variable`` (:func:`_xarray`)."""
    return _xarray().Variable


@functools.cache
def _raw_variables() -> bool:
    """Whether this xarray's Variable is exactly the slots ``_data``, ``_dims``, ``_attrs``,
    ``_encoding`` and its fast-path constructor fills them as :func:`_variable` does (a probe
    of both, compared slot by slot)."""
    import xarray as xr

    slots: set[str] = set()
    for cls in type.mro(xr.Variable):
        slots.update(getattr(cls, "__slots__", ()) or ())
    if slots != {"_data", "_dims", "_attrs", "_encoding"}:  # pragma: no cover - other xarray
        return False
    probe = np.array([1.0, 2.0])
    made = xr.Variable(("x",), probe, {"units": "m"}, fastpath=True)
    try:
        return (made._data is probe and made._dims == ("x",) and made._attrs == {"units": "m"}
                and type(made._attrs) is dict and made._encoding is None)
    except AttributeError:  # pragma: no cover - other xarray
        return False


def _indexless_dataset(data: Mapping[str, Any], coords: Mapping[str, Any],
                       attrs: dict[str, Any]) -> "xr.Dataset | None":
    """A Dataset of ready :class:`xarray.Variable` objects that need no index, built directly.

    ``xr.Dataset(...)`` merges, aligns and copies every variable: for a single run's metrics
    (twenty 0-d variables) that took about 1 ms, half of a whole turning circle, where putting
    the variables in place takes microseconds. This does the latter through xarray's
    ``Dataset._construct_direct`` once it has checked what that constructor assumes: every
    variable a Variable, no name shared by data and coordinates, no dimension coordinate (which
    would need an index) and consistent dimension sizes. None when a check fails or this
    xarray lacks the constructor: the caller then builds the Dataset the ordinary way
    (``tests/test_analysis_maneuvers.py`` checks that both give identical Datasets).
    """
    xr = _xarray()
    construct = getattr(xr.Dataset, "_construct_direct", None)
    if construct is None or set(data) & set(coords):  # pragma: no cover - other xarray
        return None
    variables = {**data, **coords}
    dims: dict[str, int] = {}
    raw = _raw_variables()  # (then a Variable's dims and shape are its slots': read them)
    for name, var in variables.items():
        if type(var) is not xr.Variable:
            return None
        var_dims, shape = (var._dims, var._data.shape) if raw and type(
            var._data) is np.ndarray else (var.dims, var.shape)
        if name in var_dims:
            return None
        for dim, size in zip(var_dims, shape):
            if dims.setdefault(dim, size) != size:
                return None
    try:
        return construct(variables, set(coords), dims, attrs, {}, None)
    except TypeError:  # pragma: no cover - a changed signature
        return None


def _single_run_dataset(variables: Mapping[str, tuple[Any, str, str]],
                        coords: Mapping[str, tuple[tuple[str, ...], Any, Mapping[str, Any]]],
                        attrs: dict[str, Any]) -> "xr.Dataset | None":
    """A single run's metrics Dataset (a grid without dimensions): what
    :meth:`~seahelm.analysis.maneuvers.common.Plan.dataset` builds through :func:`_variable`
    and :func:`_indexless_dataset`, in one pass.

    ``variables[name] = (values, units, long_name)`` with ``values`` of shape (1,) (strings
    as objects or unicode), ``coords[name] = (dims, value, attrs)`` of scalars. Every variable
    is 0-d, so there are no dimension sizes to reconcile: each one's slots are filled
    directly (the same data, a 0-d view of the value, and the same attrs as
    :func:`_variable`'s). None where an assumption does not hold (a value of another shape or
    kind, a coordinate that is not a scalar, a name shared, another xarray): the caller then
    builds it the general way (``tests/test_maneuver_single_run_dataset.py`` compares the two).
    """
    xr = _xarray()
    construct = getattr(xr.Dataset, "_construct_direct", None)
    if construct is None or not _raw_variables():  # pragma: no cover - other xarray
        return None
    cls, new = xr.Variable, _NEW_VARIABLE
    variables_out: dict[str, Any] = {}
    for name, (values, units, long_name) in variables.items():
        arr = values if type(values) is np.ndarray else np.asarray(values)
        if arr.shape != (1,):
            return None
        if arr.dtype.kind == "O":
            arr = arr.astype(str)
        if arr.dtype.kind not in "biufU":
            return None
        var = new(cls)
        var._data, var._dims, var._encoding = arr.reshape(()), (), None
        var._attrs = {"long_name": long_name, "units": units} if units else {
            "long_name": long_name}
        variables_out[name] = var
    for name, (cdims, cvalue, cattrs) in coords.items():
        carr = np.asarray(cvalue)
        if cdims or carr.ndim or carr.dtype.kind not in "biufU" or name in variables_out:
            return None
        var = new(cls)
        var._data, var._dims, var._encoding = carr, (), None
        var._attrs = dict(cattrs) if cattrs else None
        variables_out[name] = var
    try:
        return construct(variables_out, set(coords), {}, attrs, {}, None)
    except TypeError:  # pragma: no cover - a changed signature
        return None

