"""Why a budget is missed: where a build's stage spends its time, and what its memory is made of.

Used by ``benchmarks/run.py`` for a recipe over a budget: one extra build with a profiler per stage
(cProfile, swapped at each stage boundary through the pipeline's progress callback) names the
functions that take the slowest stage's time; the RSS right after imports, against the peak, says
how much of the memory is the libraries themselves. Profiling slows Python code, so the shares, not
the seconds, are the result.
"""

from __future__ import annotations

import cProfile
import pstats
import tempfile
from pathlib import Path

WAIT_STAGES = {"step": "STEP writer", "templates": "template writer"}   # stages that wait for a forked child


def stage_profiles(spec) -> dict[str, pstats.Stats]:
    """One profile per pipeline stage of a build of ``spec`` (stage names as in ``BuildResult.seconds``)."""
    from antenna_cad.pipeline import build
    profiles: dict[str, pstats.Stats] = {}
    current = cProfile.Profile()
    running = ""

    def progress(name: str, fraction: float, detail: str = "") -> None:
        """Called as each stage starts (and from inside one, with the same name): a new profile."""
        nonlocal current, running
        if name == running:
            return
        current.disable()
        if running:
            profiles[running] = pstats.Stats(current)
        current, running = cProfile.Profile(), name
        current.enable()

    with tempfile.TemporaryDirectory(prefix="antenna_cad-why-") as out:
        current.enable()
        try:
            build(spec, Path(out), progress=progress)
        finally:
            current.disable()
    return profiles


def function_name(key: tuple[str, int, str]) -> str:
    """``package.module.function`` for Python code, the bare name for a built-in (an OCCT call shows
    as its bound method, e.g. ``<method 'Perform' of 'OCP.BRepMesh.BRepMesh_IncrementalMesh' objects>``)."""
    filename, _, name = key
    if filename == "~":
        return name.strip("<>{}")
    parts = Path(filename).with_suffix("").parts
    tail = parts[parts.index("site-packages") + 1:] if "site-packages" in parts else parts[-2:]
    return ".".join((*tail, name))


def hot_spots(stats: pstats.Stats, count: int = 3) -> str:
    """The ``count`` functions with the largest own time in ``stats``, with their shares."""
    rows = sorted(stats.stats.items(), key=lambda item: item[1][2], reverse=True)[:count]   # type: ignore[attr-defined]
    total = stats.total_tt or 1.0                                                         # type: ignore[attr-defined]
    return ", ".join(f"{function_name(key)} {100 * row[2] / total:.0f} %" for key, row in rows)


def stage_reason(profiles: dict[str, pstats.Stats], stage: str) -> str:
    """A one-line reason for ``stage``'s time: the hot spots of its profile; for a stage that waits
    for a forked writer, that it waits (the writer's own work is in the child, not profiled here)."""
    if stage in WAIT_STAGES:
        return f"waiting for the forked {WAIT_STAGES[stage]} (its work runs beside STL and report)"
    if stage not in profiles:
        return "not profiled"
    return "own time in " + hot_spots(profiles[stage])


def rss_mb() -> float:
    """This process's resident set now (VmRSS), MB."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024.0
    return float("nan")
