"""Writers run in a forked child beside the rest of the build.

OCCT's STEP transfer (~1.5 ms a slot) and the template writers (ezdxf, ~1 ms an entity) are
single-threaded and independent of the STL, cut list and report writers, so the build forks them
off and collects them before the manifest: two cores work at once, the bytes are the same as when
written in line (the child runs the same function on a copy of the same memory). The files a child
will write are created empty first, so the report lists them. A child dies with its parent (Linux
PR_SET_PDEATHSIG) and on Ctrl-C; its error comes back as the parent's OSError (the same
errno) or RuntimeError. The report draws report.pdf the same way beside report.html.

A job runs in line (same bytes, one core) when ``ANTENNA_CAD_SERIAL=1``, on a one-core machine, without
``os.fork``, or off the main thread: a build in a worker thread (a sweep's dask worker, whose workers
already fill the cores) must not fork, or a lock held by another thread would be copied into the child.
:func:`forked_map` runs independent pieces of one computation (a printed body's parts) on the idle
cores the same way: values in the order of the arguments, whichever child ends first.
"""

from __future__ import annotations

import ctypes
import os
import pickle
import signal
import threading
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

SERIAL_ENV = "ANTENNA_CAD_SERIAL"       # "1": every job in the caller's process (one core, or to compare bytes)


def _in_line() -> bool:
    return (os.environ.get(SERIAL_ENV) == "1" or (os.cpu_count() or 1) < 2 or not hasattr(os, "fork")
            or threading.current_thread() is not threading.main_thread())


class Job:
    """A function running in a child process: :meth:`finish` waits for its value or stops it."""

    def __init__(self, fn: Callable, args: tuple, placeholders: Iterable[Path] = ()):
        self.name = getattr(fn, "__name__", "job")
        for path in placeholders:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.touch()
        if _in_line():
            self.pid, self.value = None, fn(*args)
            return
        read_fd, write_fd = os.pipe()
        self.pid = os.fork()
        if self.pid == 0:
            os.close(read_fd)
            _run_child(fn, args, write_fd)
        os.close(write_fd)
        self.pipe = os.fdopen(read_fd, "rb")

    def finish(self, wait: bool = True):
        """The function's value (``wait``), or stop the child and return None."""
        if self.pid is None:
            return self.value if wait else None
        if not wait:
            os.kill(self.pid, signal.SIGKILL)
        data = self.pipe.read()
        self.pipe.close()
        _, status = os.waitpid(self.pid, 0)
        self.pid, self.value = None, None
        if not wait:
            return None
        ok, value = pickle.loads(data) if data else (False, f"child ended with status {status}")
        if not ok and isinstance(value, OSError):
            raise value                             # the build turns it into its one-line OutputError
        if not ok:
            raise RuntimeError(f"{self.name} failed: {value}")
        self.value = value
        return value


def idle_cores() -> int:
    """Cores that no other runnable task uses now: the cores less the tasks running besides this one
    (/proc/loadavg); all of them where that cannot be read."""
    cores = os.cpu_count() or 1
    try:
        with open("/proc/loadavg") as f:
            running = int(f.read().split()[3].split("/")[0])
    except (OSError, ValueError, IndexError):
        return cores
    return max(1, cores - max(running - 1, 0))


def forked_map(fn: Callable, arguments: Iterable[tuple], workers: int | None = None) -> Iterator:
    """``fn(*args)`` for each of ``arguments``, in their order, at most ``workers`` (the idle cores)
    children at once; the next child starts before a value is handed on, so the caller's work on it
    overlaps theirs. In line when a :class:`Job` would be, or when fewer than two cores are idle (the
    children would only share one core and add the cost of the fork). Children left when the caller
    stops (an error, Ctrl-C) are killed."""
    workers = workers or idle_cores()
    if _in_line() or workers < 2:
        yield from (fn(*args) for args in arguments)
        return
    running: deque[Job] = deque()
    try:
        for args in arguments:
            if len(running) >= workers:
                value = running.popleft().finish()
                running.append(Job(fn, args))
                yield value
            else:
                running.append(Job(fn, args))
        while running:
            yield running.popleft().finish()
    finally:
        while running:
            running.popleft().finish(wait=False)


def _run_child(fn: Callable, args: tuple, write_fd: int) -> None:
    """In the child: run, send (ok, value or message) back, exit without the parent's cleanup."""
    code = 0
    try:
        signal.set_wakeup_fd(-1)
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        try:
            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)     # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):
            pass
        payload = pickle.dumps((True, fn(*args)))
    except BaseException as exc:                   # noqa: BLE001 — everything goes back to the parent
        code = 1
        payload = pickle.dumps((False, OSError(exc.errno, exc.strerror, exc.filename) if isinstance(exc, OSError)
                                else f"{type(exc).__name__}: {exc}"[:4000]))
    try:
        with os.fdopen(write_fd, "wb") as pipe:
            pipe.write(payload)
    finally:
        os._exit(code)
