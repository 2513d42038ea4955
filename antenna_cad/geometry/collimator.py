"""Model of the single-surface collimator (seed-000 §7.2): ideal lens, sheets, pedestal, box,
sanding allowance. Frame of DESIGN.md: vertex at z = 0, flat face at z = thickness, +Y up."""

from __future__ import annotations

import math

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.box import Panel
from antenna_cad.geometry import kernel
from antenna_cad.geometry.layup import panel_solid, pedestal_solid, sheet_solid
from antenna_cad.geometry.model import Model, ModelPart, relative_volume_check
from antenna_cad.geometry.profiles import hyperbola_edge, polyline_edges, revolve_closed
from antenna_cad.materials import Material
from antenna_cad.synthesis.collimator import CollimatorDesign, lens_volume_mm3


def lens_solid(design: CollimatorDesign, back_slab_mm: float = 0.0):
    """Revolve the exact profile once: hyperbola 0 → D/2, rim (and back slab), flat face, axis."""
    R, d, f, n = design.diameter_mm / 2, design.thickness_mm, design.focal_length_mm, design.n
    back = d + back_slab_mm
    edges = [hyperbola_edge(f, n, 0.0, R)] + polyline_edges([(R, d), (R, back), (0.0, back), (0.0, 0.0)])
    return revolve_closed(edges)


def sanding_allowance(design: CollimatorDesign, plan: LayupPlan) -> dict[str, object]:
    """Stack minus lens as one revolved ring per sheet (label → solid): between the sheet's disc
    radius and the hyperbola inside its slab (the hatched area of seed-000 Fig. 4.2). The rings
    touch along circles, so they stay separate bodies."""
    f, n, d = design.focal_length_mm, design.n, design.thickness_mm
    rings = {}
    for s in plan.sheets:
        if s.z_min_mm >= d - 1e-9:
            continue
        r_lo = float(design.radius_at(s.z_min_mm))
        z_hi = min(s.z_max_mm, d)
        edges = [hyperbola_edge(f, n, r_lo, s.radius_mm)] + polyline_edges(
            [(s.radius_mm, z_hi), (s.radius_mm, s.z_min_mm), (r_lo, s.z_min_mm)])
        rings[f"sanding-allowance-{s.index:02d}"] = revolve_closed(edges)
    return rings


def allowance_volume_mm3(design: CollimatorDesign, plan: LayupPlan) -> float:
    """Analytic Σ π·R_i²·(slab ∩ [0, d]) − V_lens."""
    d = design.thickness_mm
    stack = sum(math.pi * s.radius_mm**2 * max(0.0, min(s.z_max_mm, d) - s.z_min_mm) for s in plan.sheets)
    return stack - lens_volume_mm3(design.focal_length_mm, design.n, d)


def build_model(design: CollimatorDesign, plan: LayupPlan | None, lens_material: Material,
                box_material: Material | None = None, panels: tuple[Panel, ...] = ()) -> Model:
    """All labelled solids. ``plan`` None means a machined (solid) lens: the lens only."""
    slab = plan.back_slab_mm if plan else 0.0
    lens = lens_solid(design, slab)
    R = design.diameter_mm / 2
    lens_analytic = lens_volume_mm3(design.focal_length_mm, design.n, design.thickness_mm) + math.pi * R**2 * slab
    checks = [relative_volume_check("lens_solid_volume", kernel.volume(lens), lens_analytic,
                                    "lens solid vs analytic volume (seed-000 §7.3)")]
    role_lens = "reference" if plan else "fabricated"
    parts = [ModelPart("lens", lens_material, role_lens, lens)]
    if plan is None:
        return Model(tuple(parts), tuple(checks))
    parts += [ModelPart(s.label, lens_material, "fabricated", sheet_solid(plan, s)) for s in plan.sheets]
    parts.append(ModelPart("pedestal", lens_material, "reference", pedestal_solid(plan)))
    allowance = sanding_allowance(design, plan)
    checks.append(relative_volume_check("sanding_allowance_volume",
                                        sum(kernel.volume(ring) for ring in allowance.values()),
                                        allowance_volume_mm3(design, plan),
                                        "sanding allowance (stack − lens) vs analytic volume"))
    parts += [ModelPart(label, lens_material, "reference", ring) for label, ring in allowance.items()]
    parts += [ModelPart(p.label, box_material, "fabricated", panel_solid(p)) for p in panels]
    return Model(tuple(parts), tuple(checks))
