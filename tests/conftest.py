"""Builds in the test suite use the fast stair-step model unless a test asks for Meep (the ``meep``
fixture of tests/test_fullwave.py): the full-wave stage is tested there, once, not in every build."""

import sys

import pytest


@pytest.fixture(autouse=True)
def _full_wave_only_where_asked(request, monkeypatch):
    if "meep" not in request.fixturenames:
        monkeypatch.setenv("ANTENNA_CAD_MEEP_PYTHON", sys.executable)     # an interpreter without meep
