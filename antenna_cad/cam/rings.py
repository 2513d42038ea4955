"""Hot-wire programs of a taper-cut Luneburg ring layup (seed-002 §5.1 (b)): per ring its outer
cone, through the shell's outer sphere at the sheet's two faces, and — a ring with a hole — its
inner cone, through the inner sphere, the wire kerf/2 inside the hole. The wire reaches a hole
through a radial slit from the top (a sector joint when the ring is cut in sectors, glued into
its blank first, as a collimator disc wider than a board). Each manifest entry names its sphere
(``sphere_mm``) and side (``edge``: outer or inner), from which ``make-lens check`` rebuilds the cone;
each face is compensated by the kerf at its own speed, as a collimator's cone.

What a wire cannot cut goes to the router: the dowel holes of every ring piece, one drilling file
per piece and face (``cam/<piece>-drill-top.gcode``, ``-drill-bottom.gcode``: X/Y from the lens axis
as seen from that face, Z 0 on it), and the stand's feet (flat, vertical edges), profiled and
drilled per board as the cut list nests them (``cam/board-<id>.gcode``, unless ``router: null``).
"""

from __future__ import annotations

from antenna_cad.cam.boards import ring_parts, router_files
from antenna_cad.cam.gcode import drill_program
from antenna_cad.cam.hotwire import cone_ring
from antenna_cad.cam.machines import BUILT_IN
from antenna_cad.cam.plan import (DRILL_CLEARANCE_MM, CamPlan, _hotwire_file, face_kerfs, kerf_of, kerf_table_of,
                                  machine_of, with_order)
from antenna_cad.fabrication.ring_pieces import FootPiece, RingPiece


def plan_ring_cam(layup, cam, shells: dict, fab) -> CamPlan:
    """Hot-wire programs of every taper-cut ring of ``layup`` (``shells``: shell index → the
    design's layer, for its sphere radii), sheets in ``cam.order``; the rings' drilling files and
    the feet's router files (``fab``: the rings' fabrication plan, its pieces and nesting)."""
    m = machine_of(cam)
    sheets = sorted(layup.sheets, key=lambda s: s.index, reverse=cam.order == "flat_first")
    files, entries, cuts = {}, [], []
    for s in sheets:
        z = (s.z_min_mm, s.z_max_mm)
        for r in s.rings:
            kerf = kerf_of(cam, r.material.name)
            sh = shells[r.shell_index]
            edges = [("outer", r.cone_outer_mm, sh.r_outer_mm)]
            if max(r.cone_inner_mm) > 0:
                edges.append(("inner", r.cone_inner_mm, sh.r_inner_mm))
            for side, radii, sphere in edges:
                inward = side == "inner"
                faces = face_kerfs(radii, z[1] - z[0], kerf_table_of(cam, r.material.name), cam.feed_mm_min, inward)
                cut = cone_ring(f"{r.label}-{side}", radii, z, kerf, inward, faces)
                text, entry, xy, uv = _hotwire_file(cut, m, cam, r.material.name)
                entry = entry | {"sphere_mm": sphere, "edge": side}
                files[entry["file"]] = text
                entries.append(entry)
                cuts.append((entry, xy, uv))
    for piece in sorted((p for p in fab.pieces if isinstance(p, RingPiece)), key=lambda p: p.label):
        for text, entry in ring_drill_files(piece, cam):
            files[entry["file"]] = text
            entries.append(entry)
    if cam.router is not None and any(isinstance(p, FootPiece) for p in fab.pieces):
        board_files, board_entries = router_files(feet_parts(fab, cam.router.tool_diameter_mm), cam.router,
                                                  BUILT_IN["router-3axis"])
        files |= board_files
        entries += board_entries
    return with_order(files, entries, cuts)


def feet_parts(fab, tool_diameter_mm: float) -> dict:
    """The stand's feet per board (:func:`antenna_cad.cam.boards.ring_parts` without the rings,
    which the wire cuts)."""
    feet = {p.label for p in fab.pieces if isinstance(p, FootPiece)}
    return {board: kept for board, parts in ring_parts(fab, tool_diameter_mm).items()
            if (kept := [p for p in parts if p.label in feet])}


def ring_drill_files(piece: RingPiece, cam) -> list[tuple[str, dict]]:
    """The drilling programs of a ring piece's dowel holes, one per face holding any: "top" (the
    sheet's back face, z_max) and "bottom" (its front face, seen from below: x mirrored); a through
    hole is drilled from the top."""
    router = BUILT_IN["router-3axis"]
    out = []
    for face, faces, mirror in (("top", ("top", "through"), 1.0), ("bottom", ("bottom",), -1.0)):
        holes = [(mirror * h.x_mm, h.y_mm, piece.thickness_mm if h.face == "through" else h.depth_mm)
                 for h in piece.holes if h.face in faces]
        if not holes:
            continue
        name = f"cam/{piece.label}-drill-{face}.gcode"
        header = [f"antenna_cad dowel holes of {piece.label}: drilled from its {face} face, Z 0 on it",
                  f"X/Y from the lens axis as seen from the {face} face (Ø{piece.holes[0].diameter_mm:g} mm drill)"]
        prog = drill_program(header, holes, cam.units, cam.drill_feed_mm_min, router.rapid_mm_min, DRILL_CLEARANCE_MM)
        out.append((prog.text, {"file": name, "part": piece.label, "machine": router.name, "axes": router.axes,
                                "kerf_mm": 0.0, "feed_mm_min": cam.drill_feed_mm_min,
                                "seconds": round(float(prog.seconds), 1)}))
    return out
