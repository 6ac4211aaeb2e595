"""Start a command that a Ctrl-C (SIGINT) reaches as it reaches a command typed at a terminal.

A shell without job control (a script, ``make test &``, ``nohup make test &``, a CI step that
backgrounds the suite) starts its background jobs with SIGINT ignored (POSIX: asynchronous
lists of a non-interactive shell), and every process started from them inherits the ignore;
Python keeps an inherited ``SIG_IGN`` (it installs its ``KeyboardInterrupt`` handler only over
``SIG_DFL``). A command a test started there and sent SIGINT to ignored it: the interrupted
sweep on workers ran its 200 chunks to the end and exited 0 instead of 130
(``tests/test_cli_reliability_messages.py``, a fresh-clone run; reproduced every time with the
suite started under ``trap '' INT``).

:func:`popen_interruptible` starts the command through a one-line Python shim that sets SIGINT
back to ``SIG_DFL`` and ``exec``\\ s the command: the same process (its pid, so also its process
group with ``start_new_session=True``), with SIGINT as at a terminal. (Not ``preexec_fn``, which
runs Python code between ``fork`` and ``exec`` and is documented as unsafe in a process with
threads, as an xdist worker is.)
"""

from __future__ import annotations

import subprocess
import sys
from typing import Any

__all__ = ["popen_interruptible", "SHIM"]

#: Python code run as ``python -c SHIM CMD...``: SIGINT at its default, then ``exec`` CMD.
SHIM = ("import os, signal, sys; signal.signal(signal.SIGINT, signal.SIG_DFL); "
        "os.execvp(sys.argv[1], sys.argv[1:])")


def popen_interruptible(cmd: list[str], **popen: Any) -> subprocess.Popen:
    """``subprocess.Popen(cmd, **popen)`` with SIGINT at its default disposition in ``cmd``
    whatever this process has (see the module's docstring).

    Parameters
    ----------
    cmd : list of str
        The command; ``cmd[0]`` is looked up on ``PATH`` if it is not a path.
    **popen
        Passed to :class:`subprocess.Popen` (``stdout``, ``start_new_session``, ``env``, ...).

    Returns
    -------
    subprocess.Popen
        ``pid`` is the command's own (the shim's process became it).
    """
    return subprocess.Popen([sys.executable, "-c", SHIM, *cmd], **popen)
