"""Shared fixtures: a non-interactive matplotlib backend and the Mariner parameters."""

from __future__ import annotations

import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture
def mariner2():
    from seahelm.vessels.catalog import get

    return get("mariner-nomoto2").params


@pytest.fixture
def mariner1():
    from seahelm.vessels.catalog import get

    return get("mariner-nomoto1").params
