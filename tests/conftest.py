"""Builds in the test suite use the fast stair-step model: the session starts with
ANTENNA_CAD_MEEP_PYTHON pointing at an interpreter without Meep (set before any fixture builds
anything), and only the ``meep`` fixture below restores the real search for its test. The full-wave
stage is tested in tests/test_fullwave.py, once, not in every build."""

import os
import sys

import pytest

from antenna_cad.fullwave import solver

ORIGINAL = os.environ.get("ANTENNA_CAD_MEEP_PYTHON")


def pytest_configure(config):
    os.environ["ANTENNA_CAD_MEEP_PYTHON"] = sys.executable          # an interpreter without meep


@pytest.fixture
def meep(monkeypatch):
    """The interpreter with Meep for this test; without one, CI (CI=true) fails and elsewhere the
    test is skipped with "Meep not found, install python3-meep"."""
    if ORIGINAL is None:
        monkeypatch.delenv("ANTENNA_CAD_MEEP_PYTHON")
    else:
        monkeypatch.setenv("ANTENNA_CAD_MEEP_PYTHON", ORIGINAL)
    python = solver.meep_python()
    if python is None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{solver.MISSING} (CI must run the full-wave tests)")
        pytest.skip(solver.MISSING)
    return python
