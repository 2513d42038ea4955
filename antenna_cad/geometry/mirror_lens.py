"""Model of the aplanatic mirror-lens (seed-004 §7.1): the dielectric body revolved once between
the exact profiles, the mirror as its own thin part on the back face, a feed placeholder at the
focus and a mounting flange outside the aperture; for a sheet layup the spine's sheets, pedestal,
box and the sanding allowance.

Frame: seed-004 §1 in mm — feed (focus) at the origin, +Z into the body (front vertex z = f0·D,
mirror vertex (f0 + d0)·D), the beam leaves toward −Z. The faces are C¹ splines through the exact
marched profiles (not the truncated series) with their exact slopes.
"""

from __future__ import annotations

import math

import numpy as np

from antenna_cad.fabrication.box import Panel
from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.mirror_lens import flange_geometry
from antenna_cad.geometry import kernel
from antenna_cad.geometry.bifocal import sanding_allowance
from antenna_cad.geometry.layup import panel_solid, pedestal_solid, sheet_solid
from antenna_cad.geometry.model import Model, ModelPart, relative_volume_check
from antenna_cad.geometry.profiles import polyline_edges, revolve_closed
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.mirror_lens import MirrorLensDesign

SPLINE_POINTS = 257            # per face
VOLUME_REL_LIMIT = 1e-5        # body solid vs the Pappus integral of the marched section
FACE_LIMIT_MM = 1e-3           # CAD spline vs the exact profile (measured 8e-9 mm front, 9e-10 mm mirror, D 346)
FACE_PROBES = 401
FEED_THROAT = 0.35             # placeholder horn: throat / aperture diameter


def face_points_mm(design: MirrorLensDesign, face: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return design.face_samples_mm(face, SPLINE_POINTS)


def _spline(r, z, dz, reverse: bool = False):
    if reverse:
        r, z, dz = r[::-1], z[::-1], dz[::-1]
    sgn = -1.0 if reverse else 1.0
    pts = [(float(a), 0.0, float(b)) for a, b in zip(r, z)]
    tan = [(sgn, 0.0, sgn * float(s)) for s in dz]
    return kernel.spline(pts, tan)


def face_deviation_mm(design: MirrorLensDesign) -> float:
    """Largest axial distance between the CAD splines of both faces and the exact profiles."""
    p, D = design.profiles, design.diameter_mm
    worst = 0.0
    for face, exact in (("front", p.front_spline()), ("mirror", p.mirror_spline())):
        edge = _spline(*face_points_mm(design, face))
        pts, _ = kernel.edge_points(edge, FACE_PROBES)
        worst = max(worst, float(np.max(np.abs(pts[:, 2] - exact(pts[:, 0] / D) * D))))
    return worst


def body_solid(design: MirrorLensDesign) -> kernel.Shape:
    """Revolve once: front face (axis → rim), side wall (a cone to the mirror rim), mirror (rim → axis), axis."""
    rf, zf, df = face_points_mm(design, "front")
    rm, zm, dm = face_points_mm(design, "mirror")
    edges = [_spline(rf, zf, df), *polyline_edges([(rf[-1], zf[-1]), (rm[-1], zm[-1])]),
             _spline(rm, zm, dm, reverse=True), *polyline_edges([(0.0, zm[0]), (0.0, zf[0])])]
    return revolve_closed(edges)


def mirror_solid(design: MirrorLensDesign, thickness_mm: float) -> kernel.Shape:
    """The reflecting layer: the back face offset outward along its normal by the coating thickness."""
    rm, zm, dm = face_points_mm(design, "mirror")
    norm = np.hypot(dm, 1.0)
    ro, zo = rm - thickness_mm * dm / norm, zm + thickness_mm / norm
    do = dm                                       # an offset curve keeps its slope at corresponding points
    edges = [_spline(rm, zm, dm), *polyline_edges([(rm[-1], zm[-1]), (ro[-1], zo[-1])]),
             _spline(ro, zo, do, reverse=True), *polyline_edges([(0.0, zo[0]), (0.0, zm[0])])]
    return revolve_closed(edges)


def feed_solid(design: MirrorLensDesign, aperture_mm: float, length_mm: float) -> kernel.Shape:
    """Placeholder horn: a solid frustum, aperture centred on the focus (z = 0), body toward −Z."""
    a, t = aperture_mm / 2, FEED_THROAT * aperture_mm / 2
    return revolve_closed(polyline_edges([(0.0, 0.0), (a, 0.0), (t, -length_mm), (0.0, -length_mm), (0.0, 0.0)]))


def flange_solid(design: MirrorLensDesign, width_mm: float, thickness_mm: float, bolts: int,
                 bolt_diameter_mm: float) -> kernel.Shape:
    (ri0, ri1), ro, z0, z1 = flange_geometry(design, width_mm, thickness_mm)
    ring = revolve_closed(polyline_edges([(ri0, z0), (ro, z0), (ro, z1), (ri1, z1), (ri0, z0)]))
    if bolts == 0:
        return ring
    rb = (max(ri0, ri1) + ro) / 2
    holes = [kernel.cylinder(bolt_diameter_mm / 2, z1 - z0 + 2, (rb * math.cos(2 * math.pi * k / bolts),
                                                                rb * math.sin(2 * math.pi * k / bolts), z0 - 1))
             for k in range(bolts)]
    solid = kernel.cut(ring, holes)
    if not kernel.is_valid(solid):
        raise RuntimeError("flange solid is not valid")
    return solid


def build_model(design: MirrorLensDesign, spec_design, plan: LayupPlan | None, lens_material: Material,
                metal: Material, box_material: Material | None = None, panels: tuple[Panel, ...] = ()) -> Model:
    """All labelled solids. The body is fabricated (machined/printed) or, for a layup, the reference
    the sanded sheets reproduce; the mirror, feed and flange are their own parts (no flange on a
    layup: the pedestal and box hold it)."""
    body = body_solid(design)
    checks = [relative_volume_check("body_solid_volume", kernel.volume(body), design.volume_mm3(),
                                    "body solid vs Pappus integral of the exact section", VOLUME_REL_LIMIT),
              Check.upper("face_spline_deviation", face_deviation_mm(design), FACE_LIMIT_MM, "mm",
                          "CAD faces vs the exact profiles (axial, both faces)")]
    m = spec_design.mirror
    parts = [ModelPart("body", lens_material, "reference" if plan else "fabricated", body),
             ModelPart("mirror", metal, "fabricated", mirror_solid(design, m.thickness_mm)),
             ModelPart("feed", metal, "reference", feed_solid(design, spec_design.feed.aperture_diameter_mm,
                                                             spec_design.feed.length_mm))]
    f = spec_design.flange
    if plan is None:
        parts.append(ModelPart("flange", lens_material, "fabricated",
                               flange_solid(design, f.width_mm, f.thickness_mm, f.bolt_count, f.bolt_diameter_mm)))
        return Model(tuple(parts), tuple(checks))
    parts += [ModelPart(s.label, lens_material, "fabricated", sheet_solid(plan, s)) for s in plan.sheets]
    parts.append(ModelPart("pedestal", lens_material, "reference", pedestal_solid(plan)))
    if plan.edge == "stepped":            # a taper-cut stack is not sanded
        allowance = sanding_allowance(plan, body)
        stack = sum(math.pi * s.radius_mm**2 * s.thickness_mm for s in plan.sheets)
        checks.append(relative_volume_check("sanding_allowance_volume", kernel.volume(allowance),
                                            stack - design.volume_mm3(),
                                            "sanding allowance (stack − body) vs analytic volume", 1e-4))
        parts.append(ModelPart("sanding-allowance", lens_material, "reference", allowance))
    parts += [ModelPart(p.label, box_material, "fabricated", panel_solid(p)) for p in panels]
    return Model(tuple(parts), tuple(checks))
