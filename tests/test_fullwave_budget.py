"""The full-wave budget as a hard cap: solver runs end (their whole process group) at ``budget_s``, on an
exception and on SIGTERM, their temporary folders removed; heartbeats while they run; the throughput
measured on the machine and kept with the cache; the seconds a build spent apart from those the cache saved.

A stand-in interpreter replaces Meep's (a shell script started exactly as the runner would be), so these
tests need no Meep and take seconds: ``hang`` starts a child and waits (the runs the budget must end),
``ok`` writes a result as the runner does."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from antenna_cad.fullwave import budget, solver
from antenna_cad.fullwave.deck import make_deck
from antenna_cad.fullwave.verify import Decision, run_named

FAKE = """#!/bin/sh
# stand-in for Meep's interpreter: $1 runner.py, $2 deck.json, $3 result.npz (cwd: the run's folder)
pwd >> "$FAKE_LOG"
if [ "$FAKE_MODE" = hang ]; then
  sleep 300 &
  echo "$$ $!" >> "$FAKE_LOG"
  wait
fi
exec {python} -c 'import sys, numpy as np; np.savez(sys.argv[1], er=np.ones(8, complex), ep=np.zeros(8, complex), \\
r_mm=np.arange(8.0), seconds=np.array(0.5), meep_version=np.array("fake"))' "$3"
"""


@pytest.fixture
def fake(tmp_path, monkeypatch, fullwave_cache):
    """(interpreter path, log path): the stand-in and the file where it notes its folder and pids."""
    python = tmp_path / "fake-python"
    python.write_text(FAKE.format(python=sys.executable))
    python.chmod(0o755)
    log = tmp_path / "log"
    monkeypatch.setenv("FAKE_LOG", str(log))
    monkeypatch.setenv("FAKE_MODE", "ok")
    return str(python), log


def _deck(resolution: float = 8.0) -> dict:
    return make_deck([], frequency_ghz=10.0, resolution=resolution, feed_z_mm=-3000.0, feed_pattern="dipole",
                     feed_q=1.0, radius_mm=90.0, plane_offset_lambda=2.0, field_map=False)


def _alive(pid: int) -> bool:
    """Still running a moment after its group was killed (the kill is delivered asynchronously)."""
    for _ in range(100):
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            return False
        if state == "Z":
            return False
        time.sleep(0.05)
    return True


def _started(log: Path) -> tuple[list[int], list[Path]]:
    lines = log.read_text().split("\n") if log.exists() else []
    pids = [int(p) for line in lines if line and line[0].isdigit() for p in line.split()]
    return pids, [Path(line) for line in lines if line.startswith("/")]


def _wait_for_pids(log: Path, count: int) -> list[int]:
    for _ in range(200):
        pids, _ = _started(log)
        if len(pids) >= count:
            return pids
        time.sleep(0.05)
    raise AssertionError(f"the stand-in runs did not start: {log.read_text() if log.exists() else ''}")


def test_the_budget_ends_every_run_and_its_process_group(fake, monkeypatch):
    python, log = fake
    monkeypatch.setenv("FAKE_MODE", "hang")
    beats = []
    within = budget.Budget(1.5, lambda used, detail: beats.append((used, detail)))
    monkeypatch.setattr(budget, "HEARTBEAT_S", 0.2)
    out = solver.run_decks([_deck(8.0), _deck(9.0), _deck(10.0)], python, 2, within)
    assert out == [None, None, None]                        # cut: nothing finished, nothing cached
    pids, folders = _started(log)
    assert len(pids) == 4                                   # two runs started (jobs 2), each with its child
    assert not any(_alive(p) for p in pids)
    assert folders and not any(f.exists() for f in folders)
    assert not list(solver.cache_dir().glob("*.npz"))
    assert beats[0][1] == "full-wave: run 1 of 3, 0 s of 1.5 s budget"
    assert "run 2 of 3" in beats[1][1] and len(beats) >= 4 and all(0 <= u <= 1 for u, _ in beats)


def test_an_exception_ends_the_runs(fake, monkeypatch):
    python, log = fake
    monkeypatch.setenv("FAKE_MODE", "hang")

    def interrupt(used, detail):
        if _started(log)[0]:
            raise KeyboardInterrupt
    monkeypatch.setattr(budget, "HEARTBEAT_S", 0.0)
    with pytest.raises(KeyboardInterrupt):
        solver.run_decks([_deck()], python, 1, budget.Budget(60.0, interrupt))
    pids, folders = _started(log)
    assert pids and not any(_alive(p) for p in pids) and not any(f.exists() for f in folders)


def test_sigterm_ends_the_build_and_its_runs(fake, tmp_path):
    python, log = fake
    script = textwrap.dedent(f"""
        from antenna_cad.fullwave import solver
        from antenna_cad.fullwave.deck import make_deck
        deck = make_deck([], frequency_ghz=10.0, resolution=8.0, feed_z_mm=-3000.0, feed_pattern="dipole",
                         feed_q=1.0, radius_mm=90.0, plane_offset_lambda=2.0, field_map=False)
        solver.run_decks([deck], {python!r}, 1)
    """)
    env = os.environ | {"FAKE_MODE": "hang", "PYTHONPATH": str(Path(__file__).resolve().parents[1])}
    build = subprocess.Popen([sys.executable, "-c", script], env=env)
    pids = _wait_for_pids(log, 2)
    build.send_signal(signal.SIGTERM)
    assert build.wait(timeout=60) == 128 + signal.SIGTERM
    _, folders = _started(log)
    assert not any(_alive(p) for p in pids) and not any(f.exists() for f in folders)


def test_the_runner_dies_with_a_killed_build(tmp_path):
    """SIGKILL leaves the parent no chance to clean up: the kernel ends the run (PR_SET_PDEATHSIG)."""
    runner = Path(solver.RUNNER)
    script = textwrap.dedent(f"""
        import subprocess, sys, time
        child = subprocess.Popen([sys.executable, "-c", "import runpy, sys, time; "
                                  "sys.argv = ['runner']; m = runpy.run_path({str(runner)!r}); "
                                  "m['die_with_parent'](); print('ready', flush=True); time.sleep(300)"],
                                 stdout=subprocess.PIPE, text=True)
        assert child.stdout.readline() == "ready\\n"
        print(child.pid, flush=True)
        time.sleep(300)
    """)
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    pid = int(parent.stdout.readline())
    assert Path(f"/proc/{pid}").exists()
    parent.kill()
    parent.wait()
    assert not _alive(pid)


def test_throughput_is_measured_once_then_kept_and_refined(fake):
    python, _ = fake
    folder = solver.cache_dir()
    (folder / budget.THROUGHPUT_FILE).unlink()
    assert budget.measured(folder) is None
    solver.calibrate(python, budget.Budget(60.0))            # the probe run
    first = budget.measured(folder)
    assert first is not None and not list(folder.glob("*.npz"))     # the probe is not cached
    solver.calibrate(python, budget.Budget(60.0))            # known: no second probe
    assert budget.measured(folder) == first
    rate, setup = first
    budget.record(folder, 4.0 * rate * 10.0, 10.0, setup * 4 + 10.0)   # 4× the rate, 4× the set-up: half-way (log)
    assert budget.measured(folder) == pytest.approx((2.0 * rate, 2.0 * setup))
    est = solver.estimate_s([_deck()], 1)
    assert est == pytest.approx(2.0 * setup + solver.runner.cell_updates(_deck()) / (2.0 * rate))


def test_a_rebuild_that_ran_nothing_spends_nothing(fake):
    """``fullwave_seconds`` is this build's; the cached runs' solver time is reported beside it."""
    python, _ = fake
    decision = Decision(python, "ran", 0.0, budget.Budget(60.0))
    first = run_named(["ideal"], [_deck()], decision, 1)
    again = run_named(["ideal"], [_deck()], decision, 1)
    assert first.cached == 0 and first.figures()["fullwave_cached_solver_seconds"] == 0.0
    assert again.cached == 1 and again.figures()["fullwave_cached_solver_seconds"] == 0.5
    assert again.figures()["fullwave_seconds"] < again.figures()["fullwave_cached_solver_seconds"]
    assert "1 of 1 runs (1 from the cache, their solver 0 s; 0 s in this build)" == again.text()


def test_a_cut_stage_says_what_did_not_finish_and_warns(fake, monkeypatch):
    python, _ = fake
    monkeypatch.setenv("FAKE_MODE", "hang")
    ran = run_named(["ideal", "stepped"], [_deck(8.0), _deck(9.0)], Decision(python, "ran", 0.0, budget.Budget(0.5)), 2)
    assert ran.status == "warn" and ran.cut == ("ideal", "stepped")
    assert ran.text().endswith("cut at budget_s 0.5 s: ideal, stepped did not finish")
    assert ran.figures()["fullwave_runs_cut"] == 2.0


def test_one_build_shares_one_budget_and_its_heartbeats():
    """Inside a session (a build) every stage gets the same budget, started once, reporting to the
    build's callback; outside one each stage has its own."""
    from antenna_cad.spec.common import VerificationSpec
    settings = VerificationSpec(budget_s=30)
    heard = []
    with budget.session(lambda used, detail: heard.append(detail)):
        first, second = budget.budget_for(settings), budget.budget_for(settings)
        first.heartbeat("on-axis run 1 of 2", force=True)
    assert first is second and first.seconds == 30.0
    assert heard == ["full-wave: on-axis run 1 of 2, 0 s of 30 s budget"]
    alone = budget.budget_for(settings)
    assert alone is not first and alone.beat is None


def test_with_a_scheduler_the_runs_go_to_its_workers_and_are_cached_here(fake):
    """``make-lens build --scheduler``: every pending run is sent to the dask workers at once (the estimate
    counts them in parallel), run there (in the workers' folder), its result cached here by its key and
    its throughput recorded; the rebuild reads the cache."""
    from antenna_cad.sweep.execute import connect
    python, log = fake
    decks = [_deck(8.0), _deck(9.0)]
    sizes = [solver.runner.cell_updates(d) for d in decks]
    with connect(None, workers=1) as client, solver.on_cluster(client):
        assert solver.estimate_s(decks, 1) == pytest.approx(budget.estimate_s(sizes, solver.cache_dir(), 2))
        ran = run_named(["ideal", "stepped"], decks, Decision(python, "ran", 0.0, budget.Budget(120.0)), 1)
    assert ran.cut == () and ran.cached == 0 and all(r["meep_version"] == "fake" for r in ran.results.values())
    _, folders = _started(log)
    assert len(folders) == 2 and all("antenna_cad-sweep-" in str(f) for f in folders)     # on the workers
    assert all((solver.cache_dir() / f"{solver.deck_key(d)}.npz").exists() for d in decks)
    again = run_named(["ideal", "stepped"], decks, Decision(python, "ran", 0.0, budget.Budget(120.0)), 1)
    assert again.cached == 2 and again.figures()["fullwave_cached_solver_seconds"] == 1.0


@pytest.mark.parametrize("address, message", [
    ("http://localhost:8787", "--scheduler: http://localhost:8787: that is a web address"),
    ("tls://localhost:8786", "a build connects by tcp:// only"),
])
def test_build_with_an_unusable_scheduler_says_so_in_one_line(address, message, tmp_path):
    from typer.testing import CliRunner
    from antenna_cad.cli import app
    done = CliRunner().invoke(app, ["build", "xps-collimator-0.5m", "-o", str(tmp_path / "out"), "--scheduler", address])
    assert done.exit_code == 2 and message in done.output and "Traceback" not in done.output
    assert not (tmp_path / "out").exists()


def test_a_run_that_fails_on_the_cluster_is_one_line_naming_the_scheduler(fullwave_cache):
    from antenna_cad.sweep.execute import connect
    from antenna_cad.synthesis.checks import DesignError
    with connect(None, workers=1) as client, solver.on_cluster(client):
        with pytest.raises(DesignError, match=r"^--scheduler: a full-wave run failed on the cluster "
                                              r"\(FullWaveError: Meep runner failed \(exit 1\)"):
            solver.run_decks([_deck()], "/usr/bin/false", 1, budget.Budget(60.0))
