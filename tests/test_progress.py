"""Progress: the pipeline's reports (stage starts, details from inside a stage, the lock wait) and
their rendering off a terminal (stage lines, heartbeats with the detail, --quiet, --verbose), sweeps'
rows / failures / time per variant / time left, and tables that are not wrapped in a log."""

import io
import time
from pathlib import Path

import pytest
from rich.console import Console
from typer.testing import CliRunner

from antenna_cad import pipeline, progress
from antenna_cad.cli import app
from antenna_cad.console import NORMAL, QUIET, VERBOSE, BuildProgress, SweepProgress
from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "recipes" / "ptfe-lens-120mm.yaml"
PERIOD = 0.05                       # heartbeat period for the tests (the CLI's is 10 s)


def _lines(cls, mode, calls, period=PERIOD):
    """Render ``calls`` (tuples of arguments, or a string: wait for a line containing it)."""
    buf = io.StringIO()
    with cls("x", mode, Console(file=buf, width=300), terminal=False, period=period) as shown:
        for call in calls:
            if isinstance(call, str):
                for _ in range(200):
                    if call in buf.getvalue():
                        break
                    time.sleep(PERIOD)
            else:
                shown(*call)
    return [line.split("] ", 1)[1] for line in buf.getvalue().splitlines()]


def test_stage_lines_heartbeat_with_detail_and_the_lock_wait():
    lines = _lines(BuildProgress, NORMAL, [
        ("synthesize", 0.0), ("model", 0.2), ("waiting", 0.2, "for another build writing into out"),
        ("model", 0.2), ("verify", 0.3), ("verify", 0.35, "full-wave: run 2 of 4, 35 s of 120 s budget"),
        "so far — full-wave: run 2 of 4", ("done", 1.0)])
    assert lines[:6] == ["synthesize: started", lines[1], "model: started",
                         "waiting: started — for another build writing into out", lines[4], lines[5]]
    assert lines[1].startswith("synthesize: done in ") and lines[4].startswith("waiting: done in ")
    assert lines[5].startswith("model: done in ") and lines[6] == "verify: started"
    beats = [ln for ln in lines if "so far" in ln]
    assert beats and beats[-1].startswith("verify: ") and beats[-1].endswith(
        "so far — full-wave: run 2 of 4, 35 s of 120 s budget")
    assert lines[-1].startswith("verify: done in ")


def test_quiet_shows_nothing_and_verbose_every_detail():
    calls = [("verify", 0.3), ("verify", 0.31, "full-wave: run 1 of 4"), ("verify", 0.32, "full-wave: run 2 of 4"),
             ("done", 1.0)]
    assert _lines(BuildProgress, QUIET, calls, period=100) == []
    verbose = _lines(BuildProgress, VERBOSE, calls, period=100)
    assert verbose[1:3] == ["verify: full-wave: run 1 of 4", "verify: full-wave: run 2 of 4"]
    assert "verify: full-wave: run 1 of 4" not in _lines(BuildProgress, NORMAL, calls, period=100)


def test_sweep_progress_counts_failures_time_per_variant_and_time_left():
    lines = _lines(SweepProgress, NORMAL, [(0, 4, 0), (1, 4, 1), "(1 failed)", (4, 4, 1)], period=100)
    assert lines[0] == "x: 0 of 4 variants"
    assert lines[1].startswith("x: 1 of 4 variants (1 failed), ") and "per variant, about" in lines[1]
    assert lines[1].endswith(" left")
    assert lines[-1].startswith("x: 4 of 4 variants (1 failed), ") and lines[-1].endswith("per variant")


def test_old_two_argument_callers_still_work():
    seen = []
    with progress.reporting(lambda stage, fraction, detail="": seen.append((stage, fraction, detail))):
        progress.report("full-wave", 0.5)
        progress.report("full-wave", 0.75, "run 3 of 4")
    progress.report("nobody listens", 1.0)
    assert seen == [("full-wave", 0.5, ""), ("full-wave", 0.75, "run 3 of 4")]


@pytest.mark.slow
def test_build_reports_stage_starts_and_details_from_inside_verify(tmp_path, monkeypatch):
    """A kind's verification reporting through antenna_cad.progress reaches the build's callback as
    stage ``verify`` with the detail; stages are announced as they start, then ``done``."""
    import antenna_cad.kinds.collimator as collimator
    verify = collimator.verify

    def reporting_verify(*args):
        progress.report("full-wave", 0.5, "run 2 of 4, 35 s of 120 s budget")
        return verify(*args)
    monkeypatch.setattr(collimator, "verify", reporting_verify)
    monkeypatch.setenv("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/false")
    seen = []
    result = pipeline.build(load_spec(SPEC), tmp_path, lambda *args: seen.append(args))
    stages = list(dict.fromkeys(call[0] for call in seen))
    assert stages == [*pipeline.STAGES, "done"]
    n = len(pipeline.STAGES)
    assert ("verify", pytest.approx(3.5 / n), "full-wave: run 2 of 4, 35 s of 120 s budget") in seen
    assert pipeline.PLACED == [result.out_dir]


def test_tables_are_not_wrapped_off_a_terminal(tmp_path):
    """Off a terminal (CliRunner's pipe) a checks row is one line however long its message."""
    result = CliRunner().invoke(app, ["validate", str(ROOT / "recipes" / "xps-collimator-0.5m.yaml")])
    assert result.exit_code == 0, result.output
    row = next(line for line in result.output.splitlines() if "rim_incidence_vs_tir" in line)
    assert len(row) > 120 and "(no total reflection)" in row
