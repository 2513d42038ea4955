"""Router 2.5-D programs for the flat parts: one file per board as nested on the cut list, so a board
goes on the table once (box panels of a sheet layup).

Per part: its face holes drilled (G81, through into the spoil board), then its outline profiled in
depth passes: the tool centre offset outward by the tool radius (compensation in the path, not G41),
climb or conventional (with an M3 spindle, climb runs clockwise round an outside contour), each pass
entered on a ramp along the first edge, holding tabs left on the last pass. Board frame: X along the
board's width, Y along its length, Z 0 on the board's top face.
"""

from __future__ import annotations

import numpy as np

from antenna_cad.cam.gcode import Program, _num

THROUGH_MM = 0.3            # past the bottom face, into the spoil board
SAFE_Z_MM = 5.0


def _face_holes(panel) -> list[tuple[float, float]]:
    """Screw holes through the panel's face, in its face frame (origin at the lower-left corner,
    axes the larger then the smaller extent, as ``face_mm``); holes into an edge are left out."""
    order = np.argsort(panel.size_mm)[::-1]                  # larger, middle, thickness axis
    thick = "xyz"[order[2]]
    c, s = np.array(panel.center_mm), np.array(panel.size_mm)
    lo = c - s / 2
    out = []
    for h in panel.holes:
        if h.axis != thick:
            continue
        p = np.array([h.x_mm, h.y_mm, h.z_mm]) - lo
        out.append((float(p[order[0]]), float(p[order[1]])))
    return out


def _placed(points: np.ndarray, w: float, h: float, placement) -> np.ndarray:
    """Face-frame points put on the board: turned 90° when the placement says so, then moved."""
    if placement.rotated:
        points = np.stack([h - points[:, 1], points[:, 0]], -1)
    return points + np.array([placement.x_mm, placement.y_mm])


def _tabbed_z(p0, p1, z, tab_z, tabs, tab_len) -> list[tuple[float, float, float]]:
    """Points along the edge p0→p1 at depth z, raised to tab_z over ``tabs`` evenly spaced tabs."""
    length = float(np.hypot(*(p1 - p0)))
    out = []
    if tabs and length > 3 * tab_len:
        for k in range(1, tabs + 1):
            mid = k / (tabs + 1)
            for u, zz in ((mid - tab_len / 2 / length, z), (mid - tab_len / 2 / length, tab_z),
                          (mid + tab_len / 2 / length, tab_z), (mid + tab_len / 2 / length, z)):
                q = p0 + u * (p1 - p0)
                out.append((float(q[0]), float(q[1]), zz))
    q = p1
    out.append((float(q[0]), float(q[1]), z))
    return out


def board_program(board_id: str, parts: list, router) -> Program:
    """The program of one board: ``parts`` are (panel, placement) of the panels nested on it;
    ``router``: the spec's router settings."""
    d, t_feed = router.tool_diameter_mm, router.feed_mm_min
    lines = [f"(antenna_cad router: board {board_id}, {len(parts)} parts; tool Ø{d:g} mm, "
             f"{router.direction} milling, {router.tabs_per_edge} tab(s) per edge)",
             "(X along the board's width, Y along its length from its lower-left corner, Z 0 on the top face)",
             "G21", "G90", "G94", f"G0 Z{_num(SAFE_Z_MM)}", "M3 S18000"]
    seconds, at = 0.0, np.zeros(3)

    def move(g, x, y, z, feed=None):
        nonlocal seconds, at
        dist = float(np.linalg.norm(np.array([x, y, z]) - at))
        seconds += 60 * dist / (feed or router.rapid_mm_min)
        at = np.array([x, y, z])
        lines.append(f"{g} X{_num(x)} Y{_num(y)} Z{_num(z)}" + (f" F{_num(feed)}" if feed else ""))

    for panel, pl in parts:
        w, h = panel.face_mm
        depth = panel.thickness_mm + THROUGH_MM
        holes = _placed(np.array(_face_holes(panel)).reshape(-1, 2), w, h, pl)
        for x, y in holes:
            lines.append(f"G81 X{_num(x)} Y{_num(y)} Z{_num(-depth)} R{_num(SAFE_Z_MM)} F{_num(router.plunge_mm_min)}")
            seconds += 60 * (depth / router.plunge_mm_min + (depth + SAFE_Z_MM) / router.rapid_mm_min)
        if len(holes):
            lines.append("G80")
        r = d / 2
        rect = np.array([(-r, -r), (w + r, -r), (w + r, h + r), (-r, h + r)])   # counter-clockwise
        if router.direction == "climb":
            rect = rect[::-1]                                                  # clockwise round the outside
        path = _placed(rect, w, h, pl)
        passes = int(np.ceil(depth / router.pass_depth_mm - 1e-9))
        move("G0", path[0, 0], path[0, 1], SAFE_Z_MM)
        move("G1", path[0, 0], path[0, 1], 0.0, router.plunge_mm_min)
        for k in range(1, passes + 1):
            z, last = -depth * k / passes, k == passes
            edge = path[1] - path[0]
            ramp = path[0] + edge * min(1.0, router.ramp_length_mm / float(np.hypot(*edge)))
            move("G1", ramp[0], ramp[1], z, t_feed)                           # ramp down along the first edge
            move("G1", path[0, 0], path[0, 1], z, t_feed)                     # back to the corner at depth
            tab_z = -depth + router.tab_height_mm + THROUGH_MM
            for i in range(4):
                p0, p1 = path[i], path[(i + 1) % 4]
                for x, y, zz in _tabbed_z(p0, p1, z, tab_z if last else z, router.tabs_per_edge if last else 0,
                                          router.tab_width_mm + d):
                    move("G1", x, y, zz, t_feed)
        move("G0", path[0, 0], path[0, 1], SAFE_Z_MM)
    lines += ["M5", "M2"]
    header = f"(estimated machine time {seconds:.0f} s)"
    return Program("\n".join([header] + lines) + "\n", seconds)
