"""Progress reports from inside a stage, without threading a callback through every signature.

A report is ``progress(stage, fraction, detail="")``: ``stage`` is running, ``fraction`` (0–1) of the
work is done, ``detail`` says what it is doing now ("run 2 of 4, 35 s of 120 s budget"). The
pipeline installs its callback around a stage with :func:`reporting`; code deep inside that stage (the
full-wave runs of a kind's verification) calls :func:`report`, which goes nowhere when nobody listens
(a sweep worker, a test). Library code never prints: rendering is the console's business.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

Progress = Callable[..., None]          # progress(stage: str, fraction: float, detail: str = "")
_listeners: list[Progress] = []


@contextmanager
def reporting(callback: Progress) -> Iterator[None]:
    """Send :func:`report` calls made inside the block to ``callback`` (nested blocks: the innermost)."""
    _listeners.append(callback)
    try:
        yield
    finally:
        _listeners.remove(callback)


def report(stage: str, fraction: float, detail: str = "") -> None:
    """Tell whoever listens that ``stage`` is at ``fraction`` doing ``detail``; nothing when nobody does."""
    if _listeners:
        _listeners[-1](stage, fraction, detail)
