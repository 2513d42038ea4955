"""Run one writer in a forked child beside the caller's own work (the two cores of a workshop PC).

A build's report writes report.html (verification plots as SVG) and report.pdf (the same plots on
A4 pages, text pages) from the same content; each costs seconds of matplotlib and neither reads
the other, so the PDF is drawn in a child process while the parent draws the page (issue 16). The
child is a plain ``os.fork`` (the state it needs is already in memory, nothing is pickled on the
way in; multiprocessing would refuse inside a daemonic dask worker); it draws with the same code
on the same data, so the bytes equal a serial run's. Its exception comes back to the caller;
Ctrl-C ends it at once (the parent's handler removes the build folder). Only the main thread forks:
a build running in a worker thread (a sweep's dask worker, whose workers already fill the cores)
writes serially, so no lock held by another thread can be copied into the child.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
import threading
from collections.abc import Callable

SERIAL_ENV = "ANTENNA_CAD_SERIAL"       # "1": run in the caller's process (one core, or to compare bytes)


class Beside:
    """``join()`` waits for the child and re-raises its exception (or runs ``work`` now, serially)."""

    def __init__(self, work: Callable[[], None]):
        self._work, self._pid, self._fd = work, None, None
        if (os.environ.get(SERIAL_ENV) == "1" or (os.cpu_count() or 1) < 2 or not hasattr(os, "fork")
                or threading.current_thread() is not threading.main_thread()):
            return
        read_fd, write_fd = os.pipe()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:                                  # the child: do the work, send back None or the error
            os.close(read_fd)
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGINT, signal.SIG_DFL)
            try:
                work()
                outcome = None
            except BaseException as exc:              # noqa: BLE001 - handed to the parent as it is
                outcome = exc
            try:
                payload = pickle.dumps(outcome)
            except Exception:                         # noqa: BLE001 - an exception that does not pickle
                payload = pickle.dumps(RuntimeError(f"{type(outcome).__name__}: {outcome}"))
            with os.fdopen(write_fd, "wb") as pipe:
                pipe.write(payload)
            os._exit(0)
        os.close(write_fd)
        self._pid, self._fd = pid, read_fd

    def join(self) -> None:
        if self._pid is None:
            self._work()
            return
        with os.fdopen(self._fd, "rb") as pipe:
            payload = pipe.read()
        _, status = os.waitpid(self._pid, 0)
        if not payload:
            raise RuntimeError(f"the report writer process ended without an answer (wait status {status})")
        outcome = pickle.loads(payload)
        if outcome is not None:
            raise outcome
