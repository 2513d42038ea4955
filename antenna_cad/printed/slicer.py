"""Slicer check of a printed lens: the build's 3MF sliced on the command line by PrusaSlicer (Debian's
``prusa-slicer``, 2.5), headless, with the spec's nozzle and layer height, solid (100 % rectilinear
infill, one perimeter: the lattice is the model), and the slicer's own print time and filament read from
the G-code's closing comments (``; filament used [mm] = …``, ``; filament used [cm3] = …``,
``; estimated printing time (normal mode) = 1h 2m 3s``), to set beside the build's volume/flow estimate.

PrusaSlicer prints each 3MF object once (one plate); the ``copies`` of a part are the build's business.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

EXECUTABLE = "prusa-slicer"
TIMEOUT_S = 1800.0
_DURATION = re.compile(r"(\d+)([dhms])")
_SECONDS = {"d": 86400, "h": 3600, "m": 60, "s": 1}


class SlicerError(RuntimeError):
    """The slicer ran but produced no G-code (its last message)."""


class SlicerTimeout(SlicerError):
    """The slicer did not finish in the time allowed (it is stopped)."""


@dataclass(frozen=True)
class SliceResult:
    slicer: str             # name and version, e.g. "PrusaSlicer-2.5.0+UNKNOWN"
    layers: int
    filament_mm: float
    filament_cm3: float
    time_s: float
    gcode: str


def find_slicer() -> str | None:
    return shutil.which(EXECUTABLE)


def slicer_version(exe: str) -> str:
    """The slicer's name and version from its ``--help`` banner."""
    text = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=60).stdout
    found = re.search(r"PrusaSlicer-\S+", text)
    return found.group(0) if found else EXECUTABLE


def parse_duration(text: str) -> float:
    """Seconds of a PrusaSlicer duration such as ``1d 2h 3m 4s`` or ``44m 5s``."""
    parts = _DURATION.findall(text)
    if not parts:
        raise ValueError(f"not a duration: {text!r}")
    return float(sum(int(n) * _SECONDS[u] for n, u in parts))


def _comment(gcode: str, key: str) -> str:
    found = re.search(rf"^; {re.escape(key)} = (.+)$", gcode, re.MULTILINE)
    if found is None:
        raise SlicerError(f"the G-code has no '; {key}' comment")
    return found.group(1).strip()


def parse_gcode(gcode: str) -> dict:
    """The slicer's estimate from its G-code comments: filament (mm, cm³), time (s) and layer count."""
    return {"filament_mm": float(_comment(gcode, "filament used [mm]")),
            "filament_cm3": float(_comment(gcode, "filament used [cm3]")),
            "time_s": parse_duration(_comment(gcode, "estimated printing time (normal mode)")),
            "layers": len(re.findall(r"^;LAYER_CHANGE", gcode, re.MULTILINE))}


def slice_3mf(data: bytes, *, nozzle_mm: float, layer_height_mm: float, filament_diameter_mm: float,
              exe: str | None = None, timeout_s: float = TIMEOUT_S) -> SliceResult:
    """Slice a 3MF package (bytes) solid, in a private temporary folder; raises SlicerError when the
    slicer writes no G-code, SlicerTimeout when it runs past ``timeout_s``."""
    exe = exe or find_slicer()
    if exe is None:
        raise SlicerError(f"{EXECUTABLE} not on PATH")
    with tempfile.TemporaryDirectory(prefix="make-lens-slice-") as tmp:
        src, out = Path(tmp) / "lens.3mf", Path(tmp) / "lens.gcode"
        src.write_bytes(data)
        cmd = [exe, "--export-gcode", "--nozzle-diameter", f"{nozzle_mm:g}", "--layer-height", f"{layer_height_mm:g}",
               "--first-layer-height", f"{layer_height_mm:g}", "--filament-diameter", f"{filament_diameter_mm:g}",
               "--fill-density", "100%", "--fill-pattern", "rectilinear", "--perimeters", "1", "--skirts", "0",
               "--output", str(out), str(src)]
        try:
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout_s, cwd=tmp)
        except subprocess.TimeoutExpired:
            raise SlicerTimeout(f"{EXECUTABLE} did not finish in {timeout_s:g} s (stopped)") from None
        if run.returncode != 0 or not out.exists():
            last = (run.stderr.strip() or run.stdout.strip() or "no output").splitlines()[-1]
            raise SlicerError(f"{EXECUTABLE} exit {run.returncode}: {last}")
        gcode = out.read_text(errors="replace")
    return SliceResult(slicer_version(exe), gcode=gcode, **parse_gcode(gcode))


def extrusion_layers(gcode: str) -> dict[float, np.ndarray]:
    """Extruding moves per layer height: {z mm: segments (n, 2, 2) of (x, y) start/end}, from absolute
    G0/G1 moves whose E grows (relative E, PrusaSlicer's default ``M83``, or absolute ``M82``)."""
    layers: dict[float, list] = {}
    x = y = z = e = 0.0
    relative_e = True
    for line in gcode.splitlines():
        code = line.split(";", 1)[0].split()
        if not code:
            continue
        if code[0] in ("M82", "M83"):
            relative_e = code[0] == "M83"
            continue
        if code[0] not in ("G0", "G1"):
            continue
        word = {w[0]: float(w[1:]) for w in code[1:] if w[0] in "XYZE" and len(w) > 1}
        nx, ny, z = word.get("X", x), word.get("Y", y), word.get("Z", z)
        de = word.get("E", 0.0 if relative_e else e) - (0.0 if relative_e else e)
        if not relative_e:
            e = word.get("E", e)
        if de > 0 and (nx, ny) != (x, y):
            layers.setdefault(round(z, 4), []).append(((x, y), (nx, ny)))
        x, y = nx, ny
    return {k: np.asarray(v, float) for k, v in sorted(layers.items())}
