"""The full-wave time budget: ``verification.budget_s`` as a hard cap on the solver, the heartbeat
the stages report through, and the machine's measured throughput the estimates use.

One build's full-wave stages share one budget: :func:`session` (entered by the pipeline around the
verification) holds the progress callback, and the first stage that needs Meep starts its clock with
the spec's ``budget_s``; outside a session every stage gets a budget of its own. The throughput (cell
updates per second of one solver process, as measured on this machine under its load at the time) and
the set-up time of a run are kept beside the cached results in ``throughput.json``; when none is known a short probe run measures
it (:func:`antenna_cad.fullwave.solver.calibrate`), and every finished run refines it (:func:`record`).
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path

Beat = Callable[[float, str], None]     # (fraction of the budget used, "full-wave: run 2 of 4, 35 s of 120 s budget")
THROUGHPUT_FILE = "throughput.json"
DEFAULT_THROUGHPUT = 1.0e7   # cell-updates/s of one busy core before anything was measured (1.0–2.9·10⁷ measured)
SETUP_S = 2.0                # interpreter start, import meep, rasterizing ε (before anything was measured)
HEARTBEAT_S = 5.0            # a progress line at least this often while the solver runs
NEWEST_WEIGHT = 0.5          # weight of the newest run in the kept throughput (log-average: a busy day pulls it down)


@dataclass
class Budget:
    """``seconds`` of solver wall time from the first :meth:`start`; ``beat`` hears the heartbeats."""
    seconds: float
    beat: Beat | None = None
    started: float | None = None
    last_beat: float = field(default=-math.inf)

    def start(self) -> None:
        if self.started is None:
            self.started = time.monotonic()

    def elapsed(self) -> float:
        return 0.0 if self.started is None else time.monotonic() - self.started

    def left(self) -> float:
        return self.seconds - self.elapsed()

    def heartbeat(self, what: str, force: bool = False) -> None:
        """Report ``what`` with the time used, at most every HEARTBEAT_S unless ``force``."""
        now = time.monotonic()
        if self.beat is None or not force and now - self.last_beat < HEARTBEAT_S:
            return
        self.last_beat = now
        self.beat(min(1.0, self.elapsed() / self.seconds),
                  f"full-wave: {what}, {self.elapsed():.0f} s of {self.seconds:g} s budget")


@dataclass
class _Session:
    beat: Beat | None
    budget: Budget | None = None


_SESSION: ContextVar[_Session | None] = ContextVar("fullwave_session", default=None)


@contextmanager
def session(beat: Beat | None = None) -> Iterator[None]:
    """One build: its full-wave stages share one budget and report through ``beat``."""
    token = _SESSION.set(_Session(beat))
    try:
        yield
    finally:
        _SESSION.reset(token)


def budget_for(settings) -> Budget:
    """The budget of this build's full-wave stages (``settings.budget_s``, shared within a session)."""
    current = _SESSION.get()
    if current is None:
        return Budget(settings.budget_s)
    if current.budget is None:
        current.budget = Budget(settings.budget_s, current.beat)
    return current.budget


def _file(folder: Path) -> Path:
    return folder / THROUGHPUT_FILE


def measured(folder: Path) -> tuple[float, float] | None:
    """The kept (cell-updates/s, set-up s), None when this machine has not measured them."""
    try:
        data = json.loads(_file(folder).read_text(encoding="utf-8"))
        return float(data["cell_updates_per_s"]), float(data["setup_s"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def record(folder: Path, cell_updates: float, run_s: float, wall_s: float) -> None:
    """Fold one finished run into the kept figures: its time-stepping (``run_s``, as the runner timed it)
    gives the throughput, the rest of its wall time the set-up (start, import, rasterizing)."""
    new = (cell_updates / max(run_s, 1e-3), max(wall_s - run_s, 0.0))
    old = measured(folder) or new
    keep(folder, *(math.exp(NEWEST_WEIGHT * math.log(max(n, 1e-3)) + (1 - NEWEST_WEIGHT) * math.log(max(o, 1e-3)))
                   for n, o in zip(new, old)))


def keep(folder: Path, cell_updates_per_s: float, setup_s: float = SETUP_S) -> None:
    """Store the figures beside the cache (atomic write)."""
    folder.mkdir(parents=True, exist_ok=True)
    part = folder / f".{THROUGHPUT_FILE}.{os.getpid()}.part"
    part.write_text(json.dumps({"cell_updates_per_s": cell_updates_per_s, "setup_s": setup_s}) + "\n",
                    encoding="utf-8")
    os.replace(part, _file(folder))


def estimate_s(cell_updates: list[float], folder: Path, jobs: int) -> float:
    """Wall time of runs of these sizes, ``jobs`` at a time, at the kept throughput."""
    if not cell_updates:
        return 0.0
    rate, setup = measured(folder) or (DEFAULT_THROUGHPUT, SETUP_S)
    return sum(setup + c / rate for c in cell_updates) / max(1, min(jobs, len(cell_updates)))
