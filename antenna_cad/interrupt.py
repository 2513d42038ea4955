"""Ctrl-C for the console script: exit 130 at once, whatever the process is doing.

Python turns SIGINT into KeyboardInterrupt only between bytecodes of the main thread, so a long
OCCT call delays it and an ``except BaseException`` around an optional import (trimesh has such
guards) swallows it. Here the signal instead wakes a watcher thread (``signal.set_wakeup_fd``), which
removes the build's temporary folder and ends the process; the previous build is only ever replaced
by the final atomic swap, so stopping anywhere is as safe as a kill. A Ctrl-C after that swap says
the new build is in place and exits 0. A sweep instead asks for :func:`graceful` stopping: the first
Ctrl-C raises KeyboardInterrupt in the main thread (it ends its workers and writes what is done),
a second one ends the process at once. Imports nothing heavy: it is installed before the CLI is imported.
"""

from __future__ import annotations

import os
import shutil
import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

STOPPING = threading.Event()        # set by the watcher: the process is ending with exit 130
GRACEFUL = threading.Event()        # set while the main thread handles the first Ctrl-C itself


def hold_if_stopping() -> None:
    """On the main thread's way out (an error, even a traceback, caused by the temporary folder
    vanishing under it): print nothing and let the watcher end the process with 130."""
    if STOPPING.is_set():
        threading.Event().wait()


def stop_on_interrupt() -> None:
    """Ctrl-C stops at once with exit 130, even inside a long OCCT call or an import that catches
    KeyboardInterrupt: the signal wakes a watcher thread that removes the build's temporary folder
    and ends the process (the previous build is never touched until the final atomic swap)."""
    read_fd, write_fd = os.pipe()
    os.set_blocking(write_fd, False)
    signal.set_wakeup_fd(write_fd, warn_on_full_buffer=False)
    signal.signal(signal.SIGINT, lambda *_: None)       # the watcher acts; Python code never sees it

    def watch() -> None:
        first = True
        while True:
            while os.read(read_fd, 1) != bytes([signal.SIGINT]):   # other handled signals also wake us
                pass
            if not (GRACEFUL.is_set() and first):
                break
            first = False                                       # the main thread got KeyboardInterrupt
        STOPPING.set()
        code = 130
        try:
            pipeline = sys.modules.get("antenna_cad.pipeline")      # may be half imported
            for tmp in list(getattr(pipeline, "IN_PROGRESS", ())):
                shutil.rmtree(tmp, ignore_errors=True)
            if sys.stderr.isatty():
                sys.stderr.write("\x1b[?25h")                     # the progress bar hid the cursor
            placed = list(getattr(pipeline, "PLACED", ()))
            if placed:
                code = 0
                sys.stderr.write(f"\ninterrupted after the build was complete: {placed[-1]} is in place\n")
            else:
                sys.stderr.write("\ninterrupted\n")
            sys.stderr.flush()
        finally:
            os._exit(code)

    threading.Thread(target=watch, daemon=True, name="sigint-watch").start()


@contextmanager
def graceful() -> Iterator[None]:
    """Inside the block (main thread only), the first Ctrl-C raises KeyboardInterrupt where the main
    thread is, so it can end its children and keep what is done; a second one exits at once (130)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    GRACEFUL.set()
    try:
        yield
    finally:
        GRACEFUL.clear()
        signal.signal(signal.SIGINT, previous)
