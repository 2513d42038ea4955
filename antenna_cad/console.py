"""What ``make-lens`` shows while it works and after: progress on stderr, tables on stdout.

On a terminal a build shows a progress bar; off one (a log file, a pipe, CI) it writes one line per
stage start and end with the elapsed time, and a heartbeat at least every :data:`HEARTBEAT_S` inside
a long stage with what the stage last reported ("verify: 40 s so far — full-wave: run 2 of 4, 35 s of
120 s budget"). ``quiet`` shows nothing; ``verbose`` writes every report as a line, terminal or not.
A sweep shows rows done of all, failures, time per variant and the time left, the same two ways.
Tables are full width off a terminal (never wrapped to 80 columns in a log).
"""

from __future__ import annotations

import sys
import threading
import time

from rich.console import Console
from rich.table import Table

from antenna_cad.export import present

HEARTBEAT_S = 10.0
LOG_WIDTH = 10_000                      # off a terminal: rows are never wrapped
STATUS_STYLE = present.STATUS_COLOUR
QUIET, NORMAL, VERBOSE = "quiet", "normal", "verbose"
WAITING = "waiting"                     # the pipeline's stage name while another build holds the folder


def stdout_console() -> Console:
    """Console on stdout: the terminal's width, or one line per row when stdout is not a terminal."""
    return Console() if sys.stdout.isatty() else Console(width=LOG_WIDTH)


def stderr_console() -> Console:
    return Console(stderr=True, soft_wrap=True)


def _duration(seconds: float) -> str:
    seconds = max(seconds, 0.0)
    if seconds < 60:
        return f"{seconds:.1f} s"
    minutes, rest = divmod(round(seconds), 60)
    return f"{minutes} min {rest:02d} s" if minutes < 60 else f"{minutes // 60} h {minutes % 60:02d} min"


class _Lines:
    """A progress bar on a terminal (``mode`` normal); else timestamped lines on stderr and a
    heartbeat thread calling ``beat`` every ``period`` seconds without a line (nothing when quiet)."""

    def __init__(self, name: str, mode: str, console: Console | None, terminal: bool | None, period: float,
                 started: float | None = None):
        self.name, self.mode, self.console, self.period = name, mode, console or stderr_console(), period
        self.terminal = self.console.is_terminal if terminal is None else terminal
        self.start = time.monotonic() if started is None else started
        self.lock = threading.RLock()
        self.last_line = self.start
        self.stopped = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True, name="progress-heartbeat")
        self.bar, self.task = None, None

    def __enter__(self):
        if self.mode == NORMAL and self.terminal:
            from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
            self.bar = Progress(TextColumn("{task.description}"), BarColumn(), TimeElapsedColumn(),
                                console=self.console, transient=True)
            self.bar.start()
            self.task = self.bar.add_task(self.name, total=None)
        elif self.mode != QUIET:
            self.thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stopped.set()
        if self.bar is not None:
            self.bar.stop()

    def write(self, text: str) -> None:
        with self.lock:
            now = time.monotonic()
            self.console.print(f"[{_duration(now - self.start):>10}] {text}", markup=False, highlight=False)
            self.last_line = now

    def _run(self) -> None:
        while not self.stopped.wait(min(1.0, self.period)):
            with self.lock:
                if time.monotonic() - self.last_line >= self.period:
                    self.beat()

    def beat(self) -> None:
        raise NotImplementedError


class BuildProgress(_Lines):
    """``progress(stage, fraction, detail="")`` of :func:`antenna_cad.pipeline.build`, rendered."""

    def __init__(self, name: str, mode: str = NORMAL, console: Console | None = None,
                 terminal: bool | None = None, period: float = HEARTBEAT_S, started: float | None = None):
        """``started``: the monotonic clock when the work began (the spec's loading), else now."""
        super().__init__(name, mode, console, terminal, period, started)
        self.stage, self.detail, self.since = "", "", self.start
        self.paused: tuple | None = None       # the stage a wait for the lock interrupted

    def __call__(self, stage: str, fraction: float, detail: str = "") -> None:
        if self.mode == QUIET:
            return
        with self.lock:
            if self.bar is not None:
                text = f"{self.name}: {stage}" + (f" — {detail}" if detail else "")
                self.bar.update(self.task, completed=fraction, total=1.0, description=text)
                return
            now = time.monotonic()
            if stage == WAITING or self.paused:         # a wait for the folder's lock pauses the stage
                self._wait(stage, detail, now)
            elif stage != self.stage:
                if self.stage:
                    self.write(f"{self.stage}: done in {_duration(now - self.since)}")
                self.stage, self.detail, self.since = stage, detail, now
                if stage != "done":
                    self.write(f"{stage}: started" + (f" — {detail}" if detail else ""))
            elif detail and detail != self.detail:
                self.detail = detail
                if self.mode == VERBOSE:
                    self.write(f"{stage}: {detail}")

    def _wait(self, stage: str, detail: str, now: float) -> None:
        if stage == WAITING and not self.paused:
            self.paused = (self.stage, self.detail, self.since)
            self.stage, self.detail, self.since = stage, detail, now
            self.write(f"{stage}: started — {detail}")
        elif stage != WAITING:
            self.write(f"{WAITING}: done in {_duration(now - self.since)}")
            self.stage, self.detail, self.since = self.paused
            self.paused = None
            self(stage, 0.0, detail)

    def beat(self) -> None:
        if self.stage and self.stage != "done":
            self.write(f"{self.stage}: {_duration(time.monotonic() - self.since)} so far"
                       + (f" — {self.detail}" if self.detail else ""))


class SweepProgress(_Lines):
    """``progress(done, total, failed)`` of :func:`antenna_cad.sweep.run_sweep`: rows done of all,
    failures, wall time per variant and the time left; a line per row off a terminal (at most one a
    second unless a variant failed, and a heartbeat while none completes)."""

    def __init__(self, name: str, mode: str = NORMAL, console: Console | None = None,
                 terminal: bool | None = None, period: float = HEARTBEAT_S):
        super().__init__(name, mode, console, terminal, period)
        self.state, self.first = (0, 0, 0), None

    def text(self) -> str:
        done, total, failed = self.state
        line = f"{self.name}: {done} of {total} variants" + (f" ({failed} failed)" if failed else "")
        if done and self.first is not None:
            per = (time.monotonic() - self.first) / done
            line += f", {_duration(per)} per variant" + (f", about {_duration(per * (total - done))} left"
                                                           if done < total else "")
        return line

    def __call__(self, done: int, total: int, failed: int = 0) -> None:
        if self.mode == QUIET:
            return
        with self.lock:
            if self.first is None:
                self.first = time.monotonic()
            before, self.state = self.state, (done, total, failed)
            if self.bar is not None:
                self.bar.update(self.task, completed=done, total=total, description=self.text())
            elif self.state != before and (self.mode == VERBOSE or done in (0, total) or failed != before[2]
                                           or time.monotonic() - self.last_line >= 1.0):
                self.write(self.text())

    def beat(self) -> None:
        if self.first is not None:
            self.write(self.text())


def checks_table(checks) -> Table:
    """The checks, most urgent first, values rounded to what they resolve (:mod:`antenna_cad.export.present`)."""
    table = Table(title="checks", show_lines=False)
    for col in ("check", "status", "value", "message"):
        table.add_column(col, overflow="fold")
    for c in present.by_urgency(checks):
        table.add_row(c.name, f"[{STATUS_STYLE[c.status]}]{present.STATUS_LABEL[c.status]}[/]", present.check_value(c),
                      c.message)
    return table


HEADLINE_SUFFIXES = ("_p2p_deg", "_rms_deg", "_gain_loss_db")   # as-built figures for the terminal


def summary_table(result) -> Table:
    """The build's key figures with names, units and sensible rounding, boards and masses."""
    table = Table(title=f"{result.name} ({result.kind})")
    table.add_column("figure")
    table.add_column("value", justify="right")
    headline = {f"as_built_{k}": v for k, v in result.verified.items() if k.endswith(HEADLINE_SUFFIXES)}
    for name, value in present.figure_rows(result.figures | headline):
        table.add_row(name, value)
    for material, count in result.boards.items():
        table.add_row(f"Boards of {material}", str(count))
    for label, kg in result.masses_kg.items():
        table.add_row(f"Mass of {label}", present.figure_value("mass_kg", kg))
    return table


def seconds_table(seconds: dict[str, float]) -> Table:
    """Wall time of each build stage (``--verbose``)."""
    table = Table(title="stage times")
    table.add_column("stage")
    table.add_column("s", justify="right")
    for stage, s in seconds.items():
        table.add_row(stage, f"{s:.2f}")
    return table
