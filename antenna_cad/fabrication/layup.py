"""Slicing an axisymmetric lens into stock sheets with a pedestal (seed-000 §6.2), as plain numbers.

The plan is the single description that both the 3-D model (``geometry``) and the 2-D templates
(``fabrication.templates``) render, so a sheet's solid and its cutting outline cannot disagree.

Sheet frame: the sheet plane is (x, y) with +Y up, the lens axis is +Z (DESIGN.md). Sheets are
anchored at the lens vertex: sheet i spans z ∈ [(i−1)·t, i·t] (digest §6.2 step 4, §7.4 case 20).
When the lens thickness d is not a multiple of t, the remainder N·t − d stays on the flat side as
a uniform back slab: it adds only a constant phase (digest §7.3), so the flat face z = N·t is a
sheet boundary and sanding never touches it. Each sheet's lens part is the disc of radius
r(min(i·t, d)) — the smallest disc containing the ideal lens inside that slab — so sanding
only ever removes material. With ``edge: taper`` the rim is instead the cone through the lens
profile at the sheet's two faces, r(min(z, d)) at z = (i−1)·t and i·t (a hot-wire ruled surface):
the stack follows the profile to within the chord's sagitta and needs no sanding;
``front_radius_mm`` and ``back_radius_mm`` are the cone's radii on the feed-side and antenna-side
faces, ``radius_mm`` the larger (the disc the cone is cut from). A lens whose radius falls again
(the bifocal lens past its rim) has cones narrowing toward the back; their dowel holes are drilled
from the front face.

Pedestal (digest §6.2 [INTERPRETATION], chosen here): a foot under every sheet, ``w`` wide,
from y = −R − h up to the aperture circle r = R (a cradle the lens rests in), entirely outside the
aperture cylinder. A sheet whose disc reaches r = R is one piece with its foot. Smaller discs are
joined either by foam **dowels** (same material; disc and foot are two pieces, each pinned to its
neighbours — nothing added in the aperture) or by a **neck** (one piece; a strip of foam inside the
aperture, reported with its volume and phase cost).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

DOWEL_EDGE_CLEARANCE_MM = 10.0


@dataclass(frozen=True)
class Hole:
    x_mm: float
    y_mm: float
    diameter_mm: float


@dataclass(frozen=True)
class SheetPlan:
    index: int                  # 1 = nearest the feed
    z_min_mm: float
    z_max_mm: float
    radius_mm: float            # lens disc radius (nominal part, before kerf)
    has_neck: bool
    lens_dowels: tuple[Hole, ...]
    foot_dowels: tuple[Hole, ...]
    front_radius_mm: float | None = None    # taper-cut rim: radius at z_min (None: vertical edge)
    back_radius_mm: float | None = None     # taper-cut rim: radius at z_max (None: radius_mm)

    @property
    def tapered(self) -> bool:
        return self.front_radius_mm is not None

    @property
    def cone_mm(self) -> tuple[float, float]:
        """(front, back) radius of the rim: the cone's two faces (both the disc's when vertical)."""
        if not self.tapered:
            return self.radius_mm, self.radius_mm
        return self.front_radius_mm, self.radius_mm if self.back_radius_mm is None else self.back_radius_mm

    @property
    def drilled_from_front(self) -> bool:
        """Dowel holes go in from the feed-side face (a cone narrowing toward the back), else the back."""
        front, back = self.cone_mm
        return front > back

    def radius_at_z(self, z) -> np.ndarray:
        """The rim's radius at depth z (the cone of a taper-cut sheet, else the disc radius)."""
        z = np.asarray(z, float)
        front, back = self.cone_mm
        u = np.clip((z - self.z_min_mm) / self.thickness_mm, 0.0, 1.0)
        return front + u * (back - front)

    def hole_depth_mm(self, hole: Hole) -> float:
        """Depth of a dowel hole drilled from the wider face (the back, unless
        ``drilled_from_front``): through the sheet, or blind where the hole would break through a
        taper-cut rim (it stops DOWEL_EDGE_CLEARANCE_MM inside the cone); a foot's holes go through."""
        centre = math.hypot(hole.x_mm, hole.y_mm)
        reach = centre + hole.diameter_mm / 2 + DOWEL_EDGE_CLEARANCE_MM
        wide, narrow = sorted(self.cone_mm, reverse=True)
        if narrow >= reach or centre > wide:        # inside the cone at both faces, or in the foot
            return self.thickness_mm
        u = (wide - reach) / max(wide - narrow, 1e-9)
        return max(0.0, self.thickness_mm * u)

    @property
    def label(self) -> str:
        return f"sheet-{self.index:02d}"

    @property
    def thickness_mm(self) -> float:
        return self.z_max_mm - self.z_min_mm

    def manifest_extra(self) -> dict:
        """Kind-specific manifest fields of a sheet (the Luneburg ring sheet adds its rings)."""
        return {}


class Cradle:
    """Height range of the pedestal feet — a cradle from ``pedestal_height_mm`` below the lens up
    to the aperture circle — for a plan with ``lens_radius_mm``, ``pedestal_width_mm`` and
    ``pedestal_height_mm`` (this layup, and the Luneburg ring layup's stand)."""

    @property
    def foot_bottom_y_mm(self) -> float:
        return -self.lens_radius_mm - self.pedestal_height_mm

    @property
    def foot_corner_y_mm(self) -> float:
        """y where the foot's sides meet the aperture circle (top corners of the cradle)."""
        return -math.sqrt(self.lens_radius_mm**2 - (self.pedestal_width_mm / 2) ** 2)


@dataclass(frozen=True)
class LayupPlan(Cradle):
    lens_radius_mm: float
    sheet_thickness_mm: float
    lens_thickness_mm: float        # synthesized (hyperbolic part)
    back_slab_mm: float             # N·t − d, uniform flat slab on the shadow side
    pedestal_width_mm: float
    pedestal_height_mm: float
    neck_width_mm: float
    joining: str
    kerf_mm: float
    board_width_mm: float
    board_length_mm: float
    sheets: tuple[SheetPlan, ...]
    z_origin_mm: float = 0.0        # z of the first sheet's feed-side face (the lens vertex)
    edge: str = "stepped"           # "stepped" (vertical rims) or "taper" (cones)

    @property
    def count(self) -> int:
        return len(self.sheets)

    @property
    def stack_thickness_mm(self) -> float:
        return self.sheets[-1].z_max_mm - self.z_origin_mm



def plan_layup(*, radius_at, lens_thickness_mm: float, lens_radius_mm: float,
               sheet_thickness_mm: float, pedestal_height_mm: float,
               pedestal_width_mm: float | None, joining: str, dowel_diameter_mm: float,
               neck_width_mm: float, kerf_mm: float, board_width_mm: float,
               board_length_mm: float, max_radius_in=None, z_origin_mm: float = 0.0,
               edge: str = "stepped") -> LayupPlan:
    """Slice a lens of revolution whose radius at depth z is ``radius_at(z)`` into sheets.

    ``radius_at`` must be non-decreasing in z on [0, lens_thickness] (true for the collimator).
    Lenses whose radius is not monotonic (the bifocal lens: it rises along the illuminated face to
    the rim and falls along the shadow face) pass ``max_radius_in(z_lo, z_hi)`` instead, the largest
    lens radius within the slab (``radius_at`` then gives the taper's cones only). ``z_origin_mm`` is the z of the lens
    vertex in the lens's own frame: sheet i spans [z0 + (i−1)·t, z0 + i·t]; ``radius_at`` and
    ``max_radius_in`` take depths relative to that vertex. ``edge="taper"`` cuts every rim as the
    cone through r(min(z, d)) at the sheet's two faces (it needs ``radius_at``, the lens's section
    radius at any depth, also where it falls again).
    """
    if edge == "taper" and radius_at is None:
        raise ValueError("fabrication.edge: taper needs the lens radius at every depth; this lens has none")
    t = sheet_thickness_mm
    count = max(1, math.ceil(lens_thickness_mm / t - 1e-9))
    R = lens_radius_mm
    width = pedestal_width_mm if pedestal_width_mm is not None else 0.6 * 2 * R
    if edge == "taper":
        faces = [float(radius_at(min(i * t, lens_thickness_mm))) for i in range(count + 1)]
        cones = list(zip(faces[:-1], faces[1:]))
        radii = [max(c) for c in cones]
    elif max_radius_in is None:
        radii = [float(radius_at(min(i * t, lens_thickness_mm))) for i in range(1, count + 1)]
    else:
        radii = [float(max_radius_in((i - 1) * t, min(i * t, lens_thickness_mm))) for i in range(1, count + 1)]
    dowel_r = min(radii) / 2            # inside every disc (the first one for the collimator)
    if dowel_r - dowel_diameter_mm / 2 < DOWEL_EDGE_CLEARANCE_MM:
        raise ValueError(f"fabrication.dowel_diameter_mm: {dowel_diameter_mm:g} mm dowels do not fit "
                         f"in the smallest sheet disc (radius {min(radii):.1f} mm); use thicker sheets "
                         f"or thinner dowels")
    lens_dowels = tuple(Hole(round(dowel_r * math.cos(a), 6), round(dowel_r * math.sin(a), 6),
                             dowel_diameter_mm) for a in (0.25 * math.pi, 0.75 * math.pi,
                                                          1.25 * math.pi, 1.75 * math.pi))
    foot_dowels = tuple(Hole(x, -R - pedestal_height_mm / 2, dowel_diameter_mm)
                        for x in (-width / 4, width / 4))
    z0 = z_origin_mm
    if edge != "taper":
        cones = [(None, None)] * count
    sheets = tuple(SheetPlan(index=i, z_min_mm=z0 + (i - 1) * t, z_max_mm=z0 + i * t, radius_mm=r_i,
                             has_neck=joining == "neck" and r_i < R - 1e-9,
                             lens_dowels=lens_dowels, foot_dowels=foot_dowels, front_radius_mm=f_i, back_radius_mm=b_i)
                   for i, (r_i, (f_i, b_i)) in enumerate(zip(radii, cones), start=1))
    return LayupPlan(lens_radius_mm=R, sheet_thickness_mm=t, lens_thickness_mm=lens_thickness_mm,
                     back_slab_mm=count * t - lens_thickness_mm, pedestal_width_mm=width,
                     pedestal_height_mm=pedestal_height_mm, neck_width_mm=neck_width_mm,
                     joining=joining, kerf_mm=kerf_mm, board_width_mm=board_width_mm,
                     board_length_mm=board_length_mm, sheets=sheets, z_origin_mm=z0, edge=edge)
