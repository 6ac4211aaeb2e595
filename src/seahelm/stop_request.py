"""A stop signal that is not lost: SIGTERM and Ctrl-C recorded as well as raised.

The command line turns SIGTERM into ``SystemExit(143)`` and Ctrl-C into ``KeyboardInterrupt``
(exit 130). Python raises either from a signal handler in whatever Python frame the main
thread runs at that moment, and that frame may be Python code called from C code that clears
every error it meets: numpy, comparing a numpy integer with an ``IntEnum`` member (``status[run]
!= ApproachStatus.OK``), looks ``__array_ufunc__`` up on the member's type, which runs
``EnumType.__getattr__``, and drops whatever that raises. A SIGTERM landing there vanished:
``seahelm identify mmg ... --imo 20000`` ran on for minutes instead of ending
(tests/test_cli_stop_signals.py, about one run in three).

So the handlers :func:`install` puts in also record the signal, and :func:`check` raises it
again where the library may stop: the engine calls it after every slice of a compiled run
(:func:`seahelm.simulation.slicing.drive`), so a lost stop still ends the command within a
slice (~0.25 s) once a simulation runs. Nothing is recorded unless :func:`install` was called
(the command line does; a library user's own handlers are left alone), and :func:`check` is a
single read of a module global when nothing is pending.
"""

from __future__ import annotations

import signal
from typing import Any

__all__ = ["install", "check", "pending", "clear"]

#: The signal received and not yet raised by :func:`check` (None: none).
_pending: int | None = None


def _exception(signum: int) -> BaseException:
    """What a stop by ``signum`` raises: Ctrl-C a ``KeyboardInterrupt``, any other signal
    ``SystemExit(128 + signum)`` (a shell's exit status of a process killed by it)."""
    if signum == signal.SIGINT:
        return KeyboardInterrupt()
    return SystemExit(128 + signum)


def _handler(signum: int, frame: Any) -> None:
    global _pending
    _pending = signum
    raise _exception(signum)


def install() -> None:
    """Handle SIGTERM, and Ctrl-C (SIGINT) where Python's default handler has it, by recording
    the signal and raising its exception (:func:`check` raises it again if it was lost).

    SIGINT inherited as ignored (a background job of a shell without job control, a process
    that ignores it on purpose) stays ignored. Call from the main thread (as
    :func:`signal.signal`). Clears a signal recorded before.
    """
    clear()
    signal.signal(signal.SIGTERM, _handler)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _handler)


def pending() -> int | None:
    """The stop signal received and not raised again by :func:`check` yet.

    Returns
    -------
    int or None
        The signal number, or None.
    """
    return _pending


def clear() -> None:
    """Forget a recorded stop signal."""
    global _pending
    _pending = None


def check() -> None:
    """Raise the stop recorded by the handlers of :func:`install`, once, if there is one.

    Raises
    ------
    KeyboardInterrupt
        After a Ctrl-C (SIGINT).
    SystemExit
        After another signal (SIGTERM: code 143).
    """
    signum = _pending
    if signum is not None:
        clear()
        raise _exception(signum)
