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

Taper-cut (``edge: taper``, sphere): each ring is cut from its ``contain`` blank by a hot wire, its
outer edge the cone through the outer sphere at the sheet's two faces, sqrt(max(r_out² − z², 0)) at
z = z_lo and z_hi, its inner edge the cone through the inner sphere there (``cone_outer_mm``,
``cone_inner_mm``): the rings follow the spheres to within the chords' sagitta, with no turning.

A ring whose cut path fits no board is cut into equal sectors with radial butt joints,
staggered by half a sector in neighbouring sheets (planned here, so the registration holes can
keep clear of the joints).

Registration (seed-002 §5.1 item 5, "registration holes through stacked sheets"): across every
joint between sheets k and k+1, each shell crossed by both sheets gets three dowels at 120° on
one circle, in blind holes drilled ``depth`` = min(t/2, 2·Ø) into the joint faces of both sheets
(top face of sheet k, bottom face of sheet k+1); the pattern turns by 60° from one joint to the
next. The circle is the middle of the band of radii where a dowel lies in both rings and
(``contain``, rings turned to the spheres) inside its shell over its length; through the lens's
outer surface turning trims it with the rings. The dowels are cut from the shell's own grade, so
they leave every layer's εr unchanged. A Luneburg sphere has no region outside the aperture (its
beam scans over the whole sphere), which is why the holes are made electrically invisible
instead of being moved out of the ray path; they stay off the axis and off sector joints. A
cylinder (parallel-plate) lens is sliced along its axis and its rings are the layer radii; its
dowels are pins through the whole stack at each ring's mid-radius that also locate the rings in
matching holes of the plates.

Pure numpy/shapely: no CAD imports. Outlines, kerf offsets and nesting sizes are analytic, so
the cost is linear in sheets × rings (+ sector pieces); polygons are built only for drawings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from antenna_cad.fabrication.layup import Cradle
from antenna_cad.fabrication.outline import CHORD_TOL_MM, NEST_SPACING_MM, fits_board
from antenna_cad.materials import Material

REG_CLEARANCE_MM = 3.0           # foam kept between a dowel hole and a ring edge or sector joint
DOWEL_PATTERN_DEG = (90.0, 210.0, 330.0)


@dataclass(frozen=True)
class DowelHole:
    """A registration hole in the sheet frame: ``face`` "top" (z_max) or "bottom" (z_min) for a
    blind hole ``depth_mm`` deep, "through" for a hole cut through the ring."""
    x_mm: float
    y_mm: float
    diameter_mm: float
    depth_mm: float
    face: str


@dataclass(frozen=True)
class RingPlan:
    label: str               # "sheet-03-ring-02" (ring of shell 2 in sheet 3)
    sheet_index: int
    shell_index: int
    r_inner_mm: float        # 0 for a disc
    r_outer_mm: float
    material: Material       # the shell's foam grade
    sectors: int = 1         # equal sectors with radial butt joints (1: one piece)
    sector_start_rad: float = 0.0   # angle of the first radial joint, sheet frame, from +X
    holes: tuple[DowelHole, ...] = ()    # registration dowel holes
    cone_outer_mm: tuple[float, float] | None = None    # taper-cut: outer edge at (z_min, z_max)
    cone_inner_mm: tuple[float, float] | None = None    # taper-cut: inner edge at (z_min, z_max)

    @property
    def joint_angles_rad(self) -> np.ndarray:
        if self.sectors == 1:
            return np.empty(0)
        return self.sector_start_rad + 2 * math.pi * np.arange(self.sectors) / self.sectors


@dataclass(frozen=True)
class Dowel:
    """A registration dowel of the shell's grade through ``sheets`` (the plates too, cylinder)."""
    shell_index: int
    sheets: tuple[int, ...]
    x_mm: float
    y_mm: float
    diameter_mm: float
    length_mm: float
    material: Material


@dataclass(frozen=True)
class RingSheet:
    index: int
    label: str
    z_min_mm: float
    z_max_mm: float
    rings: tuple[RingPlan, ...]
    has_neck: bool = False
    foot_holes: tuple[DowelHole, ...] = ()     # stand foot's dowel holes (with a stand)

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
                           "r_outer_mm": r.r_outer_mm, "material": r.material.name,
                           "sectors": r.sectors,
                           "holes": [{"x_mm": h.x_mm, "y_mm": h.y_mm, "diameter_mm": h.diameter_mm,
                                      "depth_mm": h.depth_mm, "face": h.face} for h in r.holes]}
                          for r in self.rings]}


@dataclass(frozen=True)
class RingLayupPlan(Cradle):
    sheets: tuple[RingSheet, ...]
    sheet_thickness_mm: float
    sizing: str
    shape: str
    kerf_mm: float
    board_width_mm: float
    board_length_mm: float
    registration_hole_mm: float
    dropped_caps: int        # mid_plane: shell caps that miss their sheet's mid-plane; taper: caps inside a disc
    dowels: tuple[Dowel, ...] = ()
    undowelled_joints: int = 0   # (joint, shell) pairs whose band is too thin for a dowel
    lens_radius_mm: float = 0.0
    pedestal_width_mm: float | None = None     # the stand (None: none); names as ``layup.LayupPlan``
    pedestal_height_mm: float | None = None
    stand_material: Material | None = None
    edge: str = "stepped"                      # "stepped" (vertical ring edges) or "taper" (cones)

    @property
    def count(self) -> int:
        return len(self.sheets)

    @property
    def rings(self) -> list[RingPlan]:
        return [r for s in self.sheets for r in s.rings]


def sphere_radius(r_sphere: float, z: float) -> float:
    """The sphere's radius at height z (0 beyond it): a taper-cut ring's edge on a face."""
    return math.sqrt(max(r_sphere * r_sphere - z * z, 0.0))


def _cones(r_in: float, r_out: float, z_lo: float, z_hi: float) -> dict:
    """The cone fields of a taper-cut ring of the shell (r_in, r_out) in the slab [z_lo, z_hi]."""
    return {"cone_outer_mm": (sphere_radius(r_out, z_lo), sphere_radius(r_out, z_hi)),
            "cone_inner_mm": (sphere_radius(r_in, z_lo), sphere_radius(r_in, z_hi))}


def taper_cones(ri: np.ndarray, ro: np.ndarray, z_lo: float, z_hi: float, kerf_mm: float) -> tuple[list, int]:
    """Per shell the cone fields of its taper-cut ring in the slab (None: dropped), and how many
    were dropped. A wire cuts only through holes: where an inner sphere's pole lies in the slab
    (its cone closes, or opens less than the kerf, on a face), that ring is cut as a disc and
    the smaller shells' caps inside it are dropped (the disc's grade fills them; reported)."""
    cones: list = [_cones(float(a), float(b), z_lo, z_hi) for a, b in zip(ri, ro)]
    blind = [j for j, c in enumerate(cones)
             if max(c["cone_inner_mm"]) > 1e-9 and min(c["cone_inner_mm"]) <= max(kerf_mm, 1e-9)]
    if not blind:
        return cones, 0
    core = max(blind)
    cones[core]["cone_inner_mm"] = (0.0, 0.0)
    dropped = sum(max(cones[j]["cone_outer_mm"]) > 1e-9 for j in range(core))
    return [None] * core + cones[core:], dropped


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


# ---------------------------------------------------------------- sectors (analytic outlines)

def sector_box(r_in: float, r_out: float, half_rad: float, kerf_mm: float) -> tuple[float, float]:
    """Bounding box (w, h) of a sector's cut path turned so its bisector points to +Y.

    The cut path is the sector offset outward by kerf/2 with mitred corners: arcs of radius
    r_out + kerf/2 (+ the chord tolerance of the circumscribed polygon) and r_in − kerf/2, radial
    edges moved kerf/2 outward (a disc sector's apex moves to kerf/2 / sin(half) below the
    centre). ``half_rad`` = π gives the whole ring."""
    c = kerf_mm / 2
    ro = r_out + c + CHORD_TOL_MM
    if half_rad >= math.pi - 1e-12:
        return 2 * ro, 2 * ro
    hollow = r_in - c > c
    s_o = math.sqrt(ro * ro - c * c)
    sh, ch = math.sin(half_rad), math.cos(half_rad)
    # right edge (the left one mirrors it in x): direction (sin h, cos h), outward normal (cos h, −sin h)
    xo, yo = s_o * sh + c * ch, s_o * ch - c * sh
    if hollow:
        s_i = math.sqrt((r_in - c) ** 2 - c * c)
        x_in, y_low = s_i * sh + c * ch, min(yo, s_i * ch - c * sh)
    elif half_rad < math.pi / 2 - 1e-12:
        x_in, y_low = 0.0, min(yo, -c / sh)              # apex of the offset disc sector
    else:
        x_in, y_low = 0.0, yo
    x_ext = ro if yo < 0 else max(xo, x_in)              # the outer arc passes ±X
    return 2 * x_ext, ro - y_low


def sector_count(r_in: float, r_out: float, board_w: float, board_l: float, kerf_mm: float) -> int:
    """1 if the ring's cut path fits a board, else the fewest equal sectors that fit one and whose
    bounding box is at most twice the sector's area (thin rings: short arcs, less waste)."""
    if fits_board(*sector_box(r_in, r_out, math.pi, kerf_mm), board_w, board_l):
        return 1
    reach = (max(board_w, board_l) - 2 * NEST_SPACING_MM) / (2 * (r_out + kerf_mm))
    first = 2 if reach >= 1 else max(2, math.floor(math.pi / math.asin(reach)))   # chord ≤ the board
    for k in range(first, 721):
        half = math.pi / k
        w, h = sector_box(r_in, r_out, half, kerf_mm)
        if fits_board(w, h, board_w, board_l) and (w * h <= 2.0 * half * (r_out**2 - r_in**2) or k == 720):
            return k
    raise ValueError(f"ring R {r_out:.0f} mm: no sector split fits a {board_w:g} × {board_l:g} mm board")


# ---------------------------------------------------------------- the plan

def plan_rings(r_inner_mm, r_outer_mm, materials: list[Material], *, shape: str, height_mm: float | None,
               sheet_thickness_mm: float, sizing: str, kerf_mm: float, board_width_mm: float,
               board_length_mm: float, registration_hole_mm: float, pedestal_height_mm: float | None = None,
               pedestal_width_mm: float | None = None, edge: str = "stepped") -> RingLayupPlan:
    """Sheets, their rings (radii, grade, sector split, dowel holes, cones when ``edge`` is
    "taper"), the dowels, and the stand."""
    ri, ro = np.asarray(r_inner_mm, float), np.asarray(r_outer_mm, float)
    span = 2.0 * ro[-1] if shape == "sphere" else float(height_mm)
    t = sheet_thickness_mm
    n = max(1, math.ceil(span / t - 1e-9))
    z0 = -0.5 * n * t
    sheets, dropped = [], 0
    for k in range(n):
        z_lo, z_hi = z0 + k * t, z0 + (k + 1) * t
        cones: list = [{}] * len(ro)
        if shape == "sphere":
            inner, outer = ring_radii(ri, ro, z_lo, z_hi, sizing)
            if edge == "taper":
                cones, lost = taper_cones(ri, ro, z_lo, z_hi, kerf_mm)
                dropped += lost
            if sizing == "mid_plane":
                dropped += int(np.sum((outer <= 1e-9) & (ring_radii(ri, ro, z_lo, z_hi, "contain")[1] > 1e-9)))
        else:
            inner, outer = ri, ro
        label = f"sheet-{k + 1:02d}"
        rings = []
        for j in range(len(ro)):
            if outer[j] <= 1e-9 or outer[j] - inner[j] <= 1e-9 or cones[j] is None:
                continue
            r_in = 0.0 if cones[j] and max(cones[j]["cone_inner_mm"]) == 0.0 else float(inner[j])
            parts = sector_count(r_in, float(outer[j]), board_width_mm, board_length_mm, kerf_mm)
            start = 0.0 if k % 2 == 0 or parts == 1 else math.pi / parts      # staggered joints
            rings.append(RingPlan(f"{label}-ring-{j + 1:02d}", k + 1, j + 1, r_in, float(outer[j]),
                                  materials[j], parts, start, **cones[j]))
        sheets.append(RingSheet(k + 1, label, z_lo, z_hi, tuple(rings)))
    sheets, dowels, missing = _registration(sheets, ri, ro, shape, sizing, registration_hole_mm, kerf_mm)
    R = float(ro[-1])
    width = None if pedestal_height_mm is None else (pedestal_width_mm or 1.2 * R)
    if width is not None:
        sheets, feet = _stand_dowels(sheets, R, width, pedestal_height_mm, registration_hole_mm, materials[-1])
        dowels += feet
    return RingLayupPlan(tuple(sheets), t, sizing, shape, kerf_mm, board_width_mm, board_length_mm,
                         registration_hole_mm, dropped, tuple(dowels), missing, R, width, pedestal_height_mm,
                         materials[-1] if width is not None else None, edge)


def _stand_dowels(sheets: list[RingSheet], R: float, width: float, height: float, d: float, grade: Material
                  ) -> tuple[list[RingSheet], list[Dowel]]:
    """Two dowels per joint between consecutive feet, at ±w/4 halfway down the foot, in blind
    holes as the rings'."""
    if d <= 0:
        return sheets, []
    holes: dict[int, list[DowelHole]] = {s.index: [] for s in sheets}
    dowels = []
    y = -R - height / 2
    for a, b in zip(sheets, sheets[1:]):
        depth = min(0.5 * min(a.thickness_mm, b.thickness_mm), 2 * d)
        for x in (-width / 4, width / 4):
            holes[a.index].append(DowelHole(x, y, d, depth, "top"))
            holes[b.index].append(DowelHole(x, y, d, depth, "bottom"))
            dowels.append(Dowel(0, (a.index, b.index), x, y, d, 2 * depth, grade))
    return [RingSheet(s.index, s.label, s.z_min_mm, s.z_max_mm, s.rings, s.has_neck, tuple(holes[s.index]))
            for s in sheets], dowels


def _registration(sheets: list[RingSheet], ri: np.ndarray, ro: np.ndarray, shape: str, sizing: str, d: float,
                  kerf: float) -> tuple[list[RingSheet], list[Dowel], int]:
    """Dowel holes (module docstring): per joint and shared shell, three at 120° on the middle of
    the band of radii where a dowel lies in both rings and, once the rings are turned to the
    spheres (``contain``), inside its shell along its length — except through the lens surface,
    where turning trims the dowel with the rings (it must still reach the joint plane inside
    the lens). Nudged off sector joints."""
    if d <= 0:
        return sheets, [], 0
    by_label = {r.label: r for s in sheets for r in s.rings}
    holes: dict[str, list[DowelHole]] = {label: [] for label in by_label}
    dowels, missing = [], 0
    if shape == "sphere":
        joints = [(k, (sheets[k - 1], sheets[k])) for k in range(1, len(sheets))]
    else:
        joints = [(0, tuple(sheets))]                  # through pins, also into the plates
    turned = shape == "sphere" and sizing == "contain"
    for k, members in joints:
        if shape == "sphere":
            z_joint = members[0].z_max_mm
            depth = min(0.5 * min(s.thickness_mm for s in members), 2 * d)
            z_lo, z_hi, faces = z_joint - depth, z_joint + depth, ("top", "bottom")
        else:
            z_lo, z_hi = members[0].z_min_mm, members[-1].z_max_mm
            depth, faces = members[0].thickness_mm, ("through",) * len(members)
        z_near = 0.0 if z_lo <= 0.0 <= z_hi else min(abs(z_lo), abs(z_hi))
        z_far = max(abs(z_lo), abs(z_hi))
        for j in range(len(ro)):
            rings = [by_label.get(f"{s.label}-ring-{j + 1:02d}") for s in members]
            if any(r is None for r in rings):
                continue
            band_in = max(r.r_inner_mm for r in rings)
            band_out = min(r.r_outer_mm for r in rings)
            if turned:
                band_in = max(band_in, math.sqrt(max(ri[j] ** 2 - z_near**2, 0.0)))
                z_out = abs(z_joint) if j == len(ro) - 1 else z_far
                band_out = min(band_out, math.sqrt(max(ro[j] ** 2 - z_out**2, 0.0)))
            if band_out - band_in < d + 2 * REG_CLEARANCE_MM:
                missing += 1
                continue
            rho = 0.5 * (band_in + band_out)
            cuts = np.concatenate([r.joint_angles_rad for r in rings])
            gap = (d / 2 + REG_CLEARANCE_MM + kerf / 2) / rho
            for base in DOWEL_PATTERN_DEG:
                a = _clear_of(math.radians(base + 60.0 * (k % 2)), cuts, gap)
                if a is None:
                    continue
                x, y = round(rho * math.cos(a), 6), round(rho * math.sin(a), 6)
                if any(math.hypot(x - h.x_mm, y - h.y_mm) < d + REG_CLEARANCE_MM for r in rings for h in holes[r.label]):
                    continue
                for r, face in zip(rings, faces):
                    holes[r.label].append(DowelHole(x, y, d, depth, face))
                dowels.append(Dowel(j + 1, tuple(s.index for s in members), x, y, d, z_hi - z_lo, rings[0].material))
    out = [RingSheet(s.index, s.label, s.z_min_mm, s.z_max_mm,
                     tuple(replace(r, holes=tuple(holes[r.label])) for r in s.rings),
                     s.has_neck) for s in sheets]
    return out, dowels, missing


def _clear_of(angle: float, cuts: np.ndarray, gap: float) -> float | None:
    """``angle`` moved the least so it is at least ``gap`` (rad) from every angle in ``cuts``;
    None if the joints leave no room."""
    if cuts.size == 0:
        return angle
    for _ in range(3):
        delta = (angle - cuts + math.pi) % (2 * math.pi) - math.pi
        i = int(np.argmin(np.abs(delta)))
        if abs(delta[i]) >= gap - 1e-12:
            return angle
        angle += math.copysign(gap - abs(delta[i]), delta[i] if delta[i] != 0 else 1.0)
    delta = (angle - cuts + math.pi) % (2 * math.pi) - math.pi
    return angle if np.min(np.abs(delta)) >= gap - 1e-9 else None
