"""Model of the graded-index lens (seed-001 §3.2): one labelled solid per slab of constant
permittivity (its section extruded by the lens height), with its material — or, for a sheet layup,
one per foam sheet (the slab's section extruded by the sheet's thickness), read back against the slabs.

Frame: X the lens axis, Y transverse (the synthesis frame in mm), Z the extrusion, centred on z = 0.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import MultiPoint

from antenna_cad.fabrication.graded import section_polygon, slab_material, slab_pieces
from antenna_cad.geometry import kernel
from antenna_cad.geometry.model import Model, ModelPart, relative_volume_check
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.graded_design import GradedDesign

READBACK_REL = 1e-6          # sheets of a slab together vs the slab's section × height (relative volume)
OUTLINE_TOL_MM = 1e-6        # a sheet solid's face vertices vs its slab's section (Hausdorff, mm)


def _solid(poly, z0: float, height: float):
    face = kernel.face(kernel.polygon([(float(x), float(y), 0.0) for x, y in poly.exterior.coords[:-1]]))
    return kernel.translate(kernel.extrude(face, (0, 0, height)), (0, 0, z0))


def build_model(design: GradedDesign, base: Material, height_mm: float, layup=None) -> Model:
    """Slab solids, or (``layup``: a :class:`~antenna_cad.fabrication.graded_layup.GradedLayup`) sheet solids."""
    if layup is None:
        parts = [ModelPart(label, slab_material(base, design.slab_eps[k]), "fabricated",
                           _solid(poly, -height_mm / 2, height_mm)) for label, k, poly in slab_pieces(design)]
        checks = ()
    else:
        parts = [ModelPart(s.label, s.material, "fabricated", _solid(s.outline, s.z_min_mm, s.thickness_mm))
                 for s in layup.sheets]
        checks = _readback(design, layup, parts, height_mm)
    total = sum(p.volume_mm3 for p in parts)
    check = relative_volume_check("slab_volume", total, section_polygon(design).area * height_mm,
                                  f"{'sheets' if layup is not None else 'slabs'} together vs the lens section × height")
    return Model(tuple(parts), (check, *checks))


def _readback(design: GradedDesign, layup, parts: list[ModelPart], height_mm: float) -> tuple[Check, ...]:
    """Read the sheet solids back against the slabs they make: per slab piece, the sheets' volumes
    summed vs its section × height, and every sheet's bottom face vertices vs the section outline."""
    volumes, outline = {}, 0.0
    for s, part in zip(layup.sheets, parts):
        volumes[s.piece] = volumes.get(s.piece, 0.0) + part.volume_mm3
        xyz = kernel.vertices(part.shape)
        pts = MultiPoint(xyz[np.isclose(xyz[:, 2], xyz[:, 2].min(), rtol=0, atol=1e-9), :2])   # bottom face
        outline = max(outline, pts.hausdorff_distance(MultiPoint(s.outline.exterior.coords[:-1])))
    worst = max(abs(volumes[label] / (poly.area * height_mm) - 1.0) for label, _, poly in slab_pieces(design))
    return (Check.upper("sheet_slab_volume", worst, READBACK_REL, "", "sheets of each slab read back vs the slab's "
                        "section × height: worst relative volume error"),
            Check.upper("sheet_outline", outline, OUTLINE_TOL_MM, "mm", "sheet solids' faces read back vs their "
                        "slab's section: worst Hausdorff distance of the outline vertices"))
