"""Design sweeps and trade studies (issue 17): a sweep file (:mod:`.model`) expands into variants
(:mod:`.variants`) that run as dask tasks (:mod:`.tasks`, :mod:`.execute`) into one tidy table with a
Pareto front (:mod:`.results`) and a self-contained page (:mod:`.page`)."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from antenna_cad.sweep.execute import Progress, SchedulerUnreachable, connect, run
from antenna_cad.sweep.model import load_sweep
from antenna_cad.sweep.results import (PAGE, PARETO_CSV, RESULTS_CSV, RESULTS_PARQUET, RowWriter, columns,
                                       make_row, pareto_front, write_tables)
from antenna_cad.sweep.variants import expand


__all__ = ["SchedulerUnreachable", "SweepInterrupted", "SweepResult", "run_sweep"]


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep: ``rows`` rows are on disk in ``path`` (results.csv)."""

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


def run_sweep(path: str | Path, out_root: Path, scheduler: str | None = None, workers: int | None = None,
              progress: Progress | None = None) -> SweepResult:
    """Run the sweep file ``path`` into ``out_root/<name>/``: results.csv (rewritten atomically after
    every row, so an interrupted sweep keeps what is done), then results.parquet, pareto.csv, index.html.
    Raises SpecError when the sweep file or its base spec is unusable, SchedulerUnreachable when the
    scheduler does not answer (nothing written either way), SweepInterrupted on Ctrl-C."""
    file = load_sweep(path)
    sweep, variants = file.sweep, expand(file)
    out_dir = (Path(out_root) / sweep.name).resolve()
    cols = columns(sweep)
    writer = RowWriter(out_dir, cols)
    start = time.perf_counter()
    try:
        with connect(scheduler, workers) as client:     # an unreachable scheduler fails here: nothing written
            out_dir.mkdir(parents=True, exist_ok=True)
            for stale in (RESULTS_PARQUET, PARETO_CSV, PAGE):
                (out_dir / stale).unlink(missing_ok=True)
            writer.add([make_row(v, None, out_dir) for v in variants if not v.key])
            run(client, variants, sweep.mode, tuple(sweep.figures), out_dir,
                lambda same, result: writer.add([make_row(v, result, out_dir) for v in same]), progress)
    except KeyboardInterrupt:
        raise SweepInterrupted(out_dir / RESULTS_CSV, len(writer.rows)) from None
    seconds = time.perf_counter() - start
    rows = writer.sorted()
    front = pareto_front(rows, sweep.objectives)
    unique = len({v.key for v in variants if v.key})
    write_tables(out_dir, cols, rows, front)
    from antenna_cad.sweep.page import write_page      # matplotlib: on the client only, not on workers
    write_page(out_dir, sweep, file.base_source, cols, rows, front, unique)
    return SweepResult(sweep.name, out_dir, list(sweep.axes), dict(sweep.objectives), cols, rows, front, unique,
                       seconds)
