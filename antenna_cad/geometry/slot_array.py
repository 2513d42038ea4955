"""Solids of the waveguide-slot array (seed-003): guides, beam-former plates, mirrors, lens, horns.

Frame: x across the guides, y along them, z up (broadside). The guide layer sits on the top
beam-former plate (z = 0); beam-former layers and plates stack downward. Per guide: a body
(bottom, side and end walls), a slotted lid — one planar face with the slots as inner wires,
extruded once (DESIGN.md pitfalls: no per-slot 3-D booleans; small faces, separate parts), so the
cost is linear in the slot count —, the dielectric core and, for a matched termination, the
absorber wedge in front of the end wall. Mirrors and lens are C¹ splines through the synthesised
points; the horns are hollow metal bodies in the feed layer whose E-plane walls continue the
plates (the plates are notched along the horn apertures: :mod:`antenna_cad.geometry.slot_layout`).
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.geometry import kernel
from antenna_cad.geometry.model import Model, ModelPart, SlottedPrism
from antenna_cad.geometry.slot_layout import (GuideExtent, PartSizes, Stack, clip_curve, core_and_load_rings,
                                              coupling_edge, end_overlap_mm, guide_extent, horn_checks,
                                              horn_outlines, layer_indices, mirror_back_sign, plate_polygon)
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.slot_array import Curve, SlotArrayDesign, offset_curve

SPLINE_POINTS = 61        # C¹ spline knots through the synthesised points (with their tangents)


def _knots(curve: Curve, z: float, reverse: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The spline's knots (m, 3) and tangents (m, 3) in the plane z, end to start if ``reverse``."""
    n = len(curve.points_mm)
    idx = np.unique(np.linspace(0, n - 1, min(n, SPLINE_POINTS)).round().astype(int))
    pts = np.column_stack([curve.points_mm[idx], np.full(len(idx), z)])
    tan = np.column_stack([curve.tangents[idx], np.zeros(len(idx))])
    return (pts[::-1], -tan[::-1]) if reverse else (pts, tan)


def _spline(curve: Curve, z: float, reverse: bool = False):
    return kernel.spline(*_knots(curve, z, reverse))


def modelled_curve(curve: Curve, n_samples: int = 4001) -> Curve:
    """The C¹ spline the model extrudes for ``curve`` (:func:`_spline`), sampled densely: the
    surface as built, for the as-built ray trace of the verification."""
    pts, ders = kernel.edge_points(_spline(curve, 0.0), n_samples)
    tangents = ders[:, :2] / np.linalg.norm(ders[:, :2], axis=1, keepdims=True)
    return Curve(curve.name, curve.layer, pts[:, :2], tangents)


def band_wire(a: Curve, b: Curve, z: float = 0.0):
    """Closed wire between two curves over the same x span (ends joined by lines)."""
    (pa, ta), (pb, tb) = _knots(a, z), _knots(b, z, reverse=True)
    return kernel.wire([kernel.spline(pa, ta), kernel.line(pa[-1], pb[0]), kernel.spline(pb, tb),
                        kernel.line(pb[-1], pa[0])])


def band_face(a: Curve, b: Curve, z: float = 0.0):
    """Face between two curves over the same x span (:func:`band_wire`)."""
    return kernel.face(band_wire(a, b, z))


def slot_wire(x: float, y: float, length: float, width: float, angle: float, z: float):
    """Rounded-end rectangle as a clockwise wire (an inner wire of a +z face)."""
    u = np.array([np.sin(angle), np.cos(angle)])
    n = np.array([-u[1], u[0]])
    r, s = width / 2, max(length / 2 - width / 2, 1e-4)
    c = np.array([x, y])
    P = lambda v: (float(v[0]), float(v[1]), z)         # noqa: E731
    p1, p2, p3, p4 = c - u * s + n * r, c + u * s + n * r, c + u * s - n * r, c - u * s - n * r
    return kernel.wire([kernel.line(P(p1), P(p2)), kernel.arc(P(p2), P(c + u * (s + r)), P(p3)),
                        kernel.line(P(p3), P(p4)), kernel.arc(P(p4), P(c - u * (s + r)), P(p1))])


def slotted_plate(x0: float, y0: float, x1: float, y1: float, z: float, thickness: float,
                  slots: list) -> kernel.Shape:
    """Rectangle with inner slot wires at height z, extruded +z: one face, one prism."""
    outer = kernel.polygon([(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)])
    return kernel.plate(outer, slots, (0, 0, thickness))


def _prism(poly: Polygon, z0: float, z1: float, holes: tuple = ()) -> kernel.Shape:
    """A planar polygon (shapely, with its interiors) at z0 extruded to z1, plus extra inner wires."""
    wire = lambda ring: kernel.polygon([(float(x), float(y), z0) for x, y in ring.coords[:-1]])   # noqa: E731
    face = kernel.face(wire(poly.exterior), [wire(r) for r in poly.interiors] + list(holes))
    return kernel.extrude(face, (0, 0, z1 - z0))


def _guide_parts(design: SlotArrayDesign, g: int, idx: np.ndarray, ext: GuideExtent, t: float,
                 dielectric: Material, absorber: Material, metal: Material) -> tuple[list[ModelPart], int]:
    """Guide g as machined: the body ``waveguide-g`` (bottom, side and end walls: a box less its
    cavity), the slotted lid ``top-g`` (the top broad wall: one face with the slots as inner wires,
    one prism), the dielectric core and the load wedge. Returns the parts and the number of slot
    holes cut."""
    s = design.slots
    h, a = design.guide_height_mm, design.guide_width_mm
    gx, y0, y1, yl, ye, half = (float(s.guide_x_mm[g]), float(ext.y0[g]), float(ext.y_slots_end[g]),
                                float(ext.y_load_end[g]), float(ext.y_end[g]), ext.half)
    holes = [slot_wire(float(s.x_mm[i]), float(s.y_mm[i]), float(s.length_mm[i]), float(s.width_mm[i]),
                       float(s.angle_rad[i]), t + h) for i in idx]
    lid = slotted_plate(gx - half, y0, gx + half, ye, t + h, t, holes)
    outline = np.array([(gx - half, y0), (gx + half, y0), (gx + half, ye), (gx - half, ye)])
    prism = SlottedPrism(outline, np.column_stack([s.x_mm[idx], s.y_mm[idx], s.length_mm[idx], s.width_mm[idx],
                                                   s.angle_rad[idx]]).astype(float), t + h, 2 * t + h)
    eps = 0.01 * t
    cw = a / 2 if half > a / 2 else half + eps             # no side walls: the cavity spans the width
    box = kernel.box((gx - half, y0, 0.0), (2 * half, ye - y0, t + h))
    cavity = kernel.box((gx - cw, y0 - eps, t), (2 * cw, yl - y0 + eps, h + eps))
    parts = [ModelPart(f"waveguide-{g:02d}", metal, "fabricated", kernel.cut(box, [cavity])),
             ModelPart(f"top-{g:02d}", metal, "fabricated", lid, prism)]
    core, load = core_and_load_rings(a, y0, y1, yl)
    shift = lambda ring: Polygon([(gx + x, y) for x, y in ring])
    parts.append(ModelPart(f"core-{g:02d}", dielectric, "fabricated", _prism(shift(core), t, t + h)))
    if load:
        parts.append(ModelPart(f"load-{g:02d}", absorber, "fabricated", _prism(shift(load), t, t + h)))
    return parts, len(holes)


def build_model(design: SlotArrayDesign, dielectric: Material, metal: Material, absorber: Material,
                sizes: PartSizes) -> Model:
    """Every part of the array in the frame of the module docstring (labels: waveguide-07,
    top-07, core-07, load-07, plate-1, mirror-1, lens, horn-3)."""
    bf, s = design.beamformer, design.slots
    n_layers = max(max(layer_indices(m)) for m in bf.mirrors)
    t = sizes.broad_wall_mm
    st = Stack(n_layers, t, design.layer_height_mm, design.guide_height_mm)
    parts: list[ModelPart] = []
    ext = guide_extent(design, design.wall_mm, t)
    order = np.argsort(s.guide_index, kind="stable")
    bounds = np.searchsorted(s.guide_index[order], np.arange(len(s.guide_x_mm) + 1))
    holes_total = 0
    for g in range(len(s.guide_x_mm)):
        guide, n_holes = _guide_parts(design, g, order[bounds[g]:bounds[g + 1]], ext, t, dielectric, absorber, metal)
        parts += guide
        holes_total += n_holes
    horns = horn_outlines(design, sizes)
    # beam-former plates: base plate, then one per layer transition with its coupling slot(s)
    for k in range(n_layers):
        za, zb = st.plate(k)
        holes = tuple(band_wire(m, coupling_edge(design, m), za) for m in bf.mirrors
                      if layer_indices(m)[0] == k and k > 0)
        parts.append(ModelPart(f"plate-{k}", metal, "fabricated",
                               _prism(plate_polygon(design, k, sizes, horns), za, zb, holes)))
    for j, m in enumerate(bf.mirrors, start=1):
        back = offset_curve(m, mirror_back_sign(design, m) * sizes.mirror_wall_mm, f"{m.name}_back")
        solids = []
        for k in layer_indices(m):
            za, zb = st.layer(k)
            solids.append(kernel.extrude(band_face(m, back, za), (0, 0, zb - za)))
        parts.append(ModelPart(f"mirror-{j}", metal, "fabricated", kernel.compound(solids)))
    for j, lens in enumerate(bf.lenses, start=1):
        za, zb = st.layer(layer_indices(lens)[0])
        face = band_face(bf.mirrors[0], clip_curve(lens, *bf.mirrors[0].x_range_mm), za)
        parts.append(ModelPart(f"lens-{j}" if len(bf.lenses) > 1 else "lens", dielectric, "fabricated",
                               kernel.extrude(face, (0, 0, zb - za))))
    za, zb = st.layer(1)
    for k, horn in enumerate(horns, start=1):
        body = kernel.cut(_prism(horn.footprint, za - t, zb + t), [_prism(horn.channel_cut, za, zb)])
        parts.append(ModelPart(f"horn-{k}", metal, "fabricated", body))
    overlap = end_overlap_mm(design, design.wall_mm)
    checks = (Check.upper("model_slot_count", abs(holes_total - s.count), 0, "",
                          f"slot holes in the solids ({holes_total}) vs synthesised slots ({s.count})"),
              Check("guide_end_over_coupling_slot", "warn" if overlap > 0 else "pass", overlap, 0.0, "mm",
                    f"bottom-wall corner of the outer guide bodies overlaps the coupling slot's far edge by "
                    f"{overlap:.3g} mm (rectangular body ends vs a curved slot)" if overlap > 0 else
                    "guide bodies clear of the coupling slot"),
              *horn_checks(design, horns, sizes.mirror_wall_mm))
    return Model(tuple(parts), checks, step_pcurves=False)
