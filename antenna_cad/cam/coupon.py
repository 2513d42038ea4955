"""Kerf calibration: a coupon program and the kerf table from its measured pieces.

The coupon cuts three squares ``COUPON_MM`` on a side, side by side, from one foam block, each at
one feed, with the wire path on the nominal square (no kerf compensation): each square comes out
smaller by its kerf, so kerf = COUPON_MM − the measured width (Jedicut and devFoam's kerf test).
"""

from __future__ import annotations

import numpy as np

from antenna_cad.cam.gcode import Program, hotwire_program
from antenna_cad.cam.machines import Machine

COUPON_MM = 40.0
GAP_MM = 20.0
SAFE_MM = 20.0


def coupon_program(machine: Machine, grade: str, feeds: tuple[float, float, float], power: float = 100.0,
                   units: str = "mm") -> Program:
    """Three straight (XY = UV) squares, left to right at ``feeds`` mm/min, on ``machine``."""
    s = COUPON_MM
    passes = []
    for i, feed in enumerate(feeds):
        x0, y0 = GAP_MM + i * (s + GAP_MM), GAP_MM
        top = (x0 + s / 2, y0 + s)
        path = np.array([(top[0], top[1] + SAFE_MM), top, (x0, y0 + s), (x0, y0), (x0 + s, y0), (x0 + s, y0 + s),
                         top, (top[0], top[1] + SAFE_MM)])
        passes.append((path, path, path, path, float(feed)))
    header = [f"antenna_cad kerf coupon: {grade}, three {s:g} mm squares at "
              + ", ".join(f"{f:g}" for f in feeds) + " mm/min (left to right), no kerf compensation",
              f"block at least {3 * s + 4 * GAP_MM:g} x {s + 2 * GAP_MM:g} mm, bottom-left corner at X 0 Y 0 "
              f"(both towers), on {machine.name}",
              "measure each square's width; make-lens kerf table turns them into the spec's kerf_table"]
    return hotwire_program(header, machine, machine.axes, units, machine.feed_mode, passes, power, machine.dwell_s)


def kerf_rows(measured: dict[float, float]) -> list[list[float]]:
    """(feed, kerf) rows from ``measured``: feed mm/min → measured square width mm."""
    rows = []
    for feed, width in sorted(measured.items()):
        if not 0 < width <= COUPON_MM:
            raise ValueError(f"{feed:g}={width:g}: a coupon square measures between 0 and {COUPON_MM:g} mm")
        rows.append([feed, round(COUPON_MM - width, 3)])
    return rows
