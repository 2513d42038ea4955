"""Running a sweep on dask.distributed: a LocalCluster of single-threaded worker processes (one per
core) by default, or a running cluster by its scheduler address.

The graph per unique variant (resolved-spec hash ``key``): one task per part of each stage of the mode
(:mod:`antenna_cad.sweep.tasks`), keyed ``<stage>-<part>-<key>``, then ``row-<key>`` reducing them.
Rows reach the writer as they complete, so an interrupted sweep keeps what is done.
"""

from __future__ import annotations

import logging
import os
from contextlib import contextmanager
from collections.abc import Callable
from pathlib import Path

from antenna_cad.sweep.tasks import MODE_STAGES, STAGES, finish, run_part
from antenna_cad.sweep.variants import Variant

Progress = Callable[[int, int], None]      # rows done, rows in all
CONNECT_TIMEOUT = "30s"


class SchedulerUnreachable(RuntimeError):
    """No dask scheduler answers at the address given."""


@contextmanager
def connect(scheduler: str | None = None, workers: int | None = None):
    """A dask Client: to ``scheduler`` when given, else to a new LocalCluster of ``workers`` (default:
    one per core) single-threaded processes, without dashboard; closed (with its cluster) on exit."""
    from dask.distributed import Client, LocalCluster
    if scheduler:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except OSError as exc:
            raise SchedulerUnreachable(f"--scheduler: cannot reach {scheduler}: {exc}") from None
        with client:
            yield client
        return
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                      dashboard_address=None, silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        yield client


def submit(client, variants: list[Variant], mode: str, figures: tuple[str, ...], out_dir: Path) -> dict:
    """Futures of the rows, one per unique valid variant: resolved-spec hash → future."""
    stages = MODE_STAGES[mode]
    rows = {}
    for v in variants:
        if not v.key or v.key in rows:
            continue
        parts, counts = [], []
        for name in stages:
            payloads = STAGES[name].parts(v.spec, str(out_dir / "builds" / v.key[:12]))
            parts += [client.submit(run_part, name, p, key=f"{name}-{i}-{v.key}", pure=False)
                      for i, p in enumerate(payloads)]
            counts.append(len(payloads))
        rows[v.key] = client.submit(finish, stages, tuple(counts), figures, *parts, key=f"row-{v.key}", pure=False)
    return rows


def run(client, variants: list[Variant], mode: str, figures: tuple[str, ...], out_dir: Path,
        on_row: Callable[[list[Variant], dict], None], progress: Progress | None = None) -> None:
    """Compute every valid variant; ``on_row(variants, row)`` for each unique result as it completes
    (all variants sharing that spec), ``progress(done, total)`` after each."""
    from dask.distributed import as_completed
    report = progress or (lambda done, total: None)
    by_key: dict[str, list[Variant]] = {}
    for v in variants:
        if v.key:
            by_key.setdefault(v.key, []).append(v)
    futures = submit(client, variants, mode, figures, out_dir)
    total, done = len(futures), 0
    report(done, total)
    key_of = {f.key: k for k, f in futures.items()}
    for future in as_completed(list(futures.values())):
        try:
            row = future.result()
        except Exception as exc:        # a worker that died under the task (KilledWorker), a lost scheduler
            row = {"error": f"task: {type(exc).__name__}: {exc}"}
        done += 1
        on_row(by_key[key_of[future.key]], row)
        report(done, total)
