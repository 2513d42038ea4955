"""forked_map: independent pieces of one computation in child processes, values in the order given,
the same values as in line, an error and an early stop leave no child behind."""

import os
import time

import pytest

from antenna_cad.export.forked import SERIAL_ENV, forked_map


def _pid_and_square(x):
    if x == 5:
        time.sleep(0.2)                 # ends after the ones started later: the order is still kept
    return os.getpid(), x * x


def _children() -> set[int]:
    with open(f"/proc/{os.getpid()}/task/{os.getpid()}/children") as f:
        return {int(p) for p in f.read().split()}


def test_values_in_order_from_children(monkeypatch):
    monkeypatch.delenv(SERIAL_ENV, raising=False)
    out = list(forked_map(_pid_and_square, [(x,) for x in (5, 1, 2, 3)], workers=2))
    assert [v for _, v in out] == [25, 1, 4, 9]
    assert all(pid != os.getpid() for pid, _ in out)
    assert not _children()


def test_in_line_when_serial(monkeypatch):
    monkeypatch.setenv(SERIAL_ENV, "1")
    out = list(forked_map(_pid_and_square, [(x,) for x in (5, 1, 2)]))
    assert out == [(os.getpid(), 25), (os.getpid(), 1), (os.getpid(), 4)]


def test_error_and_early_stop_leave_no_child(monkeypatch):
    monkeypatch.delenv(SERIAL_ENV, raising=False)

    def fails(x):
        if x == 1:
            raise ValueError("no part today")
        time.sleep(30)
    with pytest.raises(RuntimeError, match="ValueError: no part today"):
        list(forked_map(fails, [(1,), (2,), (3,)], workers=2))
    assert not _children()                                  # the sleeper was killed and reaped
    values = forked_map(lambda x: time.sleep(30 * x), [(0,), (1,), (1,)], workers=2)
    next(values)                                            # the consumer stops (an error, Ctrl-C) here
    values.close()
    assert not _children()
