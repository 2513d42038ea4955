"""Adapters of the multilayer Luneburg lens (seed-002) between its spec and the stages.

``fabrication.method: shells``: every layer a separate shell split into front/back hemispheres
with foam pins (cylinder: rings of the plate spacing); ``sheet_layup``: sheets of concentric
rings per grade (``fabrication.rings``), vertical-edged or taper-cut (``edge: taper``: cones through
the spheres, hot-wire files per ring edge, :mod:`antenna_cad.cam.rings`); ``printed``: the law as a
graded lattice of one filament (:mod:`antenna_cad.kinds.luneburg_printed`). CAD imports stay inside
``model``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from antenna_cad.verification import Table, Verification
from antenna_cad.fabrication.cutlist import CutRow
from antenna_cad.fabrication.ring_plan import sphere_radius
from antenna_cad.fabrication.rings import FabPlanRings, RingLayupPlan, fabricate_rings, plan_rings
from antenna_cad.asbuilt.taper import cone_gap_mm
from antenna_cad.materials import Material
from antenna_cad.spec.common import resolve_material
from antenna_cad.spec.luneburg import LuneburgLayupSpec, LuneburgShellsSpec, LuneburgSpec
from antenna_cad.spec.printed import PrintedSpec
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.luneburg import LuneburgDesign, synthesize_luneburg


def synthesize(spec: LuneburgSpec) -> LuneburgDesign:
    m = resolve_material(spec.material)
    d = spec.design
    layers = d.layers
    return synthesize_luneburg(
        diameter_mm=d.diameter_mm, frequency_ghz=spec.frequency_ghz,
        focal_distance_ratio=d.focal_distance_ratio, law=d.law,
        layer_count=None if layers.count == "auto" else layers.count, split=layers.split,
        ladder=layers.ladder.model_dump() if layers.ladder else None,
        outer_shell=d.outer_shell.model_dump() if d.outer_shell else None,
        base_eps_r=m.eps_r, base_tan_delta=m.tan_delta, base_density_kg_m3=m.density_kg_m3,
        grades=list(d.grades) if d.grades else None, shape=d.shape, height_mm=d.height_mm,
        edge_taper_db=d.edge_taper_db, feed_q=d.feed_q)


def layer_materials(spec: LuneburgSpec, design: LuneburgDesign) -> list[Material]:
    """One foam material per layer, named by its grade εr (layers on one grade share it)."""
    base = resolve_material(spec.material)
    medium = "lattice" if isinstance(spec.fabrication, PrintedSpec) else "foam"
    out = []
    for L in design.layers:
        name = f"{base.name}-{medium}-{L.eps_r:.3f}"
        out.append(Material(name, L.eps_r, L.tan_delta, float(L.density_kg_m3),
                            f"{base.name} foam, fill factor {L.fill_factor:.4f} (seed-002 §2.7)"))
    return out


def plan(spec: LuneburgSpec, design: LuneburgDesign):
    fab = spec.fabrication
    if not isinstance(fab, LuneburgLayupSpec):
        return None, ()
    return plan_rings([L.r_inner_mm for L in design.layers], [L.r_outer_mm for L in design.layers],
                      layer_materials(spec, design), shape=design.shape, height_mm=design.height_mm,
                      sheet_thickness_mm=fab.sheet_thickness_mm, sizing=fab.ring_sizing, kerf_mm=fab.kerf_mm,
                      board_width_mm=fab.board.width_mm, board_length_mm=fab.board.length_mm,
                      registration_hole_mm=fab.registration_hole_mm, pedestal_height_mm=fab.pedestal_height_mm,
                      pedestal_width_mm=fab.pedestal_width_mm, edge=fab.edge), ()


def model(spec: LuneburgSpec, design: LuneburgDesign, layup: RingLayupPlan | None, panels):
    from antenna_cad.geometry.luneburg import build_layup_model, build_model
    base = resolve_material(spec.material)
    if layup is not None:
        return build_layup_model(layup, base)
    if isinstance(spec.fabrication, PrintedSpec):          # the envelope and graded shells, for reference
        shells = build_model(design, layer_materials(spec, design),
                             LuneburgShellsSpec(method="shells", pins_per_shell=0, feed_boss=None), base)
        return replace(shells, parts=tuple(replace(p, label=f"reference-{p.label}", role="reference")
                                           for p in shells.parts))
    return build_model(design, layer_materials(spec, design), spec.fabrication, base)


def fabricate(spec: LuneburgSpec, design: LuneburgDesign, layup: RingLayupPlan | None, panels):
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.luneburg_printed import fabricate_printed
        return fabricate_printed(spec, design)
    if layup is None:
        return _fabricate_blanks(spec, design)
    plan = fabricate_rings(layup, spec.name, drawings=spec.outputs.templates)
    cam = spec.fabrication.cam
    if cam is not None and layup.edge == "taper":          # the rings' cones on the hot wire
        from antenna_cad.cam.rings import plan_ring_cam
        toolpaths = plan_ring_cam(layup, cam, {L.index: L for L in design.layers}, plan)
    elif cam is not None and cam.router is not None:        # flat rings and feet on the router
        from antenna_cad.cam.boards import ring_parts
        from antenna_cad.cam.plan import plan_board_cam
        toolpaths = plan_board_cam(ring_parts(plan, cam.router.tool_diameter_mm), cam.router)
    else:
        return plan
    return replace(plan, files=plan.files | toolpaths.files, cam=toolpaths)


def _fabricate_blanks(spec: LuneburgSpec, design: LuneburgDesign) -> FabPlanRings:
    """Machined/moulded shells: one blank per hemisphere (cylinder: per ring), mass per grade."""
    a = spec.fabrication.machining_allowance_mm
    rows = []
    for L, m in zip(design.layers, layer_materials(spec, design)):
        ro = L.r_outer_mm
        if design.shape == "cylinder":
            h = design.height_mm
            vol = math.pi * (ro**2 - L.r_inner_mm**2) * h
            rows.append(CutRow(f"shell-{L.index:02d}", "ring-blank", m.name, "", 0.0, 0.0, False,
                               2 * (ro + a), 2 * (ro + a), h + 2 * a, (2 * (ro + a)) ** 2 / 1e6,
                               vol / 1e9 * m.density_kg_m3, L.index, "turn to R in/out; mass = finished ring"))
            continue
        vol = 2.0 / 3.0 * math.pi * (ro**3 - L.r_inner_mm**3)
        for order, side in ((L.index, "back"), (len(design.layers) + L.index, "front")):
            rows.append(CutRow(f"shell-{L.index:02d}-{side}", "hemisphere-blank", m.name, "", 0.0, 0.0, False,
                               2 * (ro + a), 2 * (ro + a), ro + 2 * a, (2 * (ro + a)) ** 2 / 1e6,
                               vol / 1e9 * m.density_kg_m3, order,
                               "mould or machine; mass = finished hemisphere (pin holes refilled by pins)"))
    totals: dict[str, float] = {}
    for r in rows:
        totals[r.material] = totals.get(r.material, 0.0) + r.mass_kg
    totals = dict(sorted(totals.items())) | {"all": sum(totals.values())}
    return FabPlanRings((), {}, {}, (), tuple(sorted(rows, key=lambda r: (r.assembly_order, r.part))),
                        totals, {}, 0.0, {}, {})


def summary(spec: LuneburgSpec, design: LuneburgDesign, layup: RingLayupPlan | None) -> dict:
    d = design
    figures: dict = {
        "diameter_mm": d.diameter_mm, "d_over_lambda": d.diameter_mm / d.wavelength_mm,
        "focal_distance_mm": d.focal_distance_mm, "layer_count": len(d.layers),
        "layer_count_rule": d.layer_count_rule,
        "phase_error_pp_deg": d.phase_error_pp_deg, "phase_error_rms_deg": d.phase_error_rms_deg,
        "phase_error_rms_full_deg": d.phase_error_rms_full_deg,
        "focus_spread_mm": d.focus_spread_mm, "feed_q": d.feed_q,
        "efficiency_taper": d.efficiency_taper, "efficiency_spillover": d.efficiency_spillover,
        "efficiency": d.efficiency, "efficiency_with_phase": d.efficiency_with_phase,
        "axial_loss_db": d.axial_loss_db,
    }
    mats = layer_materials(spec, d)
    for row, m in zip(d.layer_table(), mats):
        figures[f"layer {row['index']:02d}"] = (
            f"r {row['r_inner_mm']:.2f}-{row['r_outer_mm']:.2f} mm, εr {row['eps_r']:.4f} "
            f"(design {row['eps_r_design']:.4f}), tanδ {row['tan_delta']:.2e}, {m.name} "
            f"{m.density_kg_m3:.1f} kg/m³")
    if layup is not None:
        figures |= {"sheet_count": layup.count, "sheet_thickness_mm": layup.sheet_thickness_mm,
                    "ring_count": len(layup.rings), "piece_count": sum(r.sectors for r in layup.rings),
                    "ring_sizing": layup.sizing, "dowel_count": len(layup.dowels),
                    "undowelled_shell_joints": layup.undowelled_joints}
        if layup.pedestal_height_mm is not None:
            figures |= {"stand_width_mm": layup.pedestal_width_mm, "stand_height_mm": layup.pedestal_height_mm}
        per: dict[str, list] = {}
        for r in layup.rings:
            per.setdefault(r.material.name, []).append(r)
        for name, rings in sorted(per.items()):
            figures[f"rings {name}"] = (f"{len(rings)} rings ({sum(r.sectors for r in rings)} pieces) in "
                                        f"{len({r.sheet_index for r in rings})} sheets")
    return figures


def fabrication_checks(spec: LuneburgSpec, design: LuneburgDesign, layup: RingLayupPlan | None) -> list[Check]:
    """Rings against their shells over the slab (contain: holds it, no excess), the finishing
    allowance, the registration dowels and the stand."""
    if layup is None:
        return []
    if layup.shape != "sphere":
        return [_registration_check(layup)]
    stand = []
    if layup.pedestal_height_mm is not None:
        stand.append(Check("stand_outside_aperture", "pass", layup.foot_corner_y_mm, -layup.lens_radius_mm, "mm",
                           f"stand feet ({layup.pedestal_width_mm:g} mm wide) reach up to the aperture circle only: "
                           f"top corners at y = {layup.foot_corner_y_mm:.1f} mm, cradle touching the lens at "
                           f"y = −R; nothing inside the aperture cylinder of the on-axis beam"))
    L = {l.index: l for l in design.layers}
    fit = 0.0
    allowance = 0.0
    for s in layup.sheets:
        z = np.linspace(s.z_min_mm, s.z_max_mm, 257)
        for r in s.rings:
            sh = L[r.shell_index]
            if layup.sizing == "contain":
                need_out = float(np.max(np.sqrt(np.maximum(sh.r_outer_mm**2 - z * z, 0.0))))
                need_in = float(np.min(np.sqrt(np.maximum(sh.r_inner_mm**2 - z * z, 0.0))))
                fit = max(fit, abs(r.r_outer_mm - need_out), abs(r.r_inner_mm - need_in))
                allowance = max(allowance, r.r_outer_mm - float(np.min(np.sqrt(np.maximum(sh.r_outer_mm**2 - z * z, 0.0)))))
    checks = []
    if layup.edge == "taper":
        checks += _cone_checks(layup, L)
    elif layup.sizing == "contain":
        checks.append(Check.upper("ring_fit", fit, 1e-6, "mm",
                                  "ring radii vs shell radii over the slab (contain, no excess)"))
        checks.append(Check("ring_finishing_allowance", "pass", allowance, allowance, "mm",
                            f"largest radial stock turned off a ring face: {allowance:.2f} mm"))
    else:
        checks.append(Check("mid_plane_sizing", "warn" if layup.dropped_caps else "pass",
                            float(layup.dropped_caps), 0.0, "caps",
                            f"rings sized at sheet mid-planes (stepped); {layup.dropped_caps} shell caps "
                            "missing their mid-plane are dropped"))
    return checks + [_registration_check(layup)] + stand


def _cone_checks(layup: RingLayupPlan, layers: dict) -> list[Check]:
    """Taper-cut rings: every cone's radii against its sphere at the sheet's two faces (a disc
    cut over an inner sphere's pole has no inner cone), and the caps dropped inside such discs."""
    fit = 0.0
    for s in layup.sheets:
        for r in s.rings:
            sh = layers[r.shell_index]
            spheres = [(r.cone_outer_mm, sh.r_outer_mm)] + ([(r.cone_inner_mm, sh.r_inner_mm)]
                                                            if max(r.cone_inner_mm) > 0 else [])
            fit = max([fit] + [abs(c - sphere_radius(R, z)) for cone, R in spheres
                               for c, z in zip(cone, (s.z_min_mm, s.z_max_mm))])
    return [Check.upper("ring_cone_fit", fit, 1e-6, "mm", "taper-cut ring cones vs their spheres at each "
                        "sheet's two faces"),
            Check("taper_dropped_caps", "warn" if layup.dropped_caps else "pass", float(layup.dropped_caps), 0.0,
                  "caps", f"{layup.dropped_caps} shell caps inside a ring cut as a disc over an inner sphere's "
                  "pole (a wire cuts only through holes; the disc's grade fills them)")]


def _registration_check(layup: RingLayupPlan) -> Check:
    """Every joint between consecutive sheets carries at least one dowel (rings of a sheet are
    located on each other by their turned or butting faces)."""
    if layup.registration_hole_mm <= 0:
        return Check("registration_dowels", "warn", 0.0, 1.0, "dowels",
                     "registration_hole_mm = 0: sheets are not dowelled; align them on a jig")
    rings = [dw for dw in layup.dowels if dw.shell_index]           # not the stand's feet
    joined = {dw.sheets for dw in rings}
    if layup.shape == "sphere":
        loose = [k for k in range(1, layup.count) if (k, k + 1) not in joined]
    else:                                            # through pins: one set ties every sheet and plate
        loose = [] if joined else [0]
    return Check("registration_dowels", "warn" if loose else "pass", float(len(loose)), 0.0, "joints",
                 f"{len(rings)} ring dowels of the rings' own grades; {len(loose)} sheet joints without one; "
                 f"{layup.undowelled_joints} shell crossings too thin for a Ø{layup.registration_hole_mm:g} mm "
                 "dowel (those rings sit on their neighbours' faces)")


def verify(spec: LuneburgSpec, design: LuneburgDesign, layup: RingLayupPlan | None, fab) -> Verification:
    """As-built GO verification: ideal, stepped and as-built lenses, scanned feeds, tolerances
    (:mod:`antenna_cad.kinds.luneburg_verify`)."""
    from antenna_cad.kinds.luneburg_verify import verify_luneburg   # the tracers and full-wave: a build's cost only
    v = verify_luneburg(spec, design, layup, fab, layer_materials(spec, design))
    if isinstance(spec.fabrication, PrintedSpec):
        from antenna_cad.kinds.printed_package import printed_verification
        v = v.merged(printed_verification(fab))
    if layup is None or layup.edge != "taper":
        return v
    return v.merged(Verification(tables=(_ring_cone_table(layup, {L.index: L for L in design.layers}),)))


def _ring_cone_table(layup: RingLayupPlan, shells: dict) -> Table:
    """Every taper-cut ring's two cones and their largest gaps to the spheres."""
    rows = []
    for s in layup.sheets:
        z = (s.z_min_mm, s.z_max_mm)
        for r in s.rings:
            sh = shells[r.shell_index]
            gaps = [cone_gap_mm(r.cone_outer_mm, z, lambda x: sphere_radius(sh.r_outer_mm, x))]
            if max(r.cone_inner_mm) > 0:
                gaps.append(cone_gap_mm(r.cone_inner_mm, z, lambda x: sphere_radius(sh.r_inner_mm, x)))
            rows.append((r.label, round(z[0], 3), round(z[1], 3), *(round(x, 3) for x in r.cone_outer_mm + r.cone_inner_mm),
                         round(max(gaps), 3)))
    return Table("ring-cones", "Rings (taper-cut)", ("ring", "z min mm", "z max mm", "outer front mm", "outer back mm",
                                                    "inner front mm", "inner back mm", "largest gap to the spheres mm"),
                 tuple(rows), caption="each edge is the cone through its sphere at the sheet's two faces (inner 0: a "
                 "disc); gap: the largest distance from the sphere to the cone in the meridional section")
