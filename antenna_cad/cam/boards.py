"""The flat parts as they lie on their boards (the cut list's nesting), for the router: box panels
(rectangles with face screw holes), Luneburg ring pieces and stand feet (rings, discs, ring
sectors, cradles with registration holes), and slot-array lids and plates (each on its own plate,
slots and coupling slots profiled inside); one router program per board.

Placement (the cut list's): a part's bounding box has its lower-left corner at the placement's
(x, y); a ring sector is first turned so its bisector points to +Y (the nesting orientation), and
a placement marked ``rotated`` turns the part 90° counter-clockwise on the board. Registration
holes are drilled (G81): through holes through, blind holes on the top face to their depth; blind
holes on the bottom face are listed in the file for drilling from the other side.
"""

from __future__ import annotations

import math

import numpy as np
from shapely import affinity
from shapely.geometry import Point, Polygon, box

from antenna_cad.cam.router import THROUGH_MM, BoardPart, board_program
from antenna_cad.fabrication.outline import CHORD_TOL_MM, NEST_SPACING_MM
from antenna_cad.fabrication.ring_pieces import RingPiece
from antenna_cad.synthesis.checks import DesignError


def _on_board(polygon, frame: tuple[float, float, float], w: float, h: float, placement):
    """``polygon`` (any geometry, part frame) turned by frame[2] degrees about the origin, moved by
    frame[:2] into its bounding box (0..w, 0..h), turned 90° when the placement says so, placed."""
    p = affinity.translate(affinity.rotate(polygon, frame[2], origin=(0, 0)), frame[0], frame[1])
    if placement.rotated:
        p = affinity.translate(affinity.rotate(p, 90.0, origin=(0, 0)), h, 0.0)
    return affinity.translate(p, placement.x_mm, placement.y_mm)


def _point(x: float, y: float, frame, w: float, h: float, placement) -> tuple[float, float]:
    q = _on_board(Point(x, y), frame, w, h, placement)
    return float(q.x), float(q.y)


def panel_parts(panels, placements) -> dict[str, list[BoardPart]]:
    """Box panels per board: the face rectangle, its face screw holes drilled through."""
    boards: dict[str, list[BoardPart]] = {}
    for panel in panels:
        pl = placements[panel.label]
        w, h = panel.face_mm
        order = np.argsort(panel.size_mm)[::-1]                  # larger, middle, thickness axis
        lo = np.array(panel.center_mm) - np.array(panel.size_mm) / 2
        depth = panel.thickness_mm + THROUGH_MM
        drills = []
        for hole in panel.holes:
            if hole.axis != "xyz"[order[2]]:                     # holes into an edge are not on the router
                continue
            p = np.array([hole.x_mm, hole.y_mm, hole.z_mm]) - lo
            drills.append((*_point(float(p[order[0]]), float(p[order[1]]), (0, 0, 0), w, h, pl), depth))
        part = BoardPart(panel.label, _on_board(box(0, 0, w, h), (0, 0, 0), w, h, pl), panel.thickness_mm,
                         tuple(drills))
        boards.setdefault(pl.board_id, []).append(part)
    return boards


def ring_parts(fab, tool_diameter_mm: float) -> dict[str, list[BoardPart]]:
    """Luneburg ring pieces and feet per board (``fab``: the rings' fabrication plan), smallest first
    so a ring nested in another's hole is cut before its host. Raises DesignError when the tool is
    wider than the gap the nesting leaves between parts."""
    if tool_diameter_mm > NEST_SPACING_MM:
        raise DesignError("fabrication.cam.router.tool_diameter_mm",
                          f"a Ø{tool_diameter_mm:g} mm tool is wider than the {NEST_SPACING_MM:g} mm the nesting "
                          "leaves between parts")
    boards: dict[str, list[tuple[float, BoardPart]]] = {}
    for piece in fab.pieces:
        pl = fab.placements[piece.label]
        w, h = piece.size_mm(fab.kerf_mm)
        if isinstance(piece, RingPiece):
            ro = piece.ring.r_outer_mm + fab.kerf_mm / 2 + CHORD_TOL_MM
            frame = (w / 2, h - ro, piece.nest_rotation_deg)     # the axis in the bounding box (sector_box)
            outline = Polygon(piece.polygon.exterior, [r for r in piece.polygon.interiors
                                                       if not _is_dowel(r, piece.holes)])
        else:
            x0, y0, _, _ = piece.cut_path(fab.kerf_mm).bounds
            frame, outline = (-x0, -y0, 0.0), piece.polygon
        drills, other_side = [], []
        for hole in piece.holes:
            xy = _point(hole.x_mm, hole.y_mm, frame, w, h, pl)
            if hole.face == "bottom":
                other_side.append(xy)
            else:
                drills.append((*xy, piece.thickness_mm + THROUGH_MM if hole.face == "through" else hole.depth_mm))
        note = ("drill from the bottom face: " + ", ".join(f"X{x:.2f} Y{y:.2f}" for x, y in other_side)
                if other_side else "")
        part = BoardPart(piece.label, _on_board(outline, frame, w, h, pl), piece.thickness_mm, tuple(drills), note)
        boards.setdefault(pl.board_id, []).append((piece.polygon.area, part))
    return {b: [p for _, p in sorted(items, key=lambda t: t[0])] for b, items in boards.items()}


def drawing_parts(drawings, prefixes: tuple[str, ...], thickness_mm: float) -> dict[str, list[BoardPart]]:
    """Parts milled each from its own plate (slot-array lids and beam-former plates): the 1:1
    drawing's cut lines (the largest ring the outline, the rings inside it its holes: slots,
    coupling slots), the part's lower-left corner ``NEST_SPACING_MM`` in from the plate's."""
    boards = {}
    for d in drawings:
        if not d.label.startswith(prefixes) or not d.cut:
            continue
        rings = sorted((Polygon(r) for r in d.cut if len(r) >= 3), key=lambda r: -r.area)
        part = Polygon(rings[0].exterior, [r.exterior for r in rings[1:] if rings[0].contains(r)])
        x0, y0, _, _ = part.bounds
        boards[d.label] = [BoardPart(d.label, affinity.translate(part, NEST_SPACING_MM - x0, NEST_SPACING_MM - y0),
                                     thickness_mm)]
    return boards


def _is_dowel(ring, holes) -> bool:
    """A polygon hole that is one of the piece's dowel holes (drilled, not profiled)."""
    c = Polygon(ring).centroid
    return any(math.hypot(c.x - h.x_mm, c.y - h.y_mm) < 1e-3 for h in holes)


def router_files(boards: dict[str, list[BoardPart]], router, machine, field: str = "fabrication.cam.router"
                 ) -> tuple[dict[str, str], list[dict]]:
    """One router program per board, and its manifest entry (``field``: where the spec sets ``router``)."""
    files, entries = {}, []
    for board_id, parts in sorted(boards.items()):
        prog = board_program(board_id, parts, router, field)
        name = f"cam/board-{board_id}.gcode"
        files[name] = prog.text
        entries.append({"file": name, "part": ", ".join(p.label for p in parts),
                        "machine": machine.name, "axes": machine.axes, "kerf_mm": router.tool_diameter_mm,
                        "feed_mm_min": router.feed_mm_min, "seconds": round(float(prog.seconds), 1)})
    return files, entries
