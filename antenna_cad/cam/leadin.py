"""Where a hot-wire cut enters its piece (``fabrication.cam.lead_in_at``) and the way in and out.

The wire leaves a small mark where it enters and leaves the contour; put it where the mark does no
harm (Jedicut, GMFC and devFoam let the user place the lead-in):

- ``top``: the piece's highest point (the wire comes straight down through the waste above it);
- ``foot``: its lowest point, which the stand's cradle covers;
- ``dowel_line``: on the radial line through one of the piece's dowel holes (the highest one), a
  line the assembly already marks;
- ``butt_joint``: at the top end of a joint the piece is glued along (a sheet cut from board strips,
  and the blank they make); a piece with no joint enters at the top.

The entry is the contour's farthest point along the chosen direction from the lens axis; the lead
runs ``lead_in_mm`` out along that direction, and the wire starts and stops ``safe_height_mm``
beyond the piece's farthest point that way.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import Point, Polygon

UP = np.array([0.0, 1.0])


def _unit(p) -> np.ndarray:
    v = np.asarray(p, float)
    n = float(np.hypot(*v))
    return v / n if n > 1e-9 else UP


def entry_direction(at: str, sheet, piece=None, siblings=()) -> np.ndarray:
    """Unit vector (sheet frame) from the lens axis toward the entry of ``piece`` (None: the glued
    blank of the sheet's strips ``siblings``)."""
    if at == "foot":
        return -UP
    if at == "dowel_line":
        holes = [(h.x_mm, h.y_mm) for h in sheet.lens_dowels + sheet.foot_dowels
                 if piece is None or Polygon(piece.polygon.exterior).contains(Point(h.x_mm, h.y_mm))]
        return _unit(max(holes, key=lambda p: p[1])) if holes else UP
    if at == "butt_joint":
        parts = [piece] if piece is not None else list(siblings)
        ends = [c for p in parts for q in siblings if q is not p
                for c in _segment_ends(p.polygon.boundary.intersection(q.polygon.boundary))]
        return _unit(max(ends, key=lambda p: p[1])) if ends else UP
    return UP


def _segment_ends(shared) -> list[tuple[float, float]]:
    """End points of the line(s) two touching pieces share (a point contact is no joint)."""
    lines = getattr(shared, "geoms", [shared])
    return [c for g in lines if g.geom_type == "LineString" and g.length > 1e-6 for c in g.coords]


def lead_path(front: np.ndarray, back: np.ndarray, u: np.ndarray, lead_mm: float, safe_mm: float,
              cone: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Face points of the whole cut: safe start, lead point, the contour from the entry round to it,
    the lead point, safe stop (both faces' contours rolled to start at the entry; a cone's rings are
    also turned about the axis so that a ruling lies exactly on the entry direction)."""
    k = int(np.argmax(back @ u + 1e-9 * (back @ np.array([u[1], -u[0]]))))
    front, back = np.roll(front, -k, axis=0), np.roll(back, -k, axis=0)
    if cone:
        a = np.arctan2(u[1], u[0]) - np.arctan2(back[0, 1], back[0, 0])
        turn = np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])      # row vectors turned by a
        front, back = front @ turn, back @ turn
    far = max(float(np.max(np.concatenate([front, back]) @ u)), float(max(front[0] @ u, back[0] @ u)) + lead_mm)

    def path(c):
        lead, safe = c[0] + lead_mm * u, c[0] + (far + safe_mm - float(c[0] @ u)) * u
        return np.concatenate([[safe, lead], c, [c[0], lead, safe]])
    return path(front), path(back)
