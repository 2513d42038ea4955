"""The toolpaths of a sheet layup (DESIGN.md ``CamPlan``): one hot-wire program per piece, one
drilling program per piece with dowel holes, their cut order and times, and the manifest entries
from which anyone can rebuild each cut surface (towers' span, the two foam faces along the wire,
the lens axis in the first tower's coordinates).

Placement: the foam stands between the towers, its feed-side face (z_min) toward the first (XY)
tower, centred on the span; sheet +y is machine +Y (up), sheet +x machine +X; the lens axis sits
where every move of both towers keeps ``MARGIN_MM`` from the travel's zero.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from shapely.geometry import Point, Polygon

from antenna_cad.cam.gcode import drill_program, hotwire_program
from antenna_cad.cam.hotwire import RuledCut, cone_cut, piece_cut, tower_paths
from antenna_cad.cam.leadin import UP, entry_direction, lead_path
from antenna_cad.cam.machines import BUILT_IN, DEFAULT_KERF, FALLBACK_GRADE, Machine, kerf_at
from antenna_cad.cam.boards import panel_parts, router_files
from antenna_cad.synthesis.checks import DesignError

MARGIN_MM = 10.0
TOWER_GAP_MM = 50.0         # foam clear of each tower when the towers are set close
DRILL_CLEARANCE_MM = 5.0


@dataclass(frozen=True)
class CamPlan:
    files: dict[str, str]           # name under the build folder -> G-code / CSV text
    entries: tuple[dict, ...]       # manifest cam[] in cut order
    cuts: tuple[tuple[dict, np.ndarray, np.ndarray], ...]   # (entry, XY path, UV path) of every hot-wire file

    @property
    def seconds(self) -> float:
        return sum(e["seconds"] for e in self.entries)


def machine_of(cam) -> Machine:
    """The spec's machine profile with its overrides applied."""
    m = BUILT_IN[cam.machine] if isinstance(cam.machine, str) else Machine(**cam.machine.model_dump())
    return replace(m, axes=cam.axes or m.axes, span_mm=cam.tower_span_mm or m.span_mm,
                   travel_mm=tuple(cam.travel_mm or m.travel_mm), feed_mode=cam.feed_mode or m.feed_mode,
                   dwell_s=m.dwell_s if cam.dwell_s is None else cam.dwell_s)


def kerf_table_of(cam, material_name: str) -> tuple[tuple[float, float], ...]:
    """The grade's kerf table (the spec's, else the built-in one)."""
    grade = cam.foam_grade or material_name
    return cam.kerf_table.get(grade) or DEFAULT_KERF.get(grade) or DEFAULT_KERF[FALLBACK_GRADE]


def kerf_of(cam, material_name: str) -> float:
    """Kerf at the spec's feed."""
    return kerf_at(kerf_table_of(cam, material_name), cam.feed_mm_min)


def face_kerfs(radii: tuple[float, float], thickness_mm: float, table, feed_mm_min: float,
               inward: bool = False) -> tuple[float, float]:
    """(front, back) kerf of a cone cut through ``radii`` at its two faces: the faster face moves at the
    feed, the other at the feed times the ratio of their path radii (both ends sweep the same angle
    per move), each face's kerf the table's at its own speed (FreeCAD FoamCut scales kerf with speed).
    The path radii are the cone's offset by the feed's kerf/2 (outward, or ``inward`` for a ring's
    hole): one step, the correction of the radii being a fraction of a mm."""
    (r0, r1), t = radii, thickness_mm
    g = (-1.0 if inward else 1.0) * kerf_at(table, feed_mm_min) / 2 * np.hypot(t, r1 - r0) / t
    fast = max(r0 + g, r1 + g)
    return kerf_at(table, feed_mm_min * (r0 + g) / fast), kerf_at(table, feed_mm_min * (r1 + g) / fast)


def span_of(thickness_mm: float, m: Machine, cam) -> float:
    """The towers' span for a cut: the spec's ``tower_span_mm``, else as close as the foam allows
    (``TOWER_GAP_MM`` each side) on a machine with movable towers, else its fixed bow."""
    if cam.tower_span_mm is not None or not m.min_span_mm:
        return m.span_mm
    return float(min(m.span_mm, max(m.min_span_mm, thickness_mm + 2 * TOWER_GAP_MM)))


def place_cut(cut: RuledCut, m: Machine, cam, entry=UP) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                                                                 float, tuple[float, float], float]:
    """(xy, uv, front, back, front_wire_mm, center, span) of a cut placed on machine ``m``, entering
    its contour along the direction ``entry`` (:mod:`antenna_cad.cam.leadin`); raises
    DesignError naming the part when it does not fit the span or the travel."""
    t, span = cut.thickness_mm, span_of(cut.thickness_mm, m, cam)
    if t >= span:
        raise DesignError("fabrication.cam", f"part {cut.part}: {t:g} mm of foam does not fit between the "
                          f"towers of {m.name} (span {span:g} mm)")
    w0 = (span - t) / 2
    front, back = lead_path(cut.front, cut.back, entry, cam.lead_in_mm, cam.safe_height_mm, cut.cone)
    xy, uv = tower_paths_open(front, back, t, w0, span)
    both = np.concatenate([xy, uv])
    center = (float(MARGIN_MM - both[:, 0].min()), float(MARGIN_MM - both[:, 1].min()))
    xy, uv = xy + center, uv + center
    reach = np.concatenate([xy, uv]).max(axis=0)
    if reach[0] > m.travel_mm[0] or reach[1] > m.travel_mm[1]:
        raise DesignError("fabrication.cam", f"part {cut.part} needs {reach[0]:.0f} × {reach[1]:.0f} mm of tower "
                          f"travel; {m.name} has {m.travel_mm[0]:g} × {m.travel_mm[1]:g} mm")
    return xy, uv, front, back, w0, center, span


def tower_paths_open(front: np.ndarray, back: np.ndarray, t: float, w0: float, span: float):
    cut = RuledCut("", front[:-1], back[:-1], 0.0, t, 0.0, False)
    xy, uv = tower_paths(cut, w0, span, (0.0, 0.0))
    return xy, uv


def _hotwire_file(cut: RuledCut, m: Machine, cam, material: str, entry=UP) -> tuple[str, dict, np.ndarray, np.ndarray]:
    xy, uv, front, back, w0, center, span = place_cut(cut, m, cam, entry)
    name = f"cam/{cut.part}.gcode"
    kind = "cone (taper-cut rim)" if cut.cone else "straight (vertical edges, XY = UV)"
    header = [f"antenna_cad hot-wire cut of {cut.part}: {kind}, {material}",
              f"machine {m.name}, axes {m.axes}, towers set {span:g} mm apart",
              f"foam faces: z {cut.z_front_mm:g} mm (feed side) at {w0:g} mm, z {cut.z_back_mm:g} mm at "
              f"{w0 + cut.thickness_mm:g} mm from the first tower along the wire",
              f"lens axis at X {center[0]:.3f} Y {center[1]:.3f} (first tower); sheet +y up",
              f"kerf {cut.kerfs[0]:.3f} / {cut.kerfs[1]:.3f} mm at the two faces' speeds (compensated), feed "
              f"{cam.feed_mm_min:g} mm/min at the faster face",
              "dowel holes are not cut here: see the drilling file"]
    prog = hotwire_program(header, m, m.axes, cam.units, m.feed_mode, [(xy, uv, front, back, cam.feed_mm_min)],
                           cam.heat_power, m.dwell_s)
    text = prog.text.replace("(antenna_cad hot-wire", f"(estimated cut time {prog.seconds:.0f} s)\n(antenna_cad hot-wire", 1)
    entry = {"file": name, "part": cut.part, "machine": m.name, "axes": m.axes, "kerf_mm": cut.kerf_mm,
             "feed_mm_min": cam.feed_mm_min, "seconds": round(float(prog.seconds), 1), "tower_span_mm": span,
             "faces": [{"z_mm": cut.z_front_mm, "wire_mm": w0, "kerf_mm": round(cut.kerfs[0], 4)},
                       {"z_mm": cut.z_back_mm, "wire_mm": w0 + cut.thickness_mm, "kerf_mm": round(cut.kerfs[1], 4)}],
             "center_mm": [round(center[0], 6), round(center[1], 6)]}
    return text, entry, xy, uv


def _drill_file(piece, sheet, cam) -> tuple[str, dict] | None:
    outline = Polygon(piece.polygon.exterior)
    side = -1.0 if sheet.drilled_from_front else 1.0        # x as seen from the drilled face
    holes = [(side * h.x_mm, h.y_mm, sheet.hole_depth_mm(h)) for h in sheet.lens_dowels + sheet.foot_dowels
             if outline.contains(Point(h.x_mm, h.y_mm)) and sheet.hole_depth_mm(h) > 0]
    if not holes:
        return None
    router = BUILT_IN["router-3axis"]
    name = f"cam/{piece.label}-drill.gcode"
    face = ("front (feed-side)", "feed") if sheet.drilled_from_front else ("back (antenna-side)", "antenna")
    header = [f"antenna_cad dowel holes of {piece.label}: drilled from the {face[0]} face, Z 0 on it",
              f"X/Y from the lens axis, seen from the {face[1]} side"]
    prog = drill_program(header, holes, cam.units, cam.drill_feed_mm_min, router.rapid_mm_min, DRILL_CLEARANCE_MM)
    entry = {"file": name, "part": piece.label, "machine": router.name, "axes": router.axes, "kerf_mm": 0.0,
             "feed_mm_min": cam.drill_feed_mm_min, "seconds": round(float(prog.seconds), 1)}
    return prog.text, entry


def plan_cam(layup, pieces, cam, material: str, panels=(), placements=None) -> CamPlan:
    """Hot-wire and drilling programs of every piece of ``layup`` (``pieces``: the fabrication plan's),
    and router programs of the box ``panels`` per board (``placements``: the nesting)."""
    m = machine_of(cam)
    table = kerf_table_of(cam, material)
    kerf = kerf_at(table, cam.feed_mm_min)
    sheets = sorted(layup.sheets, key=lambda s: s.index, reverse=cam.order == "flat_first")
    files, entries, cuts = {}, [], []
    for sheet in sheets:
        own = sorted((p for p in pieces if p.sheet_index == sheet.index), key=lambda p: p.label)
        blank = sheet.tapered and not any(p.label == sheet.label for p in own)   # the disc is in board strips
        for piece in own:
            text, entry, xy, uv = _hotwire_file(piece_cut(piece, sheet, kerf, face_kerfs(sheet.cone_mm, sheet.thickness_mm, table, cam.feed_mm_min)),
                                                m, cam, material, entry_direction(cam.lead_in_at, sheet, piece, own))
            files[entry["file"]] = text
            entries.append(entry)
            cuts.append((entry, xy, uv))
            drill = _drill_file(piece, sheet, cam)
            if drill is not None:
                files[drill[1]["file"]] = drill[0]
                entries.append(drill[1])
        if blank:                                   # the glued strips cut to the cone
            text, entry, xy, uv = _hotwire_file(cone_cut(sheet, kerf, f"{sheet.label}-blank",
                                                         face_kerfs(sheet.cone_mm, sheet.thickness_mm, table, cam.feed_mm_min)), m, cam, material,
                                                entry_direction(cam.lead_in_at, sheet, None, own))
            files[entry["file"]] = text
            entries.append(entry)
            cuts.append((entry, xy, uv))
    if cam.router is not None and panels:
        board_files, board_entries = router_files(panel_parts(panels, placements), cam.router, BUILT_IN["router-3axis"])
        files |= board_files
        entries += board_entries
    return with_order(files, entries, cuts)


def plan_board_cam(boards, router, field: str = "fabrication.cam.router") -> CamPlan:
    """Router programs only (``boards``: board → its parts, :mod:`antenna_cad.cam.boards`)."""
    files, entries = router_files(boards, router, BUILT_IN["router-3axis"], field)
    return with_order(files, entries, [])


def with_order(files: dict[str, str], entries: list[dict], cuts: list) -> CamPlan:
    """The CamPlan of ``files`` with ``cam/cut-order.csv``: every entry in cut order and the total time."""
    rows = ["order,file,part,machine,seconds"] + [f"{i},{e['file']},\"{e['part']}\",{e['machine']},{e['seconds']:g}"
                                                  for i, e in enumerate(entries, 1)]
    rows.append(f",total,,,{sum(e['seconds'] for e in entries):.1f}")
    return CamPlan(files | {"cam/cut-order.csv": "\n".join(rows) + "\n"}, tuple(entries), tuple(cuts))
