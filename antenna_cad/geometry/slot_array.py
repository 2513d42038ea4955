"""Solids of the waveguide-slot array (seed-003): guides, beam-former plates, mirrors, lens, horns.

Frame: x across the guides, y along them, z up (broadside). The guide layer sits on the top
beam-former plate (z = 0); beam-former layers and plates stack downward. Slotted walls are one
planar face per guide with the slots as inner wires, extruded once (DESIGN.md pitfalls: no
per-slot 3-D booleans; small faces, separate parts) — cost is linear in the slot count.
"""

from __future__ import annotations

import numpy as np
from build123d import Compound, Edge, Face, Location, Solid, Vector, Wire, extrude
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon,
                                BRepBuilderAPI_MakeWire)
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.GC import GC_MakeArcOfCircle
from OCP.gp import gp_Pnt, gp_Vec

from antenna_cad.geometry.model import Model, ModelPart
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.geometry.slot_layout import (Stack, coupling_edge, end_overlap_mm, guide_extent, layer_indices,
                                              mirror_back_sign, plate_rect)
from antenna_cad.synthesis.slot_array import Curve, SlotArrayDesign, offset_curve

SPLINE_POINTS = 61        # C¹ spline knots through the synthesised points (with their tangents)


def _spline(curve: Curve, z: float, reverse: bool = False) -> Edge:
    n = len(curve.points_mm)
    idx = np.unique(np.linspace(0, n - 1, min(n, SPLINE_POINTS)).round().astype(int))
    pts = [Vector(float(x), float(y), z) for x, y in curve.points_mm[idx]]
    tan = [Vector(float(tx), float(ty), 0.0) for tx, ty in curve.tangents[idx]]
    if reverse:
        pts, tan = pts[::-1], [-v for v in tan[::-1]]
    return Edge.make_spline(pts, tangents=tan, scale=True)


def band_face(a: Curve, b: Curve, z: float = 0.0) -> Face:
    """Face between two curves over the same x span (ends joined by lines)."""
    ea, eb = _spline(a, z), _spline(b, z, reverse=True)
    return Face(Wire([ea, Edge.make_line(ea @ 1, eb @ 0), eb, Edge.make_line(eb @ 1, ea @ 0)]))


def band_wire(a: Curve, b: Curve, z: float = 0.0) -> Wire:
    return band_face(a, b, z).outer_wire()


def slot_wire(x: float, y: float, length: float, width: float, angle: float, z: float):
    """Rounded-end rectangle as a clockwise OCP wire (an inner wire of a +z face), built with
    OCP directly: build123d's per-edge Python overhead was 2 ms per slot."""
    u = np.array([np.sin(angle), np.cos(angle)])
    n = np.array([-u[1], u[0]])
    r, s = width / 2, max(length / 2 - width / 2, 1e-4)
    c = np.array([x, y])
    P = lambda v: gp_Pnt(float(v[0]), float(v[1]), z)
    p1, p2, p3, p4 = c - u * s + n * r, c + u * s + n * r, c + u * s - n * r, c - u * s - n * r
    mw = BRepBuilderAPI_MakeWire()
    mw.Add(BRepBuilderAPI_MakeEdge(P(p1), P(p2)).Edge())
    mw.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(P(p2), P(c + u * (s + r)), P(p3)).Value()).Edge())
    mw.Add(BRepBuilderAPI_MakeEdge(P(p3), P(p4)).Edge())
    mw.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(P(p4), P(c - u * (s + r)), P(p1)).Value()).Edge())
    return mw.Wire()


def slotted_plate(x0: float, y0: float, x1: float, y1: float, z: float, thickness: float,
                  slots: list) -> Solid:
    """Rectangle with inner slot wires at height z, extruded +z: one face, one prism."""
    poly = BRepBuilderAPI_MakePolygon(gp_Pnt(x0, y0, z), gp_Pnt(x1, y0, z), gp_Pnt(x1, y1, z),
                                      gp_Pnt(x0, y1, z), True)
    mf = BRepBuilderAPI_MakeFace(poly.Wire(), True)
    for wire in slots:
        mf.Add(wire)
    return Solid(BRepPrimAPI_MakePrism(mf.Face(), gp_Vec(0, 0, thickness)).Shape())


def build_model(design: SlotArrayDesign, dielectric: Material, metal: Material, *, broad_wall_mm: float,
                mirror_wall_mm: float, plate_margin_mm: float) -> Model:
    bf, s = design.beamformer, design.slots
    n_layers = max(max(layer_indices(m)) for m in bf.mirrors)
    st = Stack(n_layers, broad_wall_mm, design.layer_height_mm, design.guide_height_mm)
    t, h, a, w = broad_wall_mm, design.guide_height_mm, design.guide_width_mm, design.wall_mm
    parts: list[ModelPart] = []
    y0s, y1s, half = guide_extent(design, w)
    order = np.argsort(s.guide_index, kind="stable")
    bounds = np.searchsorted(s.guide_index[order], np.arange(len(s.guide_x_mm) + 1))
    z_top = t + h
    wires_total = 0
    for g, gx in enumerate(s.guide_x_mm):
        gx, y0, y1 = float(gx), float(y0s[g]), float(y1s[g])
        idx = order[bounds[g]:bounds[g + 1]]
        holes = [slot_wire(float(s.x_mm[i]), float(s.y_mm[i]), float(s.length_mm[i]),
                           float(s.width_mm[i]), float(s.angle_rad[i]), z_top) for i in idx]
        wires_total += len(holes)
        top = slotted_plate(gx - half, y0, gx + half, y1, z_top, t, holes)
        if w > 0:      # bottom + side walls as one U-channel prism, fused to the slotted top
            u = [(-half, 0), (half, 0), (half, t + h), (a / 2, t + h), (a / 2, t), (-a / 2, t),
                 (-a / 2, t + h), (-half, t + h)]
            face = Face(Wire.make_polygon([Vector(gx + px, y0, pz) for px, pz in u], close=True))
            body = extrude(face, y1 - y0, dir=(0, 1, 0)).fuse(top)
        else:          # pitch = width: no side walls of its own; bottom and slotted top plates
            body = Compound([top, Solid.make_box(2 * half, y1 - y0, t).moved(Location((gx - half, y0, 0)))])
        parts.append(ModelPart(f"waveguide-{g:02d}", metal, "fabricated", body))
        parts.append(ModelPart(f"core-{g:02d}", dielectric, "fabricated",
                               Solid.make_box(a, y1 - y0, h).moved(Location((gx - a / 2, y0, t)))))
    # beam-former plates: base plate, then one per layer transition with its coupling slot(s)
    x0, yb0, x1, yb1 = plate_rect(design, plate_margin_mm)
    for k in range(n_layers):
        za, zb = st.plate(k)
        outer = Wire.make_polygon([Vector(x0, yb0, za), Vector(x1, yb0, za), Vector(x1, yb1, za),
                                   Vector(x0, yb1, za)], close=True)
        holes = [band_wire(m, coupling_edge(design, m), za) for m in bf.mirrors
                 if layer_indices(m)[0] == k and k > 0]
        parts.append(ModelPart(f"plate-{k}", metal, "fabricated", extrude(Face(outer, holes), zb - za)))
    for j, m in enumerate(bf.mirrors, start=1):
        back = offset_curve(m, mirror_back_sign(design, m) * mirror_wall_mm, f"{m.name}_back")
        solids = []
        for k in layer_indices(m):
            za, zb = st.layer(k)
            solids.append(extrude(band_face(m, back, za), zb - za))
        parts.append(ModelPart(f"mirror-{j}", metal, "fabricated", Compound(solids)))
    for j, lens in enumerate(bf.lenses, start=1):
        mirror = bf.mirrors[0]
        lo, hi = max(lens.x_range_mm[0], mirror.x_range_mm[0]), min(lens.x_range_mm[1], mirror.x_range_mm[1])
        xs = np.linspace(lo, hi, 241)
        ring = [(x, float(mirror.y_at(x))) for x in xs] + [(x, float(lens.y_at(x))) for x in xs[::-1]]
        za, zb = st.layer(layer_indices(lens)[0])
        face = Face(Wire.make_polygon([Vector(x, y, za) for x, y in ring], close=True))
        parts.append(ModelPart(f"lens-{j}" if len(bf.lenses) > 1 else "lens", dielectric, "fabricated",
                               extrude(face, zb - za)))
    f = design.feeds
    za, zb = st.layer(1)
    for k, (c, aim) in enumerate(zip(f.aperture_centres_mm, f.aim), start=1):
        side = np.array([-aim[1], aim[0]])
        back = c - aim * f.length_mm
        ring = [back - side * f.throat_mm[0] / 2, c - side * f.aperture_mm[0] / 2,
                c + side * f.aperture_mm[0] / 2, back + side * f.throat_mm[0] / 2]
        face = Face(Wire.make_polygon([Vector(float(p[0]), float(p[1]), za) for p in ring], close=True))
        parts.append(ModelPart(f"horn-{k}", metal, "reference", extrude(face, zb - za)))
    overlap = end_overlap_mm(design, w)
    checks = (Check.upper("model_slot_count", abs(wires_total - s.count), 0, "",
                          f"slot holes in the solids ({wires_total}) vs synthesised slots ({s.count})"),
              Check("guide_end_over_coupling_slot", "warn" if overlap > 0 else "pass", overlap, 0.0, "mm",
                    f"bottom-wall corner of the outer guide bodies overlaps the coupling slot's far edge by "
                    f"{overlap:.3g} mm (rectangular body ends vs a curved slot)" if overlap > 0 else
                    "guide bodies clear of the coupling slot"))
    return Model(tuple(parts), checks, step_pcurves=False)

