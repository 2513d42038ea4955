"""Router 2.5-D programs for the flat parts: one file per board as nested on the cut list, so a board
goes on the table once (box panels, Luneburg ring pieces and feet).

Per part: its holes drilled (G81 cycles), then its contours profiled in depth passes, holes and
inner circles before the outline (a part stays held by the board while its inside is cut): the tool
centre one tool radius off the part (outlines outward, inner contours inward; the compensation is
in the path, not G41), climb or conventional (with an M3 spindle, climb runs clockwise round an
outline and counter-clockwise round a hole). Each pass ramps down along the contour over the ramp
length, runs the full contour, and the last pass walks the ramp again at depth; the last pass leaves
holding tabs on every outline and on a hole that other parts are nested in (its waste holds them);
the waste of any other hole (a slot) is cut free. Board frame: X along
the board's width, Y along its length from its lower-left corner, Z 0 on the board's top face.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely.geometry import Polygon
from shapely.geometry.polygon import orient

from antenna_cad.cam.gcode import Program, _num
from antenna_cad.synthesis.checks import DesignError

THROUGH_MM = 0.3            # past the bottom face, into the spoil board
SAFE_Z_MM = 5.0
QUAD_SEGS = 16              # round joins of the offset: sagitta R·(1 − cos(π/64)) ≈ 0.0012·R
SIMPLIFY_MM = 0.005         # offset vertices closer than this to a straight run are dropped
SMOOTH_TURN_DEG = 45.0      # a contour without a turn this sharp is a smooth curve (tabs by quarter)


@dataclass(frozen=True)
class BoardPart:
    """A part as it lies on its board: ``polygon`` the nominal part (board frame, mm), holes of it
    that the router cuts as contours; ``drills`` (x, y, depth) of holes drilled by G81."""
    label: str
    polygon: Polygon
    thickness_mm: float
    drills: tuple[tuple[float, float, float], ...] = ()
    note: str = ""                  # for the operator, in the file


def tool_paths(part: BoardPart, radius_mm: float, field: str = "fabrication.cam.router") -> list[tuple[np.ndarray, bool]]:
    """The part's tool-centre contours (closed, counter-clockwise, first point not repeated) and
    whether each is an inner one: inner contours first, then the outline. Raises DesignError naming
    the part when a hole is narrower than the tool."""
    path = part.polygon.buffer(radius_mm, quad_segs=QUAD_SEGS).simplify(SIMPLIFY_MM, preserve_topology=True)
    if not isinstance(path, Polygon) or len(path.interiors) != len(part.polygon.interiors):
        raise DesignError(f"{field}.tool_diameter_mm",
                          f"part {part.label}: a hole narrower than the Ø{2 * radius_mm:g} mm tool")
    path = orient(path, 1.0)
    inner = [np.asarray(r.coords)[:-1][::-1] for r in path.interiors]     # holes run clockwise in shapely
    return [(p, True) for p in inner] + [(np.asarray(path.exterior.coords)[:-1], False)]


def _tab_count(points: np.ndarray, per_edge: int) -> int:
    """Tabs of a contour: ``per_edge`` on every edge between corners, or four times that round a
    smooth curve (a circle's quadrants)."""
    d = np.diff(np.vstack([points, points[:1]]), axis=0)
    turn = np.degrees(np.abs(np.angle(np.exp(1j * (np.arctan2(d[:, 1], d[:, 0])
                                                    - np.roll(np.arctan2(d[:, 1], d[:, 0]), 1))))))
    corners = int(np.count_nonzero(turn >= SMOOTH_TURN_DEG))
    return per_edge * (corners if corners >= 2 else 4)


def contour_walk(points: np.ndarray, depth_mm: float, router, tabbed: bool = True) -> np.ndarray:
    """(x, y, z) rows of the tool along a closed contour: every pass ramps from the previous depth over
    ``ramp_length_mm`` and runs once round; then the ramp again at full depth; tabs on the last pass
    (the tool steps up and down at each tab's ends)."""
    loop = np.vstack([points, points[:1]])
    s_vert = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(loop, axis=0).T))])
    perimeter = float(s_vert[-1])
    passes = int(np.ceil(depth_mm / router.pass_depth_mm - 1e-9))
    ramp = min(router.ramp_length_mm, perimeter)
    tabs = _tab_count(points, router.tabs_per_edge) if tabbed else 0
    half = (router.tab_width_mm + router.tool_diameter_mm) / 2
    centres = perimeter * (np.arange(tabs) + 0.5) / max(tabs, 1)
    last, total = (passes - 1) * perimeter, passes * perimeter + ramp
    turns = np.arange(passes + 1)[:, None] * perimeter
    events = [(turns + s_vert[:-1]).ravel(), turns[:-1, 0] + ramp]
    if tabs:
        events.append((turns[-2:] + np.concatenate([centres - half, centres + half]) % perimeter).ravel())
    s = np.unique(np.concatenate(events))
    s = s[(s > 0) & (s <= total + 1e-9)]
    u = s % perimeter
    k = np.minimum(s // perimeter, passes - 1)
    z = -depth_mm * (k + np.minimum(1.0, (s - k * perimeter) / ramp)) / passes

    def lift(probe):
        near = np.abs((probe[:, None] % perimeter - centres + perimeter / 2) % perimeter - perimeter / 2) < half - 1e-9
        lifted = np.maximum(z, -depth_mm + router.tab_height_mm + THROUGH_MM)
        return np.where((s >= last) & near.any(axis=1), lifted, z) if tabs else z

    before, after = lift(s - 1e-6), lift(s + 1e-6)
    xy = np.stack([np.interp(u, s_vert, loop[:, 0]), np.interp(u, s_vert, loop[:, 1])], -1)
    rows = np.column_stack([xy, before])
    step = (np.abs(after - before) > 1e-9) & (s < total - 1e-9)
    out = np.insert(rows, np.flatnonzero(step) + 1, np.column_stack([xy[step], after[step]]), axis=0)
    return out


def board_program(board_id: str, parts: list[BoardPart], router, field: str = "fabrication.cam.router") -> Program:
    """The program of one board (``parts`` in cutting order; ``router``: the spec's router settings,
    at ``field``)."""
    d, feed = router.tool_diameter_mm, router.feed_mm_min
    lines = [f"(antenna_cad router: board {board_id}, {len(parts)} parts; tool Ø{d:g} mm, "
             f"{router.direction} milling, ramps {router.ramp_length_mm:g} mm, tabs {router.tab_width_mm:g} × "
             f"{router.tab_height_mm:g} mm)",
             "(X along the board's width, Y along its length from its lower-left corner, Z 0 on the top face)",
             "G21", "G90", "G94", f"G0 Z{_num(SAFE_Z_MM)}", "M3 S18000"]
    seconds, at = 0.0, np.array([0.0, 0.0, SAFE_Z_MM])

    def move(g, x, y, z, f=None):
        nonlocal seconds, at
        seconds += 60 * float(np.linalg.norm(np.array([x, y, z]) - at)) / (f or router.rapid_mm_min)
        at = np.array([x, y, z])
        lines.append(f"{g} X{_num(x)} Y{_num(y)} Z{_num(z)}" + (f" F{_num(f)}" if f else ""))

    for part in parts:
        lines.append(f"({part.label}{'; ' + part.note if part.note else ''})")
        for x, y, depth in part.drills:
            lines.append(f"G81 X{_num(x)} Y{_num(y)} Z{_num(-depth)} R{_num(SAFE_Z_MM)} F{_num(router.plunge_mm_min)}")
            seconds += 60 * (float(np.hypot(x - at[0], y - at[1])) / router.rapid_mm_min
                             + depth / router.plunge_mm_min + (depth + SAFE_Z_MM) / router.rapid_mm_min)
            at = np.array([x, y, SAFE_Z_MM])
        if part.drills:
            lines.append("G80")
        depth = part.thickness_mm + THROUGH_MM
        for points, inner in tool_paths(part, d / 2, field):
            if (router.direction == "climb") != inner:                  # climb: clockwise round an outline
                points = points[::-1]
            k = int(np.argmax(points[:, 1] - 1e-9 * points[:, 0]))     # start at the top
            points = np.roll(points, -k, axis=0)
            move("G0", *points[0], SAFE_Z_MM)
            move("G1", *points[0], 0.0, router.plunge_mm_min)
            holds = not inner or any(Polygon(points).contains(q.polygon) for q in parts if q is not part)
            for x, y, z in contour_walk(points, depth, router, holds).tolist():
                move("G1", x, y, z, feed)
            move("G0", at[0], at[1], SAFE_Z_MM)
    lines += ["M5", "M2"]
    return Program("\n".join([f"(estimated machine time {seconds:.0f} s)"] + lines) + "\n", seconds)
