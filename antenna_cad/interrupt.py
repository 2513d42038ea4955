"""Ctrl-C for the console script (issue 11): exit 130 at once, whatever the process is doing.

Python turns SIGINT into KeyboardInterrupt only between bytecodes of the main thread, so a long
OCCT call delays it and an ``except BaseException`` around an optional import (trimesh has such
guards) swallows it. Here the signal instead wakes a watcher thread (``signal.set_wakeup_fd``), which
removes the build's temporary folder and ends the process; the previous build is only ever replaced
by the final atomic swap, so stopping anywhere is as safe as a kill. Imports nothing heavy: it is
installed before the CLI is imported.
"""

from __future__ import annotations

import os
import shutil
import signal
import sys
import threading

STOPPING = threading.Event()        # set by the watcher: the process is ending with exit 130


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
        while os.read(read_fd, 1) != bytes([signal.SIGINT]):   # other handled signals also wake us
            pass
        STOPPING.set()
        try:
            pipeline = sys.modules.get("antenna_cad.pipeline")      # may be half imported
            for tmp in list(getattr(pipeline, "IN_PROGRESS", ())):
                shutil.rmtree(tmp, ignore_errors=True)
            if sys.stderr.isatty():
                sys.stderr.write("\x1b[?25h")                     # the progress bar hid the cursor
            sys.stderr.write("\ninterrupted\n")
            sys.stderr.flush()
        finally:
            os._exit(130)

    threading.Thread(target=watch, daemon=True, name="sigint-watch").start()
