"""Shared fixtures: headless Chromium (Debian's `chromium` + `chromium-driver`, installed by .ci/run)
for the pages the pipeline writes (report.html, a sweep's index.html).

Builds in the test suite use the fast stair-step model: the session starts with
ANTENNA_CAD_MEEP_PYTHON pointing at an interpreter without Meep (set before any fixture builds
anything), and only the ``meep`` fixture below restores the real search for its test. The full-wave
stage is tested in tests/test_fullwave.py, once, not in every build."""

import os
import shutil
import sys
from pathlib import Path

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

from antenna_cad.fullwave import budget, solver

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--disable-dev-shm-usage", "--window-size=1200,900",
                  "--enable-unsafe-swiftshader"]    # software WebGL for the report's 3-D view (trusted pages)


@pytest.fixture(scope="session")
def browser(tmp_path_factory):
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for flag in CHROMIUM_FLAGS:
        options.add_argument(flag)
    options.add_argument(f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(executable_path=shutil.which("chromedriver") or "/usr/bin/chromedriver")
    driver = webdriver.Chrome(options=options, service=service)
    yield driver
    driver.quit()


@pytest.fixture(scope="session")
def recipe_build(tmp_path_factory):
    """``recipe_build(path)`` → the BuildResult of one full build of that recipe, made once per
    session and shared by the slow end-to-end tests (a Ka-band array costs minutes to build)."""
    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    built = {}

    def get(recipe):
        if recipe not in built:
            built[recipe] = build(load_spec(recipe), tmp_path_factory.mktemp(Path(recipe).stem))
        return built[recipe]
    return get


ORIGINAL = os.environ.get("ANTENNA_CAD_MEEP_PYTHON")


def pytest_configure(config):
    os.environ["ANTENNA_CAD_MEEP_PYTHON"] = sys.executable          # an interpreter without meep


def pytest_collection_modifyitems(config, items):
    """Every test that runs Meep (it asks for the ``meep`` fixture) carries the ``fullwave`` marker."""
    for item in items:
        if "meep" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.fullwave)


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


@pytest.fixture
def fullwave_cache(tmp_path, monkeypatch):
    """A fresh full-wave cache for this test, its throughput known (the default: no probe run first)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("ANTENNA_CAD_FULLWAVE_CACHE", str(folder))
    budget.keep(folder, budget.DEFAULT_THROUGHPUT)
    return folder
