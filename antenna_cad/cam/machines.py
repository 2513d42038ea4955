"""Built-in machine profiles and the kerf table (data, not code paths).

A 4-axis hot-wire machine has two towers, each moving one end of the wire in its own plane; the
wire is the straight line between them (anchors: FreeCAD FoamCut's tower projection and G93
inverse-time feed; Jedicut/GMFC/devFoam kerf tables and lead-ins; Hot_wire_QT kerf per material vs
speed). Axis letters: the first tower's horizontal and vertical, then the second tower's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Machine:
    name: str
    kind: str                       # "hotwire" or "router"
    axes: str                       # "XYUV" (hot wire: tower 1 h/v, tower 2 h/v) or "XYZ" (router)
    feed_mode: str                  # "inverse_time" (G93) or "per_minute" (G94)
    span_mm: float                  # hot wire: the widest the towers go apart along the wire (the bow)
    travel_mm: tuple[float, float]  # each tower's (horizontal, vertical) travel; router (x, y)
    rapid_mm_min: float
    heat_on: str                    # G-code line(s); {power} is replaced
    heat_off: str
    dwell_s: float                  # after heat on, before the first move into foam
    min_span_mm: float = 0.0        # towers movable on the base beam down to this span (0: a fixed bow);
                                    # a steep cone swings the towers by Δr·(span − t)/2t, so the plan
                                    # sets them as close as the foam allows


BUILT_IN = {
    "hotwire-4axis": Machine("hotwire-4axis", "hotwire", "XYUV", "inverse_time", 1300.0, (1500.0, 1500.0),
                             1500.0, "M3 S{power}", "M5", 2.0, 150.0),
    "hotwire-grbl": Machine("hotwire-grbl", "hotwire", "XYZA", "per_minute", 300.0, (800.0, 500.0),
                            1200.0, "M3 S{power}", "M5", 2.0),
    "router-3axis": Machine("router-3axis", "router", "XYZ", "per_minute", 0.0, (1250.0, 2500.0),
                            5000.0, "M3 S{power}", "M5", 2.0),
}

# Kerf (full width, mm) of a hot wire against feed (mm/min) per foam grade, typical of 0.3–0.5 mm
# NiCr wire at a fixed heat (devFoam, Hot_wire_QT tables): a slower wire melts a wider slot.
DEFAULT_KERF = {
    "xps": ((100.0, 1.6), (300.0, 0.9), (600.0, 0.6)),
    "eps": ((100.0, 2.2), (300.0, 1.3), (600.0, 0.9)),
}
FALLBACK_GRADE = "xps"


def kerf_at(table: tuple[tuple[float, float], ...], feed_mm_min: float) -> float:
    """Kerf at ``feed_mm_min`` interpolated linearly in the table (clamped at its ends)."""
    feeds, kerfs = zip(*sorted(table))
    return float(np.interp(feed_mm_min, feeds, kerfs))
