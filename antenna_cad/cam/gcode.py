"""G-code writers: the hot-wire program of a ruled cut and the drilling program of dowel holes.

Hot wire (FreeCAD FoamCut, GMFC conventions): absolute mm (or inch), both towers moved together on
every line; the feed is the wire's speed at the faster foam face, given per line as G93 inverse time
(1/minutes, synchronized towers) or G94 units per minute over the 4-axis move. Start: rapid at the
safe height above the entry, heat on, dwell, then down through waste to the lead-in and the contour;
the same way out; heat off at the safe height. Drilling: G81 cycles from the back face.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.cam.machines import Machine

INCH_MM = 25.4


@dataclass(frozen=True)
class Program:
    text: str
    seconds: float


def _num(x: float) -> str:
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _words(axes: str, values, scale: float) -> str:
    return " ".join(f"{a}{_num(v / scale)}" for a, v in zip(axes, values))


def hotwire_program(header: list[str], machine: Machine, axes: str, units: str, feed_mode: str,
                    passes: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]], power: float,
                    dwell_s: float) -> Program:
    """The program of ``passes``: (xy, uv, front, back, feed mm/min), tower paths (M, 2) in machine mm
    whose moves carry the wire over the foam faces ``front``/``back`` (M, 2); each pass's first and
    last rows are its safe start/stop, where the heat goes on and off."""
    scale = INCH_MM if units == "inch" else 1.0
    lines = [f"({h})" for h in header]
    lines += ["G21" if units == "mm" else "G20", "G90", "G93" if feed_mode == "inverse_time" else "G94"]
    seconds = 0.0
    for xy, uv, front, back, feed_mm_min in passes:
        seconds += dwell_s
        lines.append("G0 " + _words(axes, (*xy[0], *uv[0]), scale))
        lines += [machine.heat_on.replace("{power}", _num(power)), f"G4 P{_num(dwell_s)}"]
        for k in range(1, len(xy)):
            face = max(np.hypot(*(front[k] - front[k - 1])), np.hypot(*(back[k] - back[k - 1])))
            if face <= 0:
                continue
            minutes = face / feed_mm_min
            seconds += 60 * minutes
            if feed_mode == "inverse_time":
                f = 1.0 / minutes
            else:
                f = np.hypot(*(xy[k] - xy[k - 1]), *(uv[k] - uv[k - 1])) / scale / minutes
            lines.append("G1 " + _words(axes, (*xy[k], *uv[k]), scale) + f" F{_num(f)}")
        lines.append(machine.heat_off)
    lines += ["G94", "M2"]
    return Program("\n".join(lines) + "\n", float(seconds))


def drill_program(header: list[str], holes: list[tuple[float, float, float]], units: str, feed_mm_min: float,
                  rapid_mm_min: float, clearance_mm: float) -> Program:
    """G81 cycles at (x, y, depth) from Z 0 on the face, retract to ``clearance_mm``."""
    scale = INCH_MM if units == "inch" else 1.0
    lines = [f"({h})" for h in header]
    lines += ["G21" if units == "mm" else "G20", "G90", "G94", f"G0 Z{_num(clearance_mm / scale)}", "M3 S10000"]
    seconds, at = 0.0, np.zeros(2)
    for x, y, depth in holes:
        seconds += 60 * (np.hypot(x - at[0], y - at[1]) / rapid_mm_min + depth / feed_mm_min
                         + (depth + clearance_mm) / rapid_mm_min)
        at = np.array([x, y])
        lines.append(f"G81 X{_num(x / scale)} Y{_num(y / scale)} Z{_num(-depth / scale)} "
                     f"R{_num(clearance_mm / scale)} F{_num(feed_mm_min / scale)}")
    lines += ["G80", "M5", "M2"]
    return Program("\n".join(lines) + "\n", seconds)
