"""A cylindrical bifocal lens inside a parallel-plate waveguide with its H-plane sectoral horn
(seed-001 §3.1 FEM case: the n = 1.6 lens, 160 mm wide, between plates 3.4 mm apart at 37.5 GHz,
fed by an H-plane horn of input 7.2×3.4 mm and aperture 13×3.4 mm).

Frame: the synthesis frame of :mod:`antenna_cad.synthesis.bifocal` — (z, y) in the section plane,
z the axis from the feed plane, y transverse; the plates and the horn are that section extruded by
the plate spacing (the lens height). Drawings use the section gauge's frame: drawing x = y,
drawing y = z − ρ1 (illuminated vertex at 0).

Assumptions where the seed is silent (README): the horn's aperture centre sits on the design focus
O1 and its axis points at the illuminated vertex (ρ1, 0); without a given flare length the horn is
the optimum H-plane horn, aperture² = 3·λ·R with R the axial distance from the apex to the
aperture; the plates are the convex hull of the lens section and the horn, grown by the margin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely import affinity
from shapely.geometry import Polygon, box

from antenna_cad.fabrication.bifocal import section_polygon
from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.templates import Drawing
from antenna_cad.materials import Material
from antenna_cad.synthesis.bifocal import BifocalDesign
from antenna_cad.synthesis.checks import Check


@dataclass(frozen=True)
class Horn:
    """H-plane sectoral horn in the section plane: ``walls`` (its two side walls, one polygon of
    two parts) and ``channel`` (the air inside: feed guide plus flare), both in (z, y) mm."""
    aperture_centre: np.ndarray      # (z, y) = the design focus O1
    axis: np.ndarray                 # unit (z, y), toward the illuminated vertex
    input_width_mm: float
    aperture_width_mm: float
    flare_length_mm: float
    feed_length_mm: float
    wall_mm: float
    walls: Polygon
    channel: Polygon


def optimum_flare_mm(input_w: float, aperture_w: float, wavelength_mm: float) -> float:
    """Axial flare length of the optimum H-plane horn: apex-to-aperture R = A²/(3λ), the throat
    where the flare is as wide as the feed guide: l = R·(1 − a/A)."""
    return aperture_w**2 / (3.0 * wavelength_mm) * (1.0 - input_w / aperture_w)


def horn(design: BifocalDesign, spec, wavelength_mm: float) -> Horn:
    """The horn of ``spec`` (:class:`antenna_cad.spec.bifocal.HornSpec`) at O1, aimed at (ρ1, 0)."""
    a, A, f, w = spec.input_width_mm, spec.aperture_width_mm, spec.feed_length_mm, spec.wall_mm
    ln = spec.length_mm if spec.length_mm is not None else optimum_flare_mm(a, A, wavelength_mm)
    u0, u1 = -ln - f, 0.0                                     # local u along the axis, aperture at 0
    inner = Polygon([(u0, -a / 2), (-ln, -a / 2), (0.0, -A / 2), (0.0, A / 2), (-ln, a / 2), (u0, a / 2)])
    outer = inner.buffer(w, join_style=2, mitre_limit=10.0).intersection(box(u0, -A, u1, A))
    focus = design.foci_mm[0]
    axis = np.array([design.rho1_mm, 0.0]) - focus
    axis /= np.linalg.norm(axis)
    ang = float(np.degrees(np.arctan2(axis[1], axis[0])))

    def place(poly: Polygon) -> Polygon:
        return affinity.translate(affinity.rotate(poly, ang, origin=(0.0, 0.0)), *focus)

    return Horn(focus, axis, a, A, float(ln), f, w, place(outer.difference(inner)), place(inner))


def plate_outline(design: BifocalDesign, horn_: Horn | None, margin_mm: float) -> Polygon:
    """The plates in (z, y): convex hull of the lens section (and the horn), grown by the margin."""
    lens = lens_section_zy(design)
    shapes = lens if horn_ is None else lens.union(horn_.walls)
    return shapes.convex_hull.buffer(margin_mm, join_style=2)


def lens_section_zy(design: BifocalDesign) -> Polygon:
    """The lens section in (z, y)."""
    return affinity.translate(affinity.affine_transform(section_polygon(design), [0, 1, 1, 0, 0, 0]),
                              design.rho1_mm, 0.0)


def wall_parts(horn_: Horn) -> list[Polygon]:
    """The horn's side walls as separate polygons."""
    return list(getattr(horn_.walls, "geoms", [horn_.walls]))


def horn_clearance_check(design: BifocalDesign, horn_: Horn) -> Check:
    """The horn walls must not reach into the lens."""
    gap = float(horn_.walls.distance(lens_section_zy(design)))
    return Check.upper("horn_lens_clearance", -gap, 0.0, "mm", "horn walls into the lens by (negative: clear)")


def _drawing_xy(poly: Polygon, rho1: float) -> Polygon:
    """(z, y) → drawing (x = y, y = z − ρ1)."""
    return affinity.affine_transform(poly, [0, 1, 1, 0, 0, -rho1])


def plates_drawing(design: BifocalDesign, outline: Polygon, horn_: Horn | None, title: str,
                   spacing_mm: float, plate_mm: float) -> Drawing:
    """1:1 template of the plate (cut: its outline), with the lens section and the horn walls marked
    where they sit between the plates."""
    d = Drawing("plates")
    d.add_polygon(_drawing_xy(outline, design.rho1_mm))
    marks = [lens_section_zy(design)] + ([] if horn_ is None else wall_parts(horn_))
    for poly in marks:
        d.marks.append([(round(x, 4), round(y, 4)) for x, y in _drawing_xy(poly, design.rho1_mm).exterior.coords])
    x0, y0, x1, y1 = _drawing_xy(outline, design.rho1_mm).bounds
    fz, fy = design.foci_mm[0]
    d.add_cross(fy, fz - design.rho1_mm, 5.0)
    horn_txt = "" if horn_ is None else (f"; H-plane horn {horn_.input_width_mm:g} → {horn_.aperture_width_mm:g} mm, "
                                         f"flare {horn_.flare_length_mm:.2f} mm, aperture centre on the design focus (cross)")
    d.add_title([f"{title}: parallel plate 1:1 (cut 2, top and bottom), {plate_mm:g} mm thick, spacing "
                 f"{spacing_mm:g} mm; marked: the lens section and the horn walls{horn_txt}"], x0, y1 + 20.0)
    d.add_check_bar(x0, y0 - 30.0)
    return d


def plate_rows(outline: Polygon, horn_: Horn | None, metal: Material, plate_mm: float,
               spacing_mm: float) -> list[CutRow]:
    """Cut-list rows: the two plates and the horn walls (metal)."""
    minx, miny, maxx, maxy = outline.bounds
    kg = outline.area * plate_mm / 1e9 * metal.density_kg_m3
    rows = [CutRow(f"plate-{s}", "metal-plate", metal.name, "stock", 0, 0, False, maxy - miny, maxx - minx,
                   plate_mm, outline.area / 1e6, kg, 1 if s == "bottom" else 3, "plates template")
            for s in ("bottom", "top")]
    if horn_ is not None:
        hx0, hy0, hx1, hy1 = horn_.walls.bounds
        hk = horn_.walls.area * spacing_mm / 1e9 * metal.density_kg_m3
        rows.append(CutRow("horn", "metal-horn", metal.name, "stock", 0, 0, False, hy1 - hy0, hx1 - hx0, spacing_mm,
                           horn_.walls.area / 1e6, hk, 2, "H-plane horn side walls between the plates "
                           "(positions marked on the plates template)"))
    return rows
