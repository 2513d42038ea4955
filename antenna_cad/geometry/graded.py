"""Model of the graded-index lens (seed-001 §3.2): one labelled solid per slab of constant
permittivity (its section extruded by the lens height), with its material.

Frame: X the lens axis, Y transverse (the synthesis frame in mm), Z the extrusion, centred on z = 0.
"""

from __future__ import annotations

from build123d import Polyline, Pos, extrude, make_face

from antenna_cad.fabrication.graded import section_polygon, slab_material, slab_pieces
from antenna_cad.geometry.model import Model, ModelPart, relative_volume_check
from antenna_cad.materials import Material
from antenna_cad.synthesis.graded_design import GradedDesign


def _solid(poly, height: float):
    face = make_face(Polyline(*[(float(x), float(y), 0.0) for x, y in poly.exterior.coords[:-1]], close=True))
    return Pos(0, 0, -height / 2) * extrude(face, height)


def build_model(design: GradedDesign, base: Material, height_mm: float) -> Model:
    parts = [ModelPart(label, slab_material(base, design.slab_eps[k]), "fabricated", _solid(poly, height_mm))
             for label, k, poly in slab_pieces(design)]
    total = sum(p.volume_mm3 for p in parts)
    check = relative_volume_check("slab_volume", total, section_polygon(design).area * height_mm,
                                  "slabs together vs the lens section × height")
    return Model(tuple(parts), (check,))
