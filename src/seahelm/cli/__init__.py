"""The ``seahelm`` command (typer + rich).

``seahelm demo``, ``seahelm run``, ``seahelm models``, ``seahelm plot`` and the subcommand
groups of the paper modules (``waves``, ``identify``, ``averaging``, ``compensate``).
Exit codes: 0 success, 2 bad input (one-line reason on stderr), 1 other failure.
"""

from __future__ import annotations

from .main import app, main

__all__ = ["app", "main"]
