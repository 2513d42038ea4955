"""Running the Meep runner (issue 10): finding Debian's interpreter, estimating the cost, caching.

Meep (Debian ``python3-meep``) is built against Debian's numpy, so it never runs in the project's
interpreter: :mod:`antenna_cad.fullwave.runner` is executed as a script by an interpreter that imports
``meep`` (``ANTENNA_CAD_MEEP_PYTHON``, else ``/usr/bin/python3``, else ``python3`` on the PATH), with
JSON in and npz out. Results are cached by the SHA-256 of the deck and the runner's source in
``ANTENNA_CAD_FULLWAVE_CACHE`` (default: the user's cache folder, ``$XDG_CACHE_HOME`` or
``~/.cache``, ``/antenna_cad/fullwave``), so rebuilding an unchanged geometry costs nothing.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from antenna_cad.fullwave import runner

RUNNER = Path(runner.__file__)
MISSING = "Meep not found, install python3-meep"
THROUGHPUT = 1.0e7          # cell-updates/s on one busy core (measured 1.0–2.9·10⁷, fullwave-notes)
SETUP_S = 2.0               # interpreter start, import meep, rasterizing ε


class FullWaveError(RuntimeError):
    """The runner failed (its last stderr line is the message)."""


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


def estimate_s(decks: list[dict], jobs: int = 1) -> float:
    """Wall-time estimate of running ``decks`` (uncached ones only) ``jobs`` at a time."""
    keys = [deck_key(d) for d in decks]
    todo = [d for i, (d, k) in enumerate(zip(decks, keys))
            if not (cache_dir() / f"{k}.npz").exists() and k not in keys[:i]]
    total = sum(SETUP_S + runner.cell_updates(d) / THROUGHPUT for d in todo)
    return total / max(1, min(jobs, len(todo))) if todo else 0.0


def _clean_env() -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    return env | {"OMP_NUM_THREADS": "1"}


def run_decks(decks: list[dict], python: str, jobs: int = 1) -> list[dict]:
    """Run every deck (cached ones are read back, identical ones run once), ``jobs`` processes at a
    time; each result is a dict of arrays as the runner saved it, plus ``cached`` (bool) and ``key``."""
    folder = cache_dir()
    folder.mkdir(parents=True, exist_ok=True)
    keys = [deck_key(d) for d in decks]
    pending = [i for i, k in enumerate(keys) if not (folder / f"{k}.npz").exists() and k not in keys[:i]]
    fresh = {keys[i] for i in pending}
    with tempfile.TemporaryDirectory(prefix="fullwave-") as tmp:
        running: list[tuple[int, subprocess.Popen]] = []
        while pending or running:
            while pending and len(running) < max(1, jobs):
                i = pending.pop(0)
                deck_path = Path(tmp) / f"{keys[i]}.json"
                deck_path.write_text(json.dumps(decks[i], sort_keys=True), encoding="utf-8")
                out = Path(tmp) / f"{keys[i]}.npz"
                running.append((i, subprocess.Popen([python, str(RUNNER), str(deck_path), str(out)], cwd=tmp,
                                                    env=_clean_env(), stdout=subprocess.DEVNULL,
                                                    stderr=subprocess.PIPE, text=True)))
            i, proc = running.pop(0)
            _, err = proc.communicate()
            if proc.returncode != 0:
                for _, other in running:
                    other.kill()
                lines = [s for s in err.splitlines() if s.strip()]
                raise FullWaveError(f"Meep runner failed (exit {proc.returncode}): {lines[-1] if lines else ''}")
            part = folder / f".{keys[i]}.{os.getpid()}.part"
            shutil.copyfile(Path(tmp) / f"{keys[i]}.npz", part)
            os.replace(part, folder / f"{keys[i]}.npz")          # atomic: a reader never sees half a file
    results = []
    for k in keys:
        with np.load(folder / f"{k}.npz") as data:
            results.append({name: data[name] for name in data.files} | {"cached": k not in fresh, "key": k})
    return results
