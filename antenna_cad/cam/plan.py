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
from antenna_cad.cam.machines import BUILT_IN, DEFAULT_KERF, FALLBACK_GRADE, Machine, kerf_at
from antenna_cad.cam.router import board_program
from antenna_cad.synthesis.checks import DesignError

MARGIN_MM = 10.0
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


def kerf_of(cam, material_name: str) -> float:
    """Kerf at the spec's feed from the grade's table (the spec's, else the built-in one)."""
    grade = cam.foam_grade or material_name
    table = cam.kerf_table.get(grade) or DEFAULT_KERF.get(grade) or DEFAULT_KERF[FALLBACK_GRADE]
    return kerf_at(table, cam.feed_mm_min)


def _face_path(cut: RuledCut, lead_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Face points of the whole cut: lead point above the entry, the contour, back to the lead point."""
    up = np.array([0.0, lead_mm])

    def path(c):
        return np.concatenate([[c[0] + up], c, c[:1], [c[0] + up]])
    return path(cut.front), path(cut.back)


def place_cut(cut: RuledCut, m: Machine, cam) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float,
                                                       tuple[float, float]]:
    """(xy, uv, front, back, front_wire_mm, center) of a cut placed on machine ``m``; raises
    DesignError naming the part when it does not fit the span or the travel."""
    t = cut.thickness_mm
    if t >= m.span_mm:
        raise DesignError("fabrication.cam", f"part {cut.part}: {t:g} mm of foam does not fit between the "
                          f"towers of {m.name} (span {m.span_mm:g} mm)")
    w0 = (m.span_mm - t) / 2
    front, back = _face_path(cut, cam.lead_in_mm)
    top = max(front[:, 1].max(), back[:, 1].max()) + cam.safe_height_mm    # the wire clear of the foam
    lift = np.array([0.0, top - min(front[0, 1], back[0, 1])])
    front = np.concatenate([[front[0] + lift], front, [front[-1] + lift]])
    back = np.concatenate([[back[0] + lift], back, [back[-1] + lift]])
    xy, uv = tower_paths_open(front, back, t, w0, m.span_mm)
    both = np.concatenate([xy, uv])
    center = (float(MARGIN_MM - both[:, 0].min()), float(MARGIN_MM - both[:, 1].min()))
    xy, uv = xy + center, uv + center
    reach = np.concatenate([xy, uv]).max(axis=0)
    if reach[0] > m.travel_mm[0] or reach[1] > m.travel_mm[1]:
        raise DesignError("fabrication.cam", f"part {cut.part} needs {reach[0]:.0f} × {reach[1]:.0f} mm of tower "
                          f"travel; {m.name} has {m.travel_mm[0]:g} × {m.travel_mm[1]:g} mm")
    return xy, uv, front, back, w0, center


def tower_paths_open(front: np.ndarray, back: np.ndarray, t: float, w0: float, span: float):
    cut = RuledCut("", front[:-1], back[:-1], 0.0, t, 0.0, False)
    xy, uv = tower_paths(cut, w0, span, (0.0, 0.0))
    return xy, uv


def _hotwire_file(cut: RuledCut, m: Machine, cam, material: str) -> tuple[str, dict, np.ndarray, np.ndarray]:
    xy, uv, front, back, w0, center = place_cut(cut, m, cam)
    name = f"cam/{cut.part}.gcode"
    kind = "cone (taper-cut rim)" if cut.cone else "straight (vertical edges, XY = UV)"
    header = [f"antenna_cad hot-wire cut of {cut.part}: {kind}, {material}",
              f"machine {m.name}, axes {m.axes}, tower span {m.span_mm:g} mm",
              f"foam faces: z {cut.z_front_mm:g} mm (feed side) at {w0:g} mm, z {cut.z_back_mm:g} mm at "
              f"{w0 + cut.thickness_mm:g} mm from the first tower along the wire",
              f"lens axis at X {center[0]:.3f} Y {center[1]:.3f} (first tower); sheet +y up",
              f"kerf {cut.kerf_mm:g} mm (compensated), feed {cam.feed_mm_min:g} mm/min at the faster face",
              "dowel holes are not cut here: see the drilling file"]
    prog = hotwire_program(header, m, m.axes, cam.units, m.feed_mode, [(xy, uv, front, back, cam.feed_mm_min)],
                           cam.heat_power, m.dwell_s)
    text = prog.text.replace("(antenna_cad hot-wire", f"(estimated cut time {prog.seconds:.0f} s)\n(antenna_cad hot-wire", 1)
    entry = {"file": name, "part": cut.part, "machine": m.name, "axes": m.axes, "kerf_mm": cut.kerf_mm,
             "feed_mm_min": cam.feed_mm_min, "seconds": round(float(prog.seconds), 1), "tower_span_mm": m.span_mm,
             "faces": [{"z_mm": cut.z_front_mm, "wire_mm": w0},
                       {"z_mm": cut.z_back_mm, "wire_mm": w0 + cut.thickness_mm}],
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


def _router_files(panels, placements, cam) -> tuple[dict[str, str], list[dict]]:
    """One router program per board the box panels are nested on."""
    boards: dict[str, list] = {}
    for panel in panels:
        boards.setdefault(placements[panel.label].board_id, []).append((panel, placements[panel.label]))
    files, entries = {}, []
    router = BUILT_IN["router-3axis"]
    for board_id, parts in sorted(boards.items()):
        prog = board_program(board_id, parts, cam.router)
        name = f"cam/board-{board_id}.gcode"
        files[name] = prog.text
        entries.append({"file": name, "part": ", ".join(p.label for p, _ in parts), "machine": router.name,
                        "axes": router.axes, "kerf_mm": cam.router.tool_diameter_mm,
                        "feed_mm_min": cam.router.feed_mm_min, "seconds": round(float(prog.seconds), 1)})
    return files, entries


def plan_cam(layup, pieces, cam, material: str, panels=(), placements=None) -> CamPlan:
    """Hot-wire and drilling programs of every piece of ``layup`` (``pieces``: the fabrication plan's),
    and router programs of the box ``panels`` per board (``placements``: the nesting)."""
    m = machine_of(cam)
    kerf = kerf_of(cam, material)
    sheets = sorted(layup.sheets, key=lambda s: s.index, reverse=cam.order == "flat_first")
    files, entries, cuts = {}, [], []
    for sheet in sheets:
        own = sorted((p for p in pieces if p.sheet_index == sheet.index), key=lambda p: p.label)
        blank = sheet.tapered and not any(p.label == sheet.label for p in own)   # the disc is in board strips
        for piece in own:
            text, entry, xy, uv = _hotwire_file(piece_cut(piece, sheet, kerf), m, cam, material)
            files[entry["file"]] = text
            entries.append(entry)
            cuts.append((entry, xy, uv))
            drill = _drill_file(piece, sheet, cam)
            if drill is not None:
                files[drill[1]["file"]] = drill[0]
                entries.append(drill[1])
        if blank:                                   # the glued strips cut to the cone
            text, entry, xy, uv = _hotwire_file(cone_cut(sheet, kerf, f"{sheet.label}-blank"), m, cam, material)
            files[entry["file"]] = text
            entries.append(entry)
            cuts.append((entry, xy, uv))
    if cam.router is not None and panels:
        router_files, router_entries = _router_files(panels, placements, cam)
        files |= router_files
        entries += router_entries
    return with_order(files, entries, cuts)


def with_order(files: dict[str, str], entries: list[dict], cuts: list) -> CamPlan:
    """The CamPlan of ``files`` with ``cam/cut-order.csv``: every entry in cut order and the total time."""
    rows = ["order,file,part,machine,seconds"] + [f"{i},{e['file']},\"{e['part']}\",{e['machine']},{e['seconds']:g}"
                                                  for i, e in enumerate(entries, 1)]
    rows.append(f",total,,,{sum(e['seconds'] for e in entries):.1f}")
    return CamPlan(files | {"cam/cut-order.csv": "\n".join(rows) + "\n"}, tuple(entries), tuple(cuts))
