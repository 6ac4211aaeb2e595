"""Exceptions and warnings raised by seahelm.

Every seahelm exception subclasses :class:`SeahelmError` and, where it makes sense, the
matching built-in (``ValueError``, ``ImportError``, ``ArithmeticError``) so that callers can
catch either.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

__all__ = [
    "SeahelmError",
    "ParameterError",
    "ValidityRangeWarning",
    "SimulationDiverged",
    "MissingDependencyError",
    "strict_validity",
    "warn_validity",
    "deprecated_names",
    "deprecated_method",
    "deprecated_modules",
]


class SeahelmError(Exception):
    """Base class of every seahelm exception."""


class ParameterError(SeahelmError, ValueError):
    """A parameter is outside its admissible domain (names the parameter, unit and value).

    The error carries what it is about as fields, so that a scenario loader or the CLI can say
    it in its own words (a TOML key, a ``--option``) without reading the message text:

    Attributes
    ----------
    field : str or None
        Dotted path of the parameter (``"dt"``, ``"params.Y_v"``, ``"steering_gear.params.
        max_angle"``); :meth:`within` prefixes it as the error travels outwards.
    reason : str
        What is wrong with it, without the name (``"must be > 0 [s], got -1.0"``).
    unit : str or None
        The parameter's unit, where it has one.
    value : object
        The bad value, where there is one.
    run : int or None
        Index of the run in a batch, where the error concerns one run.

    With a ``field`` the message reads ``"`field` reason"`` (``"`field`: reason"`` for a reason
    that starts with a colon); without, it is ``reason``. The run index is an attribute only
    (a batch's caller names the run in its own terms, e.g. a grid point).
    """

    def __init__(self, reason: str = "", *, field: str | None = None, unit: str | None = None,
                 value: Any = None, run: int | None = None) -> None:
        self.reason = str(reason)
        self.field = field
        self.unit = unit
        self.value = value
        self.run = run
        super().__init__(self._render())

    def _render(self) -> str:
        if not self.field:
            text = self.reason
        else:  # "`dt` must be > 0 ...", or "`bounds`: ..." for a reason that starts with ":"
            sep = "" if self.reason.startswith((":", ",", " ")) else " "
            text = f"`{self.field}`{sep}{self.reason}"
        return text

    def within(self, prefix: str, *, run: int | None = None) -> "ParameterError":
        """The same error one level out: ``field`` prefixed with ``prefix`` (and a run index).

        Parameters
        ----------
        prefix : str
            Path of the object the field belongs to (``"params"``, ``"vessel"``).
        run : int, optional
            Run index to attach (default: keep this error's).

        Returns
        -------
        ParameterError
            A new error of the same type (the traceback is the caller's to chain).
        """
        field = f"{prefix}.{self.field}" if self.field else prefix
        new = type(self).__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.field = field
        if run is not None:
            new.run = run
        Exception.__init__(new, new._render())
        return new

    def __reduce__(self) -> Any:
        # pickled with its fields (dask sends errors between processes)
        return (_restore_error, (type(self), self.args, self.__dict__.copy()))


def _restore_error(cls: type, args: tuple, state: dict) -> BaseException:
    err = Exception.__new__(cls)
    Exception.__init__(err, *args)
    err.__dict__.update(state)
    return err


class ValidityRangeWarning(UserWarning):
    """An empirical formula is used outside the range of data it was fitted to."""


class SimulationDiverged(SeahelmError, ArithmeticError):
    """A simulated state became NaN/inf or left its declared bounds.

    Attributes
    ----------
    time : float
        Simulation time [s] of the first step at which the state was invalid.
    state : numpy.ndarray
        The state at that time (may contain NaN/inf).
    run : int
        Index of the run in the batch.
    """

    def __init__(self, message: str, *, time: float, state: Any, run: int = 0) -> None:
        super().__init__(message)
        self.time = float(time)
        self.state = np.asarray(state)
        self.run = int(run)


class MissingDependencyError(SeahelmError, ImportError):
    """An optional dependency is needed for this feature; the message names the extra."""


_STRICT = {"on": False}


class strict_validity:
    """Context manager (and function) turning :class:`ValidityRangeWarning` into errors.

    Examples
    --------
    >>> with strict_validity():
    ...     pass  # empirical formulas outside their range now raise ParameterError
    """

    def __init__(self, on: bool = True) -> None:
        self._on = on
        self._old = _STRICT["on"]

    def __enter__(self) -> "strict_validity":
        self._old = _STRICT["on"]
        _STRICT["on"] = self._on
        return self

    def __exit__(self, *exc: object) -> None:
        _STRICT["on"] = self._old


def _first_frame_outside_seahelm() -> int:
    """The :func:`warnings.warn` ``stacklevel`` of the first caller outside the seahelm package
    (the user's line; 2 if every frame is seahelm's), counted from the caller of this function."""
    import os
    import sys

    package = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame, level = sys._getframe(2), 2  # (the caller of warn_validity is level 2 of warn)
    while frame is not None:
        if not os.path.abspath(frame.f_code.co_filename).startswith(package):
            return level
        frame, level = frame.f_back, level + 1
    return 2


def warn_validity(message: str, *, strict: bool | None = None,
                  stacklevel: int | None = None) -> None:
    """Warn (or raise in strict mode) that an empirical formula is outside its validity range.

    Parameters
    ----------
    message : str
        Warning (or error) message.
    strict : bool, optional
        Raise :class:`ParameterError` instead of warning (default: the global strict mode).
    stacklevel : int, optional
        Passed to :func:`warnings.warn`; by default the warning points at the first line
        outside seahelm on the call stack: the user's call (``simulate(...)``, a manoeuvre,
        ``Simulator.step``), however deep in the library the check runs.
    """
    if strict is None:
        strict = _STRICT["on"]
    if strict:
        raise ParameterError(message)
    if stacklevel is None:
        stacklevel = _first_frame_outside_seahelm()
    warnings.warn(message, ValidityRangeWarning, stacklevel=stacklevel)


def deprecated_names(module: str, aliases: dict[str, tuple[str, str, str]], *,
                     stacklevel: int = 2) -> Any:
    """A module ``__getattr__`` (PEP 562) for names kept for old code: each access warns
    (:class:`DeprecationWarning`, naming the replacement) and returns the object it now is.

    Parameters
    ----------
    module : str
        The module's name (``__name__``), for the messages.
    aliases : dict of str to (str, str, str)
        Old name -> (module of the replacement, its name there, how users reach it, e.g.
        ``"seahelm.Problem"``).
    stacklevel : int, optional
        Of the warning (2: the code that reads the name from the module).

    Returns
    -------
    callable
        ``__getattr__(name)``: the replacement for an old name; ``AttributeError`` otherwise.
    """
    def __getattr__(name: str) -> Any:
        if name not in aliases:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        import importlib

        home, new, public = aliases[name]
        warnings.warn(f"{module}.{name} is deprecated: use {public} (the same object); the old "
                      "name will be removed", DeprecationWarning, stacklevel=stacklevel)
        return getattr(importlib.import_module(home), new)

    return __getattr__


def deprecated_method(new: str, why: str = "") -> Any:
    """A method kept for old code under its old name: each call warns
    (:class:`DeprecationWarning`, naming ``new``) and returns what ``self.new()`` returns.

    Parameters
    ----------
    new : str
        The method's name now (``"to_xarray"``).
    why : str, optional
        Said after the replacement (``"one name for it across seahelm"``).

    Returns
    -------
    function
        To assign in the class body: ``to_dataset = deprecated_method("to_xarray")``.
    """
    def old(self: Any, *args: Any, **kwargs: Any) -> Any:
        warnings.warn(f"{type(self).__name__}.{old.__name__}() is deprecated: use .{new}() "
                      f"({'the same result' + ('; ' + why if why else '')})",
                      DeprecationWarning, stacklevel=2)
        return getattr(self, new)(*args, **kwargs)

    old.__doc__ = f"Deprecated name of :meth:`{new}` (a :class:`DeprecationWarning`)."
    return _Named(old)


class _Named:
    """A function that takes the name it is assigned to in a class body."""

    def __init__(self, func: Any) -> None:
        self.func = func

    def __set_name__(self, owner: type, name: str) -> None:
        self.func.__name__ = self.func.__qualname__ = name

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        return self.func if obj is None else self.func.__get__(obj, owner)


def deprecated_modules(package: str, moved: dict[str, str], *, stacklevel: int = 2) -> Any:
    """Old module paths of ``package`` kept for old code, with no second home: importing
    ``package.old`` (``import``, ``from package.old import x``, ``from package import old``)
    or reading the attribute warns (:class:`DeprecationWarning`, naming the new module) and
    gives the new module itself (the same object, registered in :data:`sys.modules` under the
    old name too).

    Installs one finder on :data:`sys.meta_path` for ``package`` (once; called from the
    package's ``__init__``, which Python imports before any of its submodules).

    Parameters
    ----------
    package : str
        The package that held the modules (``__name__`` of its ``__init__``).
    moved : dict of str to str
        Old submodule name -> the module's full name now.
    stacklevel : int, optional
        Of the warning (2: the code that imports or reads the old name).

    Returns
    -------
    callable
        ``__getattr__(name)`` for the package (PEP 562): the new module for an old name;
        ``AttributeError`` otherwise.
    """
    import importlib
    import importlib.abc
    import importlib.util
    import sys

    def warn(old: str) -> None:
        warnings.warn(f"{package}.{old} is deprecated: use {moved[old]} (the same module); the "
                      "old name will be removed", DeprecationWarning, stacklevel=stacklevel + 1)

    class _Finder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
        """Finds ``package.old`` and loads it as the module it now is."""

        key = ("seahelm.deprecated_modules", package)
        specs: dict[str, Any] = {}

        def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
            parent, _, leaf = fullname.rpartition(".")
            if parent != package or leaf not in moved:
                return None
            return importlib.util.spec_from_loader(fullname, self)

        def create_module(self, spec: Any) -> Any:
            leaf = spec.name.rpartition(".")[2]
            warn(leaf)
            module = importlib.import_module(moved[leaf])
            self.specs[spec.name] = module.__spec__
            return module

        def exec_module(self, module: Any) -> None:
            # the import system set the old name's spec on the module it was given: give it
            # back its own (reload and pickling read it)
            module.__spec__ = self.specs.pop(module.__spec__.name, module.__spec__)

    if not any(getattr(f, "key", None) == _Finder.key for f in sys.meta_path):
        sys.meta_path.insert(0, _Finder())

    def __getattr__(name: str) -> Any:
        if name not in moved:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        warn(name)
        return importlib.import_module(moved[name])

    return __getattr__
