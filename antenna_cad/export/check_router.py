"""``make-lens check`` of the router files: each board's program parsed back (PyPI ``gcodeparser``,
via :func:`antenna_cad.export.check_cam.parse_moves`) and held against its parts as the cut list
nests them, rebuilt from the manifest's spec (the fabrication plan again, not the written files;
a taper-cut Luneburg layup's boards hold only its feet, the wire cuts the rings).

Every cutting move's end point, and the midpoint of every move along a contour, must lie one tool
radius off the nearest part outline within ``CAM_TOL_MM`` and outside every part (no gouge);
the drilling cycles must be as many as the parts' drilled holes, each going down; every move must
stay on the router's travel.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from antenna_cad.export.check import Finding

CAM_TOL_MM = 0.05


def board_parts(manifest: dict) -> tuple[dict, float]:
    """(board id → its parts, tool diameter) of the manifest's spec, planned again."""
    from antenna_cad.cam.boards import drawing_parts, panel_parts, ring_parts
    from antenna_cad.registry import adapter
    from antenna_cad.spec import parse_spec
    spec = parse_spec(manifest["spec"])
    kind = adapter(spec.kind)
    design = kind.synthesize(spec)
    layup, panels = kind.plan(spec, design)
    fab = kind.fabricate(spec, design, layup, panels)
    if spec.kind == "slot_array":
        router = spec.fabrication.router
        return drawing_parts(fab.drawings, kind.PLATE_PARTS, spec.fabrication.broad_wall_mm), router.tool_diameter_mm
    d = spec.fabrication.cam.router.tool_diameter_mm
    if spec.kind == "luneburg":
        from antenna_cad.cam.rings import feet_parts                # a taper-cut layup routes only its feet
        return (feet_parts(fab, d) if layup.edge == "taper" else ring_parts(fab, d)), d
    return panel_parts(panels, fab.placements), d


def router_error_mm(moves: list[np.ndarray], cutting: list[bool], parts, radius_mm: float) -> tuple[float, bool]:
    """(largest |distance to the nearest outline − tool radius| over the cutting moves' end points and
    the midpoints of consecutive cutting moves, whether any of those points lies inside a part)."""
    m = np.array(moves)
    g1 = np.array(cutting)
    pts = m[g1, :2]
    pair = g1[1:] & g1[:-1]
    mids = ((m[1:, :2] + m[:-1, :2]) / 2)[pair]
    probe = shapely.points(np.vstack([pts, mids]))
    ends = [np.asarray(r.coords) for p in parts for r in (p.polygon.exterior, *p.polygon.interiors)]
    segments = shapely.linestrings(np.concatenate([np.stack([c[:-1], c[1:]], 1) for c in ends]))
    (_, nearest), dist = shapely.STRtree(segments).query_nearest(probe, return_distance=True, all_matches=False)
    err = np.abs(dist - radius_mm)
    inside = any(bool(np.any(shapely.contains_xy(p.polygon, *np.vstack([pts, mids]).T))) for p in parts)
    return float(err.max(initial=0.0)), inside


def router_findings(folder: Path, entries: list[dict], boards: dict, tool_mm: float, travel) -> list[Finding]:
    from antenna_cad.export.check_cam import drill_cycles, parse_moves
    out = []
    for entry in entries:
        name = entry["file"]
        parts = boards.get(name.removeprefix("cam/board-").removesuffix(".gcode"))
        if parts is None:
            out.append(Finding(name, "cam_router", False, "no board of that name on the cut list"))
            continue
        text = (folder / name).read_text(encoding="utf-8")
        moves, cutting = parse_moves(text, "XYZ")
        cycles = drill_cycles("\n".join(line for line in text.splitlines() if not line.startswith(("G0 ", "G1 "))))
        err, inside = router_error_mm(moves, cutting, parts, tool_mm / 2)
        drills = sum(len(p.drills) for p in parts)
        m = np.array(moves)
        on_table = bool(np.all(m[:, :2] >= 0) and np.all(m[:, :2] <= np.array(travel)))
        ok = err <= CAM_TOL_MM and not inside and len(cycles) == drills and all(z < 0 for *_, z in cycles) and on_table
        out.append(Finding(name, "cam_router", ok, f"{len(parts)} parts: tool centre vs outline ± Ø{tool_mm:g}/2 "
                           f"{err:.4f} mm (≤ {CAM_TOL_MM} mm){', a move inside a part' if inside else ''}; "
                           f"{len(cycles)} of {drills} drilling cycles"
                           + ("" if on_table else "; a move off the router's travel")))
    return out
