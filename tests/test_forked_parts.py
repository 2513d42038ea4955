"""A printed body's parts in child processes: forked_map keeps the order given, equals in line, and an
error or an early stop leaves no child behind; what a child writes into shared buffers (the STL, the
3MF mesh text) is the bytes written in turn."""

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


def test_in_line_when_no_second_core_is_idle(monkeypatch):
    import antenna_cad.export.forked as forked
    monkeypatch.delenv(SERIAL_ENV, raising=False)
    monkeypatch.setattr(forked, "idle_cores", lambda: 1)
    assert list(forked_map(_pid_and_square, [(1,), (2,)])) == [(os.getpid(), 1), (os.getpid(), 4)]
    monkeypatch.setattr(forked, "idle_cores", lambda: 2)
    assert all(pid != os.getpid() for pid, _ in forked_map(_pid_and_square, [(1,), (2,)]))
    assert 1 <= forked.idle_cores() <= (os.cpu_count() or 1)


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


def test_mesh_text_and_stl_written_into_buffers_are_the_bytes_made_in_turn():
    """What a child writes for the printed package: the 3MF mesh text fits its bound and reads as
    mesh_rows; the STL written in place is the binary STL of the mesh (record by record)."""
    import mmap

    import numpy as np

    from antenna_cad.printed.export3mf import mesh_rows, mesh_rows_bound, mesh_rows_into, stl_bytes, stl_size
    rng = np.random.default_rng(3)
    v = rng.uniform(-999.99996, 999.99996, (1000, 3))
    v[0] = [-999.99996, 0.0, 0.0]                           # rounds to the widest number
    f = rng.integers(0, len(v), (3000, 3))
    out = mmap.mmap(-1, mesh_rows_bound(v, f))
    ends = mesh_rows_into(out, v, f)
    text = "".join(mesh_rows(v, f)).encode()
    assert ends[-1] == len(text) <= len(out) and out[:ends[-1]] == text
    stl = stl_bytes(v, f, "part")
    assert len(stl) == stl_size(len(f)) and stl[:80].rstrip() == b"part"
    rec = np.frombuffer(stl, np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), offset=84)
    assert np.array_equal(rec["v"], v[f].astype(np.float32)) and not rec["a"].any()
