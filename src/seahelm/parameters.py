"""Frozen parameter dataclasses with units, and their packing into flat float arrays.

Every dynamic component (vessel model, actuator, controller) takes its parameters as a frozen,
keyword-only dataclass that subclasses :class:`Params`. Fields are declared with
:func:`param`, which records the unit, the paper's symbol and a one-line description; these
feed ``seahelm models``, scenario validation and the docs. Inside the compiled simulation loop
a parameter set is a flat ``float64`` array in field order (:meth:`Params.to_array`).

Compiled component code reads parameters **by name**: the engine hands each run's parameters
to numba as a record (a row of a NumPy structured array, :meth:`Params.record_dtype`), so a
controller writes ``p.kp``, never ``p[0]``. :func:`as_records` views a ``(runs, n_params)``
float array as such records without copying; a parameter class that extends another (e.g. a
compensated PID over the PID's gains) gives records that the base class's compiled code reads
unchanged, since fields are found by name.

SI units and radians inside; degrees only at the edges (scenario files may write
``max_angle_deg = 35`` for a field ``max_angle`` whose unit is ``rad``).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any, ClassVar, Self

import numpy as np

from .errors import ParameterError

__all__ = ["Params", "param", "ParamInfo", "stack_params", "as_records", "signal_indices"]

# Compiled code that already has a specialisation for a parameter class's records, given the
# records of a subclass (a controller's parameters extending the vessel's, the servo-driven
# catamaran's extending the catamaran's), reuses that specialisation instead of compiling a new
# one: numba's width subtyping of records. It is exact here, because a subclass only appends
# fields (the base fields keep their names, types and offsets), but numba flags it as an
# experimental feature (NumbaExperimentalFeatureWarning) at every such call. Filtered by message
# so that numba need not be imported here.
warnings.filterwarnings("ignore", message=r"Record\(.*\) has been considered a subtype of Record\(")


@dataclasses.dataclass(frozen=True)
class ParamInfo:
    """Description of one parameter field."""

    name: str
    unit: str
    symbol: str
    doc: str
    default: Any
    low: float
    high: float
    size: int = 0  # 0: a number; N: a vector of N numbers


def param(
    default: Any = dataclasses.MISSING,
    *,
    unit: str = "",
    symbol: str = "",
    doc: str = "",
    low: float = -math.inf,
    high: float = math.inf,
    low_inclusive: bool = True,
    size: int = 0,
) -> Any:
    """Declare a parameter field with its unit [..], paper symbol and admissible range.

    The range is checked by :meth:`Params.__post_init__`; a value outside it raises
    :class:`~seahelm.errors.ParameterError` naming the field, the unit and the value.

    Parameters
    ----------
    default : object, optional
        Default value (SI units, radians); no default if omitted.
    unit : str, optional
        Unit, e.g. "m", "rad/s", "-" (default "").
    symbol : str, optional
        The paper's symbol (default "").
    doc : str, optional
        Short description (default "").
    low, high : float, optional
        Admissible range [unit] (default -inf, +inf; ``high`` inclusive).
    low_inclusive : bool, optional
        Whether ``low`` itself is admissible (default True).
    size : int, optional
        0 (default) for a number; N > 0 for a vector of N numbers (a tuple; each element in
        the range), e.g. the coordinates of a route. Compiled code reads it as an array field
        of the record (``p.route_north[k]``).

    Returns
    -------
    dataclasses.Field
        The field, with the above in its ``metadata``.
    """
    meta = {
        "unit": unit,
        "symbol": symbol,
        "doc": doc,
        "low": low,
        "high": high,
        "low_inclusive": low_inclusive,
        "size": int(size),
    }
    if default is dataclasses.MISSING:
        return dataclasses.field(metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Params:
    """Base class of parameter sets: validated on construction, packable to an array."""

    #: Human-readable provenance of a named parameter set (paper, table, ship).
    provenance: ClassVar[str] = ""

    def __post_init__(self) -> None:
        for f, name, size, low, high, incl in self._field_checks():
            value = getattr(self, name)
            if size:
                values = _vector(f, value, size)
                object.__setattr__(self, name, values)  # a tuple of floats, however given
                for k, v in enumerate(values):
                    _check_number(f, f"{name}[{k}]", v)
                continue
            # a plain float or int inside the range passes at once; anything else (numpy
            # scalars, True/False -- refused: no field is a flag --, NaN, out of range) goes
            # through the full check, which says what is wrong
            t = type(value)
            if (t is float or t is int) and (low <= value if incl else low < value) \
                    and value <= high and math.isfinite(value):
                continue
            _check_number(f, name, value)
        self.validate()

    @classmethod
    @functools.cache  # per class
    def _fields_by_name(cls) -> Mapping[str, dataclasses.Field]:
        """The dataclass fields by name (read once per class)."""
        return MappingProxyType({f.name: f for f in dataclasses.fields(cls)})

    @classmethod
    @functools.cache  # per class
    def _has_vector_fields(cls) -> bool:
        """Whether a field holds a vector (``param(size=N)``)."""
        return any(c[2] for c in cls._field_checks())

    @classmethod
    @functools.cache  # per class
    def _field_checks(cls) -> tuple[tuple[Any, str, int, float, float, bool], ...]:
        """(field, name, vector size or 0, low, high, low inclusive) of every field, read
        from the fields' metadata once per class (what every construction checks)."""
        return tuple((f, f.name, f.metadata.get("size", 0), f.metadata.get("low", -math.inf),
                      f.metadata.get("high", math.inf), f.metadata.get("low_inclusive", True))
                     for f in dataclasses.fields(cls))

    def validate(self) -> None:
        """Cross-field checks; override in subclasses (raise ParameterError)."""

    # -- packing -----------------------------------------------------------------------
    @classmethod
    @functools.cache  # per class (the fields of a dataclass do not change)
    def field_names(cls) -> tuple[str, ...]:
        """Field names in packing order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    @classmethod
    @functools.cache
    def field_sizes(cls) -> tuple[int, ...]:
        """Values per field in packing order: 1 for a number, N for a vector of N."""
        return tuple(max(f.metadata.get("size", 0), 1) for f in dataclasses.fields(cls))

    @classmethod
    @functools.cache
    def n_values(cls) -> int:
        """Length of the packed array (:meth:`to_array`): the fields' sizes summed."""
        return sum(cls.field_sizes())

    @classmethod
    @functools.cache
    def value_names(cls) -> tuple[str, ...]:
        """A name per packed value: the field name, ``name[k]`` for a vector's elements."""
        return tuple(n if size == 1 and not _is_vector(cls, n) else f"{n}[{k}]"
                     for n, size in zip(cls.field_names(), cls.field_sizes())
                     for k in range(size))

    @classmethod
    @functools.cache
    def record_dtype(cls) -> np.dtype:
        """The structured dtype compiled code sees: one float64 field per parameter, in order.

        A class without fields gets one padding field ``_unused`` (numba needs a non-empty
        record).

        Returns
        -------
        numpy.dtype
        """
        if not cls.field_names():
            return np.dtype([("_unused", np.float64)])
        return np.dtype([(n, np.float64, (size,)) if _is_vector(cls, n) else (n, np.float64)
                         for n, size in zip(cls.field_names(), cls.field_sizes())])

    @classmethod
    @functools.cache
    def _record_view_dtype(cls) -> np.dtype:
        """:meth:`record_dtype` as records (items read as ``rec.kp``), for :func:`as_records`."""
        return np.dtype((np.record, cls.record_dtype()))

    def to_record(self) -> np.record:
        """This parameter set as one record (``rec.kp``), for compiled code.

        Returns
        -------
        numpy.record
            A record of :meth:`record_dtype` (fields readable as attributes).
        """
        return as_records(self.to_array()[None, :], type(self))[0]

    def to_array(self) -> np.ndarray:
        """Pack the fields, in declaration order, into a float64 array (SI units; a vector field
        gives its elements in order)."""
        return self._packed().copy()

    def _packed(self) -> np.ndarray:
        """:meth:`to_array`, read-only, packed once per instance (the fields are frozen)."""
        packed = self.__dict__.get("_packed_values")
        if packed is None:
            packed = self._pack()
            packed.setflags(write=False)
            object.__setattr__(self, "_packed_values", packed)
        return packed

    def _pack(self) -> np.ndarray:
        checks = self._field_checks()
        if not self._has_vector_fields():  # one value per field
            return np.array([getattr(self, c[1]) for c in checks], dtype=float)
        out: list[float] = []
        for _, n, size, _, _, _ in checks:
            value = getattr(self, n)
            if size:
                out.extend(float(v) for v in value)
            else:
                out.append(float(value))
        return np.array(out, dtype=float)

    @classmethod
    def from_array(cls, values: Sequence[float]) -> Self:
        """Inverse of :meth:`to_array`.

        Parameters
        ----------
        values : sequence of float
            One value per field, in field order (SI units, radians).

        Returns
        -------
        Params
        """
        names = cls.field_names()
        if len(values) != cls.n_values():
            raise ParameterError(
                f"{cls.__name__} needs {cls.n_values()} values ({', '.join(cls.value_names())}), "
                f"got {len(values)}"
            )
        kwargs: dict[str, Any] = {}
        i = 0
        for n, size in zip(names, cls.field_sizes()):
            if _is_vector(cls, n):
                kwargs[n] = tuple(float(v) for v in values[i:i + size])
            else:
                kwargs[n] = float(values[i])
            i += size
        return cls(**kwargs)

    @classmethod
    def info(cls) -> list[ParamInfo]:
        """Field descriptions (name, unit, symbol, doc, default, range)."""
        out = []
        for f in dataclasses.fields(cls):
            default = f.default if f.default is not dataclasses.MISSING else None
            out.append(
                ParamInfo(
                    f.name,
                    f.metadata.get("unit", ""),
                    f.metadata.get("symbol", ""),
                    f.metadata.get("doc", ""),
                    default,
                    f.metadata.get("low", -math.inf),
                    f.metadata.get("high", math.inf),
                    f.metadata.get("size", 0),
                )
            )
        return out

    def replace_many(self, columns: Mapping[str, Any]) -> "list[Self] | None":
        """Copies of this set with some scalar fields changed, one per row of ``columns``.

        The batched form of ``type(self).from_mapping(row, base=self)`` for many rows (a
        Monte-Carlo study's samples): the ranges of the changed fields are checked for all rows
        at once, the other fields are this set's (already valid), each copy runs the class's
        cross-field :meth:`validate` and gets its packed row (:meth:`to_array`) from one
        array. The copies equal what ``from_mapping`` builds.

        Parameters
        ----------
        columns : mapping of str to array_like, shape (n,)
            Values of scalar fields (SI units, radians), one array per field.

        Returns
        -------
        list of Params, or None
            None when a row would not pass the fields' checks, or a key is not a scalar field
            of this class (a ``_deg`` key, a vector field, an unknown name): then
            ``from_mapping`` per row builds the copies or says what is wrong, as before.

        Raises
        ------
        ParameterError
            From a copy's :meth:`validate` (as ``from_mapping`` would raise it).
        """
        cls = type(self)
        fields = cls._fields_by_name()
        checks = {c[1]: c for c in cls._field_checks()}
        names = list(fields)
        packed = self._packed()
        if cls._has_vector_fields() or not columns or cls.__post_init__ is not \
                Params.__post_init__:  # (a class that derives fields on construction)
            return None
        values = {}
        n = None
        for key, column in columns.items():
            if key not in fields:
                return None
            arr = np.asarray(column)
            if arr.ndim != 1 or arr.dtype.kind != "f" or (n is not None and arr.size != n):
                return None
            n = arr.size
            _, _, _, low, high, incl = checks[key]
            with np.errstate(invalid="ignore"):
                ok = np.isfinite(arr) & ((arr >= low) if incl else (arr > low)) & (arr <= high)
            if not ok.all():
                return None
            values[key] = arr.astype(float)
        assert n is not None
        rows = np.repeat(packed[None, :], n, axis=0)
        for key, arr in values.items():
            rows[:, names.index(key)] = arr
        rows.setflags(write=False)
        base = {name: self.__dict__[name] for name in names}  # (the fields only, no cache)
        lists = {key: arr.tolist() for key, arr in values.items()}  # (Python floats)
        out = []
        for i in range(n):
            p = object.__new__(cls)
            p.__dict__.update(base)
            for key, column in lists.items():
                p.__dict__[key] = column[i]
            p.__dict__["_packed_values"] = rows[i]
            p.validate()
            out.append(p)
        return out

    def replace(self, **changes: Any) -> Self:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        """Fields as a plain dict."""
        return {n: getattr(self, n) for n in self.field_names()}

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any], *, base: "Params | None" = None) -> Self:
        """Build from a mapping; keys ``<name>_deg`` set a radian field ``<name>`` from degrees.

        Unknown keys raise :class:`ParameterError` listing the valid ones.

        Parameters
        ----------
        values : mapping of str to float
            Field values by name (SI units, radians), or ``<name>_deg`` in degrees for angle fields.
        base : Params, optional
            Parameter set providing the fields not in ``values`` (default: the class defaults).

        Returns
        -------
        Params
        """
        fields = cls._fields_by_name()
        kwargs: dict[str, Any] = base.as_dict() if base is not None else {}
        in_degrees: dict[str, str] = {}  # field -> the `_deg` key it was given by
        both = [k for k in values if k.endswith("_deg") and k[:-4] in values]
        if both:
            raise ParameterError(f"give `{both[0][:-4]}` [rad] or `{both[0]}` [deg], not both")
        for key, value in values.items():
            name, factor = key, 1.0
            if key not in fields and key.endswith("_deg") and key[:-4] in fields:
                name = key[:-4]
                if "rad" not in fields[name].metadata.get("unit", ""):
                    raise ParameterError(
                        f"`{key}`: field `{name}` is not an angle "
                        f"(unit [{fields[name].metadata.get('unit', '')}])"
                    )
                factor = math.pi / 180.0
            if name not in fields:
                raise ParameterError(
                    f"unknown parameter `{key}` for {cls.__name__}; "
                    f"valid: {', '.join(fields)} (angles also as <name>_deg)"
                )
            size = fields[name].metadata.get("size", 0)
            if size:
                kwargs[name] = tuple(v * factor for v in _vector(fields[name], value, size,
                                                                  key=key))
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ParameterError(f"must be a number{_unit(fields[name])}, got {value!r}",
                                     field=key, unit=_unit_of(fields[name]), value=value)
            kwargs[name] = float(value) * factor
            if factor != 1.0:
                in_degrees[name] = key
        try:
            return cls(**kwargs)
        except ParameterError as exc:
            key = in_degrees.get((exc.field or "").partition("[")[0])
            if key is None or exc.value is None:
                raise
            raise _in_degrees(exc, key, fields[key[:-4]]) from None


def _in_degrees(exc: ParameterError, key: str, f: dataclasses.Field) -> ParameterError:
    """A range error of an angle given in degrees (``max_angle_deg = 200``), said in degrees
    about the key the user wrote, not in radians about the field."""
    deg = 180.0 / math.pi
    low, high = f.metadata.get("low", -math.inf), f.metadata.get("high", math.inf)
    lo = "[" if f.metadata.get("low_inclusive", True) else "("
    value = float(exc.value) * deg
    if math.isfinite(low) or math.isfinite(high):
        reason = (f"must be in {lo}{low * deg:.6g}, {high * deg:.6g}] [deg], got "
                  f"{value:.6g}")
    else:
        reason = f"{exc.reason} (as written: {value:.6g} deg)"
    return ParameterError(reason, field=key, unit="deg", value=value)


def _is_vector(cls: type, name: str) -> bool:
    return bool(cls.__dataclass_fields__[name].metadata.get("size", 0))


def _vector(f: dataclasses.Field, value: Any, size: int, *, key: str | None = None
            ) -> tuple[float, ...]:
    """A vector field's value as a tuple of ``size`` floats (from a list, tuple or array)."""
    key = key or f.name
    if isinstance(value, (str, bytes, Mapping)) or not hasattr(value, "__len__"):
        raise ParameterError(f"must be a sequence of {size} numbers{_unit(f)}, got {value!r}",
                             field=key, unit=_unit_of(f), value=value)
    items = list(np.asarray(value, dtype=object).ravel()) if isinstance(value, np.ndarray) \
        else list(value)
    if len(items) != size:
        raise ParameterError(f"must have {size} values{_unit(f)}, got {len(items)}",
                             field=key, unit=_unit_of(f), value=value)
    for k, v in enumerate(items):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)):
            raise ParameterError(f"must be a number{_unit(f)}, got {v!r}", field=f"{key}[{k}]",
                                 unit=_unit_of(f), value=v)
    return tuple(float(v) for v in items)


def _check_number(f: dataclasses.Field, name: str, value: Any) -> None:
    """A scalar parameter value: a finite number in the field's range."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ParameterError(f"must be a number{_unit(f)}, got {value!r}", field=name,
                             unit=_unit_of(f), value=value)
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(f"must be finite{_unit(f)}, got {v!r}", field=name,
                             unit=_unit_of(f), value=v)
    low = f.metadata.get("low", -math.inf)
    high = f.metadata.get("high", math.inf)
    incl = f.metadata.get("low_inclusive", True)
    if (v < low if incl else v <= low) or v > high:
        lo = "[" if incl else "("
        raise ParameterError(f"must be in {lo}{low:g}, {high:g}]{_unit(f)}, got {v!r}",
                             field=name, unit=_unit_of(f), value=v)


def _unit_of(f: dataclasses.Field) -> str | None:
    return f.metadata.get("unit", "") or None


def _unit(f: dataclasses.Field) -> str:
    unit = f.metadata.get("unit", "")
    return f" [{unit}]" if unit else ""


def stack_params(params: "Params | Sequence[Params]", cls: type[Params] | None = None) -> np.ndarray:
    """Pack one parameter set or a sequence of them into a ``(n_runs, n_params)`` array.

    Parameters
    ----------
    params : Params or sequence of Params
        One parameter set or several of the same type.
    cls : type, optional
        Required parameter class (default: any).

    Returns
    -------
    numpy.ndarray, shape (n_runs, n_params)
    """
    if isinstance(params, Params):
        if cls is None or isinstance(params, cls):  # (one set: its row, a copy of its own)
            return params._packed()[None, :].copy()
        params = [params]
    params = list(params)
    if not params:
        raise ParameterError("at least one parameter set is needed, got an empty sequence")
    kinds = {type(p) for p in params}
    if len(kinds) != 1:
        raise ParameterError(f"all parameter sets in a batch must have one type, got {kinds}")
    if cls is not None and not isinstance(params[0], cls):
        raise ParameterError(
            f"expected {cls.__name__} parameters, got {type(params[0]).__name__}"
        )
    return np.stack([p._packed() for p in params])


def as_records(rows: Any, cls: type[Params]) -> np.ndarray:
    """View parameter rows ``(runs, n_params)`` (floats in field order) as records of ``cls``.

    No copy when ``rows`` is a C-contiguous float64 array; the records share its memory.

    Parameters
    ----------
    rows : array_like, shape (runs, n_params) or (n_params,)
        Packed parameter values (:meth:`Params.to_array` rows; SI units, radians).
    cls : type[Params]
        Parameter class that names the fields.

    Returns
    -------
    numpy.ndarray, shape (runs,)
        Structured array of :meth:`Params.record_dtype`; ``out[i].kp`` is run i's ``kp``.
    """
    arr = np.asarray(rows, dtype=np.float64)
    if arr.ndim == 1:
        arr = arr[None, :]
    n = cls.n_values()
    if arr.ndim != 2 or arr.shape[1] != n:
        raise ParameterError(
            f"{cls.__name__} rows must have shape (runs, {n}), got {arr.shape}"
        )
    if n == 0:
        arr = np.zeros((arr.shape[0], 1))
    arr = np.ascontiguousarray(arr)
    if not arr.flags.writeable:  # one compiled specialisation per kernel, not two
        arr = arr.copy()
    # np.record items read as ``rec.kp`` in Python too (NUMBA_DISABLE_JIT, py_func); the
    # records made on ``arr``'s buffer directly: what ``arr.view(dtype).reshape(runs)`` gives
    # (the same memory, dtype, flags and numba type) without its view checks, a third of the
    # cost (three parameter groups a run, issue 46's fixed cost of one call)
    return np.ndarray(shape=(arr.shape[0],), dtype=cls._record_view_dtype(), buffer=arr)


def signal_indices(labels: Sequence[str]) -> Any:
    """Named integer constants for a component's signal vector, e.g. ``S.yaw_rate``.

    Compiled code indexes its state, input and output vectors through these (``x[S.heading]``)
    instead of bare numbers; numba freezes the named tuple into the code as constants.

    Parameters
    ----------
    labels : sequence of str
        Signal names in vector order (valid Python identifiers).

    Returns
    -------
    collections.namedtuple
        ``S.<label> == position`` for every label.
    """
    from collections import namedtuple

    labels = tuple(labels)
    bad = [lab for lab in labels if not lab.isidentifier()]
    if bad:
        raise ValueError(f"signal names must be identifiers, got {bad}")
    if len(set(labels)) != len(labels):
        raise ValueError(f"duplicate signal names in {labels}")
    return namedtuple("Signals", labels)(*range(len(labels)))
