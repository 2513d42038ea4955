"""Design sweeps and trade studies: a sweep file (:mod:`.model`) expands into variants
(:mod:`.variants`) that run as dask tasks (:mod:`.tasks`, :mod:`.execute`) into one tidy table with a
Pareto front (:mod:`.results`) and a self-contained page (:mod:`.page`). A sweep locks its folder,
and a run after an interrupted one computes only the variants whose rows are missing."""

from __future__ import annotations

import fcntl
import os
import shutil
import time
from dataclasses import dataclass
from pathlib import Path

from antenna_cad.sweep.execute import (Progress, SchedulerUnreachable, SweepError, check_address, connect, run,
                                       security)
from antenna_cad.sweep.model import load_sweep
from antenna_cad.sweep.results import (PAGE, PARETO_CSV, RESULTS_CSV, RESULTS_PARQUET, RowWriter, columns, kept_row,
                                       make_row, pareto_front, previous_results, write_tables)
from antenna_cad.sweep.variants import expand


__all__ = ["SchedulerUnreachable", "SweepError", "SweepInterrupted", "SweepResult", "run_sweep"]


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep: ``rows`` rows are on disk in ``path`` (results.csv), with their
    index.html and pareto.csv."""

    def __init__(self, path: Path, rows: int):
        super().__init__(f"{rows} rows in {path}")
        self.path, self.rows = path, rows


@dataclass(frozen=True)
class SweepResult:
    name: str
    out_dir: Path
    axes: list[str]
    objectives: dict[str, str]
    columns: list[str]
    rows: list[dict]
    front: list[dict]
    unique: int              # distinct resolved specs computed
    seconds: float           # wall time of the computation (cluster start included)
    resumed: int = 0         # rows kept from an interrupted earlier run (not computed again)


def run_sweep(path: str | Path, out_root: Path, scheduler: str | None = None, workers: int | None = None,
              progress: Progress | None = None) -> SweepResult:
    """Run the sweep file ``path`` into ``out_root/<name>/``: results.csv (rewritten atomically after
    every row, so an interrupted sweep keeps what is done), then results.parquet, pareto.csv, index.html.
    Rows of an interrupted earlier run with the same spec hash are kept, not computed again.
    ``progress(done, total, failed)`` counts the variants computed in this run. Raises SpecError when
    the sweep file or its base spec is unusable, SweepError (SchedulerUnreachable) when the scheduler
    address, its certificates or the output folder are unusable (nothing written either way), and
    SweepInterrupted on Ctrl-C (after ending the local workers and writing the page of the rows done)."""
    file = load_sweep(path)
    sweep, variants = file.sweep, expand(file)
    tls = None
    if scheduler and check_address(scheduler) == "tls":
        tls = security(sweep.tls, Path(file.source).parent)
    out_dir = (Path(out_root) / sweep.name).resolve()
    cols = columns(sweep)
    writer = RowWriter(out_dir, cols)
    start = time.perf_counter()
    interrupted, kept = False, []
    try:
        with connect(scheduler, workers, tls) as client:     # an unreachable scheduler fails here: nothing written
            lock = _lock(out_dir)
            try:
                earlier = previous_results(out_dir, cols, list(sweep.axes))
                kept = [v for v in variants if v.key and v.key[:12] in earlier]
                for stale in (RESULTS_PARQUET, PARETO_CSV, PAGE):
                    (out_dir / stale).unlink(missing_ok=True)
                writer.add([make_row(v, None, out_dir) for v in variants if not v.key]
                           + [kept_row(v, earlier[v.key[:12]]) for v in kept])
                todo = [v for v in variants if v.key and v.key[:12] not in earlier]
                run(client, todo, sweep.mode, tuple(sweep.figures), out_dir,
                    lambda same, result: writer.add([make_row(v, result, out_dir) for v in same]), progress)
            finally:
                os.close(lock)
    except KeyboardInterrupt:        # the workers are ended by now (connect); the rows done are on disk
        interrupted = True
    if interrupted and not writer.rows:
        raise SweepInterrupted(out_dir / RESULTS_CSV, 0)
    for leftover in out_dir.glob("builds/*/.*.tmp-*"):     # build mode: what ended workers were writing
        shutil.rmtree(leftover, ignore_errors=True)
    seconds = time.perf_counter() - start
    rows = writer.sorted()
    front = pareto_front(rows, sweep.objectives)
    unique = len({v.key for v in variants if v.key})
    write_tables(out_dir, cols, rows, front)
    from antenna_cad.sweep.page import write_page      # matplotlib: on the client only, not on workers
    write_page(out_dir, sweep, file.base_source, cols, rows, front, unique)
    if interrupted:
        raise SweepInterrupted(out_dir / RESULTS_CSV, len(rows))
    return SweepResult(sweep.name, out_dir, list(sweep.axes), dict(sweep.objectives), cols, rows, front, unique,
                       seconds, len(kept))


def _lock(out_dir: Path) -> int:
    """The sweep folder, created and locked for this run (SweepError when another sweep holds it)."""
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        fd = os.open(out_dir, os.O_RDONLY | os.O_DIRECTORY)
    except OSError as exc:
        raise SweepError(f"{out_dir}: cannot create the sweep folder ({exc.strerror})") from None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        raise SweepError(f"{out_dir}: another sweep is writing into this folder; wait for it to end or "
                         "choose another -o") from None
    return fd
