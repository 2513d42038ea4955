"""Running a sweep on dask.distributed: a LocalCluster of single-threaded worker processes (one per
core) by default, or a running cluster by its scheduler address.

The graph per unique variant (resolved-spec hash ``key``): one task per part of each stage of the mode
(:mod:`antenna_cad.sweep.tasks`), keyed ``<stage>-<part>-<key>``, then ``row-<key>`` reducing them.
Rows reach the writer as they complete, so an interrupted sweep keeps what is done.

A running cluster is reached at ``tcp://`` or ``tls://`` only (checked before anything connects);
``tls://`` takes a :class:`distributed.Security` built from the sweep file's ``tls`` block or Dask's
own environment settings. Dask sends pickled functions and data: a scheduler and its workers run
whatever code their clients send, so a cluster shared with others should use ``tls://`` with
certificates that only trusted users hold.
"""

from __future__ import annotations

import logging
import os
import re
import signal
import tempfile
import threading
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path

from antenna_cad.sweep.tasks import MODE_STAGES, STAGES, finish, run_part
from antenna_cad.sweep.variants import Variant

Progress = Callable[[int, int, int], None]      # rows done, rows in all, rows failed
CONNECT_TIMEOUT = "30s"
CLOSE_TIMEOUT_S = 10
HOST_PORT = re.compile(r"(?P<host>\[[0-9a-fA-F:]+\]|[^\s:/\[\]]+):(?P<port>[^/]*)/?")
ADDRESS_FORM = "expected tcp://HOST:PORT or tls://HOST:PORT (the scheduler's address, port 8786 by default)"
WHY_NOT = {"http": "that is a web address (the dashboard's?); the scheduler listens on tcp://HOST:8786",
           "https": "that is a web address (the dashboard's?); the scheduler listens on tcp://HOST:8786",
           "ucx": "UCX needs the optional ucx-py transport, which make-lens does not install",
           "inproc": "inproc:// addresses exist only inside the process that made them",
           "ws": "websocket transports are not supported", "wss": "websocket transports are not supported"}


class SweepError(RuntimeError):
    """The sweep cannot start or go on: one line (the address, the output folder, the certificates)."""


class SchedulerUnreachable(SweepError):
    """No dask scheduler answers at the address given."""


def check_address(address: str) -> str:
    """The protocol of a scheduler address (``tcp`` or ``tls``), or SweepError saying what is wrong."""
    protocol, sep, rest = address.strip().partition("://")
    if not sep:
        raise SweepError(f"--scheduler: {address!r}: {ADDRESS_FORM}")
    if protocol not in ("tcp", "tls"):
        raise SweepError(f"--scheduler: {address}: {WHY_NOT.get(protocol, f'unknown protocol {protocol}://')}; "
                         + ADDRESS_FORM)
    match = HOST_PORT.fullmatch(rest)
    if not match:
        raise SweepError(f"--scheduler: {address}: no HOST:PORT after {protocol}://; {ADDRESS_FORM}")
    port = match["port"]
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise SweepError(f"--scheduler: {address}: port {port!r} is not a number from 1 to 65535")
    return protocol


TLS_ENV = ("DASK_DISTRIBUTED__COMM__TLS__CA_FILE", "DASK_DISTRIBUTED__COMM__TLS__CLIENT__CERT",
           "DASK_DISTRIBUTED__COMM__TLS__CLIENT__KEY")


def security(tls, folder: Path):
    """The distributed Security of a ``tls://`` scheduler: the sweep file's ``tls`` block (paths
    relative to ``folder``), else Dask's own settings (:data:`TLS_ENV` in the environment, or its
    configuration files); SweepError when a certificate is missing or unreadable."""
    import dask
    from distributed import Security
    if tls is not None:
        files = {"tls_ca_file": tls.ca_file, "tls_client_cert": tls.cert, "tls_client_key": tls.key}
        files = {k: str(folder / v) for k, v in files.items() if v}
        source = "the sweep file's tls block"
    else:
        files = {k: dask.config.get(f"distributed.comm.tls.{name}", None) for k, name in
                 (("tls_ca_file", "ca-file"), ("tls_client_cert", "client.cert"), ("tls_client_key", "client.key"))}
        files = {k: v for k, v in files.items() if v}
        source = "the environment"
    if "tls_ca_file" not in files or "tls_client_cert" not in files:
        raise SweepError("--scheduler tls://: needs certificates: a tls block in the sweep file (ca_file, cert, "
                         f"key) or {TLS_ENV[0]} and {TLS_ENV[1]} (and {TLS_ENV[2]}) in the environment")
    for file in files.values():
        try:
            with open(file, "rb"):
                pass
        except OSError as exc:
            raise SweepError(f"{file}: cannot read this certificate file from {source} ({exc.strerror})") from None
    return Security(require_encryption=True, **files)


@contextmanager
def _interrupts_ignored():
    """SIGINT ignored meanwhile (in the main thread): processes spawned now start with it ignored
    (Python and asyncio install no KeyboardInterrupt handler over an ignored SIGINT)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


@contextmanager
def connect(scheduler: str | None = None, workers: int | None = None, security=None):
    """A dask Client: to ``scheduler`` when given (``security``: a distributed Security for tls://),
    else to a new LocalCluster of ``workers`` (default: one per core) single-threaded processes,
    without dashboard. On exit (Ctrl-C included) the cluster is closed, every process it started
    (workers, and what they run, such as Meep) is ended, and the workers' temporary folder is removed."""
    from dask.distributed import Client, LocalCluster
    if scheduler:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT, security=security)
        except Exception as exc:        # OSError, a TLS handshake, a timeout: one line, never a traceback
            raise SchedulerUnreachable(f"--scheduler: cannot reach {scheduler}: {exc}") from None
        with client:
            yield client
        return
    import dask
    with tempfile.TemporaryDirectory(prefix="antenna_cad-sweep-") as scratch, \
            dask.config.set({"temporary-directory": scratch}):    # dask's own lock files too, not TMPDIR
        with _interrupts_ignored():     # the workers start deaf to Ctrl-C (a terminal sends it to the whole
            # process group): this process ends them, and a worker's own KeyboardInterrupt is a traceback
            cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR, local_directory=scratch,
                                   env={"TMPDIR": scratch})
        started: list = []
        try:
            with Client(cluster) as client:
                try:
                    yield client
                except BaseException:            # Ctrl-C, an error: the workers and their runs end at once
                    started = _descendants(cluster)
                    _end(started)
                    raise
        finally:
            started += _descendants(cluster)     # before closing: a dying worker's children lose their parent
            try:
                cluster.close(timeout=CLOSE_TIMEOUT_S)
            finally:
                _end(started)


def _descendants(cluster) -> list:
    """The worker processes of a LocalCluster and everything they started (psutil processes); never
    this process (``psutil.Process(None)`` is this process: a nanny whose worker has gone has no pid)."""
    import psutil
    found = []
    for nanny in list(cluster.workers.values()):
        pid = getattr(getattr(nanny, "process", None), "pid", None)
        if not isinstance(pid, int) or pid == os.getpid():
            continue
        try:
            worker = psutil.Process(pid)
            found += [worker, *worker.children(recursive=True)]
        except (psutil.Error, ValueError, TypeError):
            continue
    return found


def _end(processes: list) -> None:
    """Terminate what is still running of ``processes`` (SIGTERM, SIGKILL after 5 s)."""
    import psutil
    alive = [p for p in processes if p.is_running()]
    for p in alive:
        try:
            p.terminate()
        except psutil.Error:
            pass
    _, left = psutil.wait_procs(alive, timeout=5)
    for p in left:
        try:
            p.kill()
        except psutil.Error:
            pass


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
    (all variants sharing that spec), ``progress(done, total, failed)`` after each. On Ctrl-C the
    futures not done are cancelled (queued tasks never start)."""
    from dask.distributed import as_completed
    report = progress or (lambda done, total, failed: None)
    by_key: dict[str, list[Variant]] = {}
    for v in variants:
        if v.key:
            by_key.setdefault(v.key, []).append(v)
    futures = submit(client, variants, mode, figures, out_dir)
    total, done, failed = len(futures), 0, 0
    report(done, total, failed)
    key_of = {f.key: k for k, f in futures.items()}
    try:
        for future in as_completed(list(futures.values())):
            try:
                row = future.result()
            except Exception as exc:        # a worker that died under the task (KilledWorker), a lost scheduler
                row = {"error": f"task: {type(exc).__name__}: {exc}"}
            done, failed = done + 1, failed + ("error" in row)
            on_row(by_key[key_of[future.key]], row)
            report(done, total, failed)
    except KeyboardInterrupt:
        client.cancel([f for f in futures.values() if not f.done()], force=True)
        raise
