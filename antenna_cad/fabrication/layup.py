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
the stack follows the profile to within the chord's sagitta and needs no sanding; ``radius_mm``
stays the back face's (largest) radius, ``front_radius_mm`` is the feed-side face's.

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

    @property
    def tapered(self) -> bool:
        return self.front_radius_mm is not None

    def radius_at_z(self, z) -> np.ndarray:
        """The rim's radius at depth z (the cone of a taper-cut sheet, else the disc radius)."""
        z = np.asarray(z, float)
        if not self.tapered:
            return np.full_like(z, self.radius_mm)
        u = np.clip((z - self.z_min_mm) / self.thickness_mm, 0.0, 1.0)
        return self.front_radius_mm + u * (self.radius_mm - self.front_radius_mm)

    def hole_depth_mm(self, hole: Hole) -> float:
        """Depth of a dowel hole drilled from the back face: through the sheet, or blind where the
        hole would break through a taper-cut rim (it stops DOWEL_EDGE_CLEARANCE_MM inside the cone)."""
        reach = math.hypot(hole.x_mm, hole.y_mm) + hole.diameter_mm / 2 + DOWEL_EDGE_CLEARANCE_MM
        if not self.tapered or self.front_radius_mm >= reach:
            return self.thickness_mm
        u = (reach - self.front_radius_mm) / max(self.radius_mm - self.front_radius_mm, 1e-9)
        return max(0.0, self.thickness_mm * (1.0 - u))

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
    lens radius within the slab (``radius_at`` is then unused). ``z_origin_mm`` is the z of the lens
    vertex in the lens's own frame: sheet i spans [z0 + (i−1)·t, z0 + i·t]; ``radius_at`` and
    ``max_radius_in`` take depths relative to that vertex. ``edge="taper"`` cuts every rim as the
    cone through r(min(z, d)) at the sheet's two faces (it needs ``radius_at``).
    """
    if edge == "taper" and max_radius_in is not None:
        raise ValueError("fabrication.edge: taper needs a lens whose radius grows from the vertex to the "
                         "flat face (the collimator); this lens's radius is not monotonic")
    t = sheet_thickness_mm
    count = max(1, math.ceil(lens_thickness_mm / t - 1e-9))
    R = lens_radius_mm
    width = pedestal_width_mm if pedestal_width_mm is not None else 0.6 * 2 * R
    if max_radius_in is None:
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
    fronts = ([float(radius_at(min((i - 1) * t, lens_thickness_mm))) for i in range(1, count + 1)]
              if edge == "taper" else [None] * count)
    sheets = tuple(SheetPlan(index=i, z_min_mm=z0 + (i - 1) * t, z_max_mm=z0 + i * t, radius_mm=r_i,
                             has_neck=joining == "neck" and r_i < R - 1e-9,
                             lens_dowels=lens_dowels, foot_dowels=foot_dowels, front_radius_mm=f_i)
                   for i, (r_i, f_i) in enumerate(zip(radii, fronts), start=1))
    return LayupPlan(lens_radius_mm=R, sheet_thickness_mm=t, lens_thickness_mm=lens_thickness_mm,
                     back_slab_mm=count * t - lens_thickness_mm, pedestal_width_mm=width,
                     pedestal_height_mm=pedestal_height_mm, neck_width_mm=neck_width_mm,
                     joining=joining, kerf_mm=kerf_mm, board_width_mm=board_width_mm,
                     board_length_mm=board_length_mm, sheets=sheets, z_origin_mm=z0, edge=edge)
