"""The full-wave time budget: ``verification.budget_s`` as a hard cap on the solver, the heartbeat
the stages report through, and the machine's measured throughput the estimates use.

One build's full-wave stages share one budget: :func:`session` (entered by the pipeline around the
verification) holds the progress callback, and the first stage that needs Meep starts its clock with
the spec's ``budget_s``; outside a session every stage gets a budget of its own. The throughput (cell
updates per second of one solver process, as measured on this machine under its load at the time) is
kept beside the cached results in ``throughput.json``; when none is known a short probe run measures
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
SETUP_S = 2.0                # interpreter start, import meep, rasterizing ε
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


def measured(folder: Path) -> float | None:
    """The kept throughput (cell-updates/s), None when this machine has not measured one."""
    try:
        return float(json.loads(_file(folder).read_text(encoding="utf-8"))["cell_updates_per_s"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def throughput(folder: Path) -> float:
    return measured(folder) or DEFAULT_THROUGHPUT


def record(folder: Path, cell_updates: float, wall_s: float) -> None:
    """Fold one finished run (its cell updates and wall time) into the kept throughput."""
    new = cell_updates / max(wall_s - SETUP_S, 0.25 * wall_s, 1e-3)
    old = measured(folder)
    keep(folder, new if old is None else math.exp(NEWEST_WEIGHT * math.log(new) + (1 - NEWEST_WEIGHT) * math.log(old)))


def keep(folder: Path, cell_updates_per_s: float) -> None:
    """Store the throughput beside the cache (atomic write)."""
    folder.mkdir(parents=True, exist_ok=True)
    part = folder / f".{THROUGHPUT_FILE}.{os.getpid()}.part"
    part.write_text(json.dumps({"cell_updates_per_s": cell_updates_per_s}) + "\n", encoding="utf-8")
    os.replace(part, _file(folder))


def estimate_s(cell_updates: list[float], folder: Path, jobs: int) -> float:
    """Wall time of runs of these sizes, ``jobs`` at a time, at the kept throughput."""
    if not cell_updates:
        return 0.0
    rate = throughput(folder)
    return sum(SETUP_S + c / rate for c in cell_updates) / max(1, min(jobs, len(cell_updates)))
