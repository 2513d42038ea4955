"""Sheet layup of a multilayer Luneburg lens: slabs of stock thickness, concentric rings per slab.

seed-002 digest §5.1 (b): the sphere is sliced by planes z = z_k into sheets of thickness t; each
sheet is a set of concentric rings, one per shell crossed, each cut from the board of its own
foam grade. Ring sizing (selectable, reported):

* ``contain``: over the slab [z_lo, z_hi] the ring of shell (r_in, r_out) has outer radius
  max sqrt(r_out² − z²) and inner radius min sqrt(max(r_in² − z², 0)), so turning/sanding the
  bevelled faces to the spheres only removes material (neighbouring rings overlap radially by
  that finishing allowance until turned);
* ``mid_plane``: radii sqrt(r² − z_m²) at the sheet mid-plane (stepped lens, rings butt, no
  finishing); shell caps that do not reach the mid-plane are dropped (reported).

A cylinder (parallel-plate) lens is sliced along its axis; its rings are the layer radii.
Pure shapely/numpy: no CAD imports. Cost is linear in sheets × rings (+ nesting per grade).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field

import numpy as np
from shapely import affinity
from shapely.geometry import Polygon

from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.nesting import Placement, nest
from antenna_cad.fabrication.outline import CHORD_TOL_MM, NEST_SPACING_MM, Piece, circle_polygon, fits_board
from antenna_cad.fabrication.templates import TEXT_HEIGHT_MM, Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check


@dataclass(frozen=True)
class RingPlan:
    label: str               # "sheet-03-ring-02" (ring of shell 2 in sheet 3)
    sheet_index: int
    shell_index: int
    r_inner_mm: float        # 0 for a disc
    r_outer_mm: float
    material: Material       # the shell's foam grade


@dataclass(frozen=True)
class RingSheet:
    index: int
    label: str
    z_min_mm: float
    z_max_mm: float
    rings: tuple[RingPlan, ...]
    has_neck: bool = False

    @property
    def thickness_mm(self) -> float:
        return self.z_max_mm - self.z_min_mm

    @property
    def radius_mm(self) -> float:
        return max((r.r_outer_mm for r in self.rings), default=0.0)

    def manifest_extra(self) -> dict:
        """Per-sheet manifest fields beyond the common ones (pipeline hook)."""
        return {"material": sorted({r.material.name for r in self.rings}),
                "rings": [{"label": r.label, "shell": r.shell_index, "r_inner_mm": r.r_inner_mm,
                           "r_outer_mm": r.r_outer_mm, "material": r.material.name} for r in self.rings]}


@dataclass(frozen=True)
class RingLayupPlan:
    sheets: tuple[RingSheet, ...]
    sheet_thickness_mm: float
    sizing: str
    shape: str
    kerf_mm: float
    board_width_mm: float
    board_length_mm: float
    registration_hole_mm: float
    dropped_caps: int        # mid_plane: shell caps that miss their sheet's mid-plane

    @property
    def count(self) -> int:
        return len(self.sheets)

    @property
    def rings(self) -> list[RingPlan]:
        return [r for s in self.sheets for r in s.rings]


def ring_radii(r_inner: np.ndarray, r_outer: np.ndarray, z_lo: float, z_hi: float, sizing: str
               ) -> tuple[np.ndarray, np.ndarray]:
    """(inner, outer) ring radii of spherical shells crossed by the slab (outer 0: not crossed)."""
    if sizing == "mid_plane":
        zm = 0.5 * (z_lo + z_hi)
        return (np.sqrt(np.maximum(r_inner**2 - zm * zm, 0.0)),
                np.sqrt(np.maximum(r_outer**2 - zm * zm, 0.0)))
    z_near = 0.0 if z_lo <= 0.0 <= z_hi else min(abs(z_lo), abs(z_hi))
    z_far = max(abs(z_lo), abs(z_hi))
    outer = np.sqrt(np.maximum(r_outer**2 - z_near * z_near, 0.0))
    inner = np.sqrt(np.maximum(r_inner**2 - z_far * z_far, 0.0))
    return inner, outer


def plan_rings(r_inner_mm, r_outer_mm, materials: list[Material], *, shape: str, height_mm: float | None,
               sheet_thickness_mm: float, sizing: str, kerf_mm: float, board_width_mm: float,
               board_length_mm: float, registration_hole_mm: float) -> RingLayupPlan:
    ri, ro = np.asarray(r_inner_mm, float), np.asarray(r_outer_mm, float)
    span = 2.0 * ro[-1] if shape == "sphere" else float(height_mm)
    t = sheet_thickness_mm
    n = max(1, math.ceil(span / t - 1e-9))
    z0 = -0.5 * n * t
    sheets, dropped = [], 0
    for k in range(n):
        z_lo, z_hi = z0 + k * t, z0 + (k + 1) * t
        if shape == "sphere":
            inner, outer = ring_radii(ri, ro, z_lo, z_hi, sizing)
            if sizing == "mid_plane":
                dropped += int(np.sum((outer <= 1e-9) & (ring_radii(ri, ro, z_lo, z_hi, "contain")[1] > 1e-9)))
        else:
            inner, outer = ri, ro
        label = f"sheet-{k + 1:02d}"
        rings = tuple(RingPlan(f"{label}-ring-{j + 1:02d}", k + 1, j + 1, float(inner[j]), float(outer[j]),
                               materials[j])
                      for j in range(len(ro)) if outer[j] > 1e-9 and outer[j] - inner[j] > 1e-9)
        sheets.append(RingSheet(k + 1, label, z_lo, z_hi, rings))
    return RingLayupPlan(tuple(sheets), t, sizing, shape, kerf_mm, board_width_mm, board_length_mm,
                         registration_hole_mm, dropped)


def vertex_count(radius: float, tol: float = CHORD_TOL_MM) -> int:
    """Vertices of ``outline.circle_polygon`` (same chord rule)."""
    return max(24, 4 * math.ceil(math.pi * math.sqrt(radius / (2 * tol)) / 4))


def _circle_xy(radius: float, count: int, circumscribed: bool) -> np.ndarray:
    rv = radius / math.cos(math.pi / count) if circumscribed else radius
    a = 2 * math.pi * np.arange(count) / count
    return np.column_stack([rv * np.cos(a), rv * np.sin(a)])


def ring_polygon(ring: RingPlan, registration_hole_mm: float) -> Polygon:
    """Nominal ring: circumscribed outer polygon (as ``outline.circle_polygon``, vectorized),
    inscribed hole, so the cut part never lies inside the nominal one."""
    n = vertex_count(ring.r_outer_mm)
    outer = _circle_xy(ring.r_outer_mm, n, True)
    if ring.r_inner_mm > 0:
        return Polygon(outer, [_circle_xy(ring.r_inner_mm, n, False)[::-1]])
    outer = Polygon(outer)
    if 0 < registration_hole_mm < ring.r_outer_mm:
        return outer.difference(circle_polygon(0.0, 0.0, registration_hole_mm / 2, tol=0.01))
    return outer


@dataclass(frozen=True)
class FabPlanRings:
    """Same fields as ``sheets.FabPlan`` (what the pipeline reads) plus the nesting report."""
    pieces: tuple[Piece, ...]
    placements: dict[str, Placement]
    joints: dict
    drawings: tuple[Drawing, ...]
    rows: tuple[CutRow, ...]
    totals_kg: dict[str, float]
    boards: dict[str, int]
    kerf_mm: float
    in_hole: dict[str, str]                   # piece label -> host ring label
    in_hole_saving_m2: dict[str, float]       # grade -> board area saved by nesting in holes
    files: dict[str, str] = field(default_factory=dict)   # extra text files, as in ``FabPlan``

    @property
    def checks(self) -> tuple[Check, ...]:
        """Nesting report (the pipeline adds a fabrication plan's ``checks``)."""
        if not self.pieces:
            return ()
        saved = sum(self.in_hole_saving_m2.values())
        return (Check("rings_in_holes", "pass", saved, 0.0, "m2",
                      f"{len(self.in_hole)} rings/discs cut inside ring holes of their grade, saving "
                      f"{saved:.3f} m² of board (bounding squares)"),)


def fabricate_rings(plan: RingLayupPlan, title: str, drawings: bool = True) -> FabPlanRings:
    """Pieces, nesting per grade (discs/rings inside ring holes first, then rectpack), cut list,
    mass per grade and templates per sheet and per ring."""
    kerf = plan.kerf_mm
    pieces: list[Piece] = []
    grade_of: dict[str, Material] = {}
    circ: dict[str, tuple[float, float]] = {}          # whole (unsplit) rings: label -> (r_in, r_out)
    nest_angle: dict[str, float] = {}                  # sector -> rotation (deg) applied for nesting
    for ring in plan.rings:
        piece = Piece(ring.label, ring.sheet_index, ring_polygon(ring, plan.registration_hole_mm),
                      plan.sheets[ring.sheet_index - 1].thickness_mm)
        parts, angles = split_ring_sectors(piece, ring, plan.board_width_mm, plan.board_length_mm, kerf)
        for p, a in zip(parts, angles):
            grade_of[p.label] = ring.material
            nest_angle[p.label] = a
            pieces.append(p)
        if len(parts) == 1:
            circ[ring.label] = (ring.r_inner_mm, ring.r_outer_mm)
    by_grade: dict[str, list[Piece]] = {}
    for p in pieces:
        by_grade.setdefault(grade_of[p.label].name, []).append(p)
    placements: dict[str, Placement] = {}
    in_hole: dict[str, str] = {}
    saving: dict[str, float] = {}
    for grade, items in sorted(by_grade.items()):
        hosted, saved = _nest_in_holes(items, circ, kerf)
        in_hole |= hosted
        saving[grade] = saved
        free = [(p.label, *_size(affinity.rotate(p.cut_path(kerf), nest_angle[p.label], origin=(0, 0))))
                for p in items if p.label not in hosted]
        placements |= {pl.key: pl for pl in nest(free, plan.board_width_mm, plan.board_length_mm, grade)}
        for label in sorted(hosted, key=lambda s: -circ[s][1]):    # hosts are placed before guests
            host = placements[hosted[label]]
            hr, r = circ[hosted[label]][1], circ[label][1]
            placements[label] = Placement(label, host.board_id, host.x_mm + hr - r, host.y_mm + hr - r, False)
    rows = []
    for p in pieces:
        m, pl = grade_of[p.label], placements[p.label]
        w, h = _size(p.polygon)
        area = p.polygon.area / 1e6
        ring_in = circ.get(p.label, (None,))[0]
        kind = "disc" if ring_in == 0 else ("ring" if p.label in circ else "ring-strip")
        note = f"cut inside the hole of {in_hole[p.label]}" if p.label in in_hole else ""
        if nest_angle[p.label]:
            kind = "ring-sector"
            w, h = _size(affinity.rotate(p.polygon, nest_angle[p.label], origin=(0, 0)))
            note = f"sector; drawn in the sheet frame, nested turned {nest_angle[p.label]:.2f}°; butt-joint radially"
        if plan.sizing == "contain" and plan.shape == "sphere" and p.label in circ:
            note = (note + "; " if note else "") + "turn/sand bevelled faces to the shell spheres"
        rows.append(CutRow(p.label, kind, m.name, pl.board_id, pl.x_mm, pl.y_mm, pl.rotated, w, h,
                           p.thickness_mm, area, area * p.thickness_mm / 1e3 * m.density_kg_m3,
                           p.sheet_index, note))
    totals: dict[str, float] = {}
    for r in rows:
        totals[r.material] = totals.get(r.material, 0.0) + r.mass_kg
    totals = dict(sorted(totals.items())) | {"all": sum(totals.values())}
    boards: dict[str, set] = {}
    for pl in placements.values():
        boards.setdefault(pl.board_id.rsplit("-B", 1)[0], set()).add(pl.board_id)
    draws: tuple[Drawing, ...] = ()
    if drawings:
        per_sheet = {}
        for p in pieces:
            per_sheet.setdefault(p.sheet_index, []).append(p)
        draws = tuple(d for s in plan.sheets for d in
                      [_sheet_drawing(plan, s, per_sheet.get(s.index, []), grade_of, title)] +
                      [_ring_drawing(plan, s, p, grade_of[p.label], title) for p in per_sheet.get(s.index, [])])
    return FabPlanRings(tuple(pieces), placements, {}, draws,
                        tuple(sorted(rows, key=lambda r: (r.assembly_order, r.part))), totals,
                        {m: len(ids) for m, ids in sorted(boards.items())}, kerf, in_hole, saving)


def split_ring_sectors(piece: Piece, ring: RingPlan, board_w: float, board_l: float, kerf: float
                       ) -> tuple[list[Piece], list[float]]:
    """A ring (or disc) that fits no board is cut into the fewest equal sectors that do, with
    radial butt joints; neighbouring sheets are staggered by half a sector. Returns the pieces
    (sheet frame, labelled -a, -b, …) and the rotation (deg) that turns each sector's
    bisector to +Y for nesting (0 for a whole ring)."""
    x0, y0, x1, y1 = piece.cut_path(kerf).bounds
    if fits_board(x1 - x0, y1 - y0, board_w, board_l):
        return [piece], [0.0]
    ro, ri = ring.r_outer_mm * 1.001 + kerf, ring.r_inner_mm
    for k in range(2, 721):
        step = 2 * math.pi / k
        half = step / 2
        # bounding box of one sector turned to +Y: width 2·ro·sin(half) (or 2·ro), height ro − ri·cos(half)
        w = 2 * ro * math.sin(half) if half < math.pi / 2 else 2 * ro
        h = ro - (ri * math.cos(half) if half < math.pi / 2 else -ro)
        if not fits_board(w + kerf, h + kerf, board_w, board_l):
            continue
        if w * h > 2.0 * half * (ro * ro - ri * ri) and k < 720:     # bounding box < 2× the sector
            continue
        shift = 0.0 if piece.sheet_index % 2 else half
        parts, angles = [], []
        n = vertex_count(ring.r_outer_mm)
        rv = ring.r_outer_mm / math.cos(math.pi / n)
        for j in range(k):
            a0 = shift + j * step
            a1 = a0 + step
            m = max(2, math.ceil(n * step / (2 * math.pi)) + 1)
            ta = np.linspace(a0, a1, m)
            outer = np.column_stack([rv * np.cos(ta), rv * np.sin(ta)])
            inner = (np.column_stack([ri * np.cos(ta[::-1]), ri * np.sin(ta[::-1])]) if ri > 0
                     else np.zeros((1, 2)))
            sector = Polygon(np.vstack([outer, inner]))
            parts.append(Piece(f"{piece.label}-{_suffix(len(parts))}", piece.sheet_index, sector, piece.thickness_mm))
            angles.append(90.0 - math.degrees(a0 + half))
        return parts, angles
    raise ValueError(f"{piece.label}: no sector split fits a {board_w:g} × {board_l:g} mm board")


def _suffix(j: int) -> str:
    return chr(97 + j) if j < 26 else f"{chr(97 + j // 26 - 1)}{chr(97 + j % 26)}"


def _nest_in_holes(items: list[Piece], circ: dict[str, tuple[float, float]], kerf: float
                   ) -> tuple[dict[str, str], float]:
    """Greedy, largest first: each whole ring/disc goes into the smallest free ring hole of the
    same grade that holds it with the nesting gap; its own hole then becomes free. O(n log n)."""
    whole = sorted((p for p in items if p.label in circ), key=lambda p: (-circ[p.label][1], p.label))
    holes: list[tuple[float, str]] = []                 # sorted (usable radius, host label)
    hosted: dict[str, str] = {}
    saved = 0.0
    for p in whole:
        r_in, r_out = circ[p.label]
        need = r_out + kerf / 2 + NEST_SPACING_MM
        i = bisect.bisect_left(holes, (need, ""))
        if i < len(holes):
            _, host = holes.pop(i)
            hosted[p.label] = host
            saved += (2 * r_out + kerf + 2 * NEST_SPACING_MM) ** 2 / 1e6
        if r_in > 0:
            bisect.insort(holes, (r_in - kerf / 2, p.label))
    return hosted, saved


def _size(poly) -> tuple[float, float]:
    x0, y0, x1, y1 = poly.bounds
    return x1 - x0, y1 - y0


def _marks(drawing: Drawing, r: float, hole_mm: float) -> None:
    drawing.add_cross(0.0, 0.0, 10.0)                                    # lens axis / centre
    for x, y in ((r, 0), (-r, 0), (0, r), (0, -r)):                      # registration ticks at the rim
        drawing.marks.append([(x * 1.02 + 2 * np.sign(x), y * 1.02 + 2 * np.sign(y)), (x * 1.06 + 6 * np.sign(x), y * 1.06 + 6 * np.sign(y))])


def _sheet_drawing(plan: RingLayupPlan, sheet: RingSheet, pieces: list[Piece], grade_of, title: str) -> Drawing:
    d = Drawing(sheet.label)
    for p in pieces:
        d.add_polygon(p.cut_path(plan.kerf_mm))
    for ring in sheet.rings:
        a = math.radians(20 + 25 * (ring.shell_index % 7))
        rm = 0.5 * (ring.r_inner_mm + ring.r_outer_mm)
        d.texts.append((f"{ring.label[-7:]} {ring.material.name}", rm * math.cos(a) - 10, rm * math.sin(a), 3.0))
    _marks(d, max(sheet.radius_mm, 20.0), plan.registration_hole_mm)
    _title(d, [f"{title}  {sheet.label} of {plan.count}: z {sheet.z_min_mm:g} to {sheet.z_max_mm:g} mm, "
               f"thickness {sheet.thickness_mm:g} mm, {len(sheet.rings)} rings ({plan.sizing} sizing)",
               "assembly view: each ring is cut from its own grade (see the ring templates)"])
    return d


def _ring_drawing(plan: RingLayupPlan, sheet: RingSheet, piece: Piece, grade: Material, title: str) -> Drawing:
    d = Drawing(piece.label)
    d.add_polygon(piece.cut_path(plan.kerf_mm))
    ring = next(r for r in sheet.rings if piece.label.startswith(r.label))
    _marks(d, max(ring.r_outer_mm, 20.0), plan.registration_hole_mm)
    _title(d, [f"{title}  {piece.label} (sheet {sheet.label}, shell {ring.shell_index:02d})",
               f"grade {grade.name}: εr {grade.eps_r:.4g}, {grade.density_kg_m3:.4g} kg/m³, "
               f"board thickness {sheet.thickness_mm:g} mm",
               f"R out {ring.r_outer_mm:.2f} mm, R in {ring.r_inner_mm:.2f} mm; CUT = tool path "
               f"(kerf {plan.kerf_mm:g} mm)"])
    return d


def _title(d: Drawing, lines: list[str]) -> None:
    x0, y0, _, y1 = d.bounds()
    for k, text in enumerate(lines):
        d.texts.append((text, x0, y1 + 12 + 9 * (len(lines) - 1 - k), TEXT_HEIGHT_MM))
    d.add_check_bar(x0, y0 - 20)
