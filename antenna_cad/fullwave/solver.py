"""Running the Meep runner: finding Debian's interpreter, estimating the cost, caching.

Meep (Debian ``python3-meep``) is built against Debian's numpy, so it never runs in the project's
interpreter: :mod:`antenna_cad.fullwave.runner` is executed as a script by an interpreter that imports
``meep`` (``ANTENNA_CAD_MEEP_PYTHON``, else ``/usr/bin/python3``, else ``python3`` on the PATH), with
JSON in and npz out. Results are cached by the SHA-256 of the deck and the runner's source in
``ANTENNA_CAD_FULLWAVE_CACHE`` (default: the user's cache folder, ``$XDG_CACHE_HOME`` or
``~/.cache``, ``/antenna_cad/fullwave``), so rebuilding an unchanged geometry costs nothing.
Every run is a process group of its own, ended whole when the budget (:mod:`.budget`) runs out or the
build stops for any reason; the runner also dies with the build (see :func:`runner.main`).

Inside :func:`on_cluster` (``make-lens build --scheduler``) the runs go to the dask workers instead,
as many at a time as there are runs (they are independent): each worker runs the runner with its own
Meep (:func:`run_remote`) and sends the result back, which is cached here by the same key. At the
budget the futures still running are cancelled (a run already started on a worker finishes there).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from contextvars import ContextVar
from functools import lru_cache
from pathlib import Path

import numpy as np

from antenna_cad.fullwave import budget, runner
from antenna_cad.fullwave.deck import make_deck
from antenna_cad.synthesis.checks import DesignError

RUNNER = Path(runner.__file__)
MISSING = "Meep not found, install python3-meep"
POLL_S = 0.2                # how often running solver processes are looked at
PROBE = make_deck([], frequency_ghz=10.0, resolution=10.0, feed_z_mm=-3000.0, feed_pattern="dipole", feed_q=1.0,
                  radius_mm=90.0, plane_offset_lambda=2.0, field_map=False)      # ≈ 10⁷ cell updates: ~1 s of solver


_CLIENT: ContextVar = ContextVar("fullwave_client", default=None)


class FullWaveError(RuntimeError):
    """The runner failed (its last stderr line is the message)."""


@contextmanager
def on_cluster(client) -> Iterator[None]:
    """Within: every full-wave run goes to the workers of ``client`` (a dask Client)."""
    token = _CLIENT.set(client)
    try:
        yield
    finally:
        _CLIENT.reset(token)


@lru_cache(maxsize=None)
def _imports_meep(python: str) -> bool:
    try:
        done = subprocess.run([python, "-c", "import meep"], capture_output=True, timeout=120, env=_clean_env())
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


def meep_python() -> str | None:
    """The interpreter that imports meep, or None. ``ANTENNA_CAD_MEEP_PYTHON`` overrides the search
    (an override that does not import meep gives None: no silent fallback)."""
    override = os.environ.get("ANTENNA_CAD_MEEP_PYTHON")
    if override:
        return override if _imports_meep(override) else None
    for python in ("/usr/bin/python3", shutil.which("python3")):
        if python and _imports_meep(python):
            return python
    return None


def cache_dir() -> Path:
    if os.environ.get("ANTENNA_CAD_FULLWAVE_CACHE"):
        return Path(os.environ["ANTENNA_CAD_FULLWAVE_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "antenna_cad" / "fullwave"


def deck_key(deck: dict) -> str:
    text = json.dumps(deck, sort_keys=True, separators=(",", ":")) + RUNNER.read_text(encoding="utf-8")
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def _pending(decks: list[dict], keys: list[str], cache: bool = True) -> list[int]:
    """Indices of the decks that must run: not in the cache, first of identical ones."""
    folder = cache_dir()
    return [i for i, k in enumerate(keys) if not (cache and (folder / f"{k}.npz").exists()) and k not in keys[:i]]


def estimate_s(decks: list[dict], jobs: int = 1) -> float:
    """Wall-time estimate of running ``decks`` (uncached ones only) ``jobs`` at a time (all at once on a
    cluster), at the throughput measured on this machine (:mod:`.budget`)."""
    keys = [deck_key(d) for d in decks]
    jobs = len(decks) if _CLIENT.get() is not None else jobs          # on a cluster every run at once
    return budget.estimate_s([runner.cell_updates(decks[i]) for i in _pending(decks, keys)], cache_dir(), jobs)


def calibrate(python: str, within: budget.Budget) -> None:
    """Measure the throughput with a short probe run when none is known (its time counts in ``within``)."""
    if budget.measured(cache_dir()) is None:
        run_decks([PROBE], python, 1, within, "probe run", cache=False)


def _clean_env() -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    return env | {"OMP_NUM_THREADS": "1", "ANTENNA_CAD_PARENT_PID": str(os.getpid())}


def run_decks(decks: list[dict], python: str, jobs: int = 1, within: budget.Budget | None = None,
              what: str = "run", cache: bool = True) -> list[dict | None]:
    """Run every deck (cached ones are read back, identical ones run once), ``jobs`` processes at a
    time, each in its own process group, until ``within`` runs out: then (and on any exception,
    Ctrl-C or SIGTERM) every group still running is killed and its temporary files removed. Each
    result is a dict of arrays as the runner saved it, plus ``cached`` (bool), ``key`` and ``wall_s``
    (seconds this call spent on it); None for a run the budget cut."""
    within = within or budget.Budget(math.inf)
    folder = cache_dir()
    folder.mkdir(parents=True, exist_ok=True)
    keys = [deck_key(d) for d in decks]
    pending = _pending(decks, keys, cache)
    total, done = len(pending), {}
    if pending and _CLIENT.get() is not None:
        within.start()
        done = _run_on_cluster(_CLIENT.get(), decks, keys, pending, python, within, what, cache)
    elif pending:
        within.start()
        with tempfile.TemporaryDirectory(prefix="fullwave-") as tmp, _sigterm_raises():
            running: dict[int, tuple[subprocess.Popen, float]] = {}
            try:
                while (pending or running) and within.left() > 0:
                    while pending and len(running) < max(1, jobs):
                        i = pending.pop(0)
                        running[i] = (_start(decks[i], keys[i], python, Path(tmp)), time.monotonic())
                        within.heartbeat(f"{what} {total - len(pending)} of {total}", force=True)
                    for i, (proc, t0) in list(running.items()):
                        if proc.poll() is not None:
                            del running[i]
                            done[keys[i]] = _finish(proc, keys[i], Path(tmp), time.monotonic() - t0, decks[i], cache)
                    within.heartbeat(f"{what} {total - len(pending)} of {total}")
                    time.sleep(POLL_S)
            finally:
                for proc, _ in running.values():
                    _end(proc)
        within.heartbeat(f"{what}s: {len(done)} of {total} finished" + ("" if len(done) == total else
                                                                          ", the rest cut at the budget"), force=True)
    results = []
    for k in keys:
        if k in done:
            results.append(done[k])
        elif cache and (folder / f"{k}.npz").exists():
            with np.load(folder / f"{k}.npz") as data:
                results.append({name: data[name] for name in data.files} | {"cached": True, "key": k, "wall_s": 0.0})
        else:
            results.append(None)
    return results


def _run_on_cluster(client, decks: list[dict], keys: list[str], pending: list[int], python: str,
                    within: budget.Budget, what: str, cache: bool) -> dict[str, dict]:
    """The pending runs on the cluster's workers, all submitted at once, collected until ``within`` runs out."""
    futures = {i: client.submit(run_remote, decks[i], keys[i], python, key=f"fullwave-{keys[i]}", pure=False)
               for i in pending}
    done: dict[str, dict] = {}
    try:
        while futures and within.left() > 0:
            for i, fut in list(futures.items()):
                if fut.done():
                    del futures[i]
                    try:
                        data, wall_s = fut.result()
                    except Exception as exc:     # noqa: BLE001 — anything from the cluster: one line
                        why = f"{type(exc).__name__}: {' '.join(str(exc).split())[:160]}"
                        raise DesignError("--scheduler", f"a full-wave run failed on the cluster ({why}); the "
                                          "scheduler and its workers need this antenna_cad and Meep") from None
                    done[keys[i]] = _kept(data, keys[i], decks[i], wall_s, cache)
            within.heartbeat(f"{what}s on the cluster: {len(done)} of {len(pending)} finished")
            time.sleep(POLL_S)
    finally:
        client.cancel(list(futures.values()))
    return done


def run_remote(deck: dict, key: str, python: str) -> tuple[bytes, float]:
    """On a worker: run one deck with ``python`` when it is there, else the worker's own Meep
    interpreter; (the result's npz bytes, wall seconds). FullWaveError when it fails."""
    python = python if Path(python).exists() else meep_python()
    if python is None:
        raise FullWaveError(f"on worker: {MISSING}")
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="fullwave-") as tmp:
        proc = _start(deck, key, python, Path(tmp))
        try:
            proc.wait()
        finally:
            _end(proc)
        _raise_failed(proc, key, Path(tmp))
        return (Path(tmp) / f"{key}.npz").read_bytes(), time.monotonic() - t0


def _kept(data: bytes, key: str, deck: dict, wall_s: float, cache: bool) -> dict:
    """A result that came back from a worker: its throughput recorded, kept in the cache (atomic)."""
    part = cache_dir() / f".{key}.{os.getpid()}.part"
    part.write_bytes(data)
    with np.load(part) as npz:
        out = {name: npz[name] for name in npz.files}
    budget.record(cache_dir(), runner.cell_updates(deck), float(out["seconds"]), wall_s)
    if cache:
        os.replace(part, cache_dir() / f"{key}.npz")
    else:
        part.unlink()
    return out | {"cached": False, "key": key, "wall_s": wall_s}


def _raise_failed(proc: subprocess.Popen, key: str, tmp: Path) -> None:
    if proc.returncode != 0:
        lines = [s for s in (tmp / f"{key}.err").read_text(errors="replace").splitlines() if s.strip()]
        raise FullWaveError(f"Meep runner failed (exit {proc.returncode}): {lines[-1] if lines else ''}")


def _start(deck: dict, key: str, python: str, tmp: Path) -> subprocess.Popen:
    (tmp / f"{key}.json").write_text(json.dumps(deck, sort_keys=True), encoding="utf-8")
    with open(tmp / f"{key}.err", "wb") as err:                 # a file: a full pipe would stall the run
        return subprocess.Popen([python, str(RUNNER), f"{key}.json", f"{key}.npz"], cwd=tmp, env=_clean_env(),
                                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err,
                                start_new_session=True)


def _finish(proc: subprocess.Popen, key: str, tmp: Path, wall_s: float, deck: dict, cache: bool) -> dict:
    """The finished run's result (kept in the cache), its throughput recorded; FullWaveError if it failed."""
    _raise_failed(proc, key, tmp)
    with np.load(tmp / f"{key}.npz") as data:
        out = {name: data[name] for name in data.files}
    budget.record(cache_dir(), runner.cell_updates(deck), float(out["seconds"]), wall_s)
    if cache:
        part = cache_dir() / f".{key}.{os.getpid()}.part"
        shutil.copyfile(tmp / f"{key}.npz", part)
        os.replace(part, cache_dir() / f"{key}.npz")          # atomic: a reader never sees half a file
    return out | {"cached": False, "key": key, "wall_s": wall_s}


def _end(proc: subprocess.Popen) -> None:
    """Kill the run's whole process group and reap it."""
    with suppress(ProcessLookupError, PermissionError):
        os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()


@contextmanager
def _sigterm_raises() -> Iterator[None]:
    """SIGTERM (when nobody else handles it) raises SystemExit(143) while runs are going, so that they
    are ended and their folders removed as on Ctrl-C."""
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGTERM) != signal.SIG_DFL:
        yield
        return

    def stop(signum, frame):
        raise SystemExit(128 + signum)
    signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
