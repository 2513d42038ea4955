"""Sheet-layup steps shared by every lens of revolution cut from boards (seed-000 §6):
spec → layup plan (sheet thickness resolved) + box, the layup's fabrication plan, its figures, and
the neck warning."""

from __future__ import annotations

from dataclasses import replace

from antenna_cad.fabrication.box import plan_box
from antenna_cad.fabrication.layup import LayupPlan, plan_layup
from antenna_cad.fabrication.outline import added_in_aperture_mm2
from antenna_cad.asbuilt.stock import choose_stock, stock_study
from antenna_cad.materials import Material
from antenna_cad.spec.common import SheetLayupSpec, VerificationSpec, resolve_material
from antenna_cad.synthesis.checks import Check, DesignError


def plan_sheets(fab: SheetLayupSpec, sheet_thickness_mm: float, *, lens_radius_mm: float,
                lens_thickness_mm: float, radius_at=None, max_radius_in=None, z_origin_mm: float = 0.0) -> LayupPlan:
    """The LayupPlan of ``sheet_thickness_mm`` boards from the spec's ``fabrication`` block and the
    lens geometry (a plan that cannot be made raises DesignError naming the field)."""
    try:
        return plan_layup(
            radius_at=radius_at, max_radius_in=max_radius_in, z_origin_mm=z_origin_mm,
            lens_thickness_mm=lens_thickness_mm, lens_radius_mm=lens_radius_mm,
            sheet_thickness_mm=sheet_thickness_mm,
            pedestal_height_mm=fab.pedestal_height_mm, pedestal_width_mm=fab.pedestal_width_mm,
            joining=fab.joining, dowel_diameter_mm=fab.dowel_diameter_mm,
            neck_width_mm=fab.neck_width_mm, kerf_mm=fab.kerf_mm,
            board_width_mm=fab.board.width_mm, board_length_mm=fab.board.length_mm, edge=fab.edge)
    except ValueError as exc:
        field, _, message = str(exc).partition(": ")
        raise DesignError(field, message) from None


def plan_layup_and_box(fab, sheets, lens_for, settings: VerificationSpec = VerificationSpec()):
    """(LayupPlan, box panels) for a sheet layup; (None, ()) for a machined lens. ``sheets(t)`` plans
    t mm boards; with ``sheet_thickness_mm: auto`` the stock study picks t, judging each
    candidate ``lens_for(layup)`` by the fast sub-wavelength model (``settings``: the spec's
    ``verification`` block)."""
    if not isinstance(fab, SheetLayupSpec):
        return None, ()
    if fab.sheet_thickness_mm == "auto":
        layup = choose_stock(stock_study(sheets, lens_for, fab.stock_thicknesses_mm, settings)).layup
    else:
        layup = sheets(fab.sheet_thickness_mm)
    b = fab.box
    return layup, plan_box(layup, wall_mm=b.wall_thickness_mm, clearance_mm=b.clearance_mm,
                           screw_diameter_mm=b.screw_diameter_mm, screw_spacing_mm=b.screw_spacing_mm)


def fabricate_layup(fab: SheetLayupSpec, layup: LayupPlan, panels, foam: Material, title: str):
    from antenna_cad.fabrication.sheets import fabricate_sheets
    b = fab.box
    plan = fabricate_sheets(layup, panels, foam, resolve_material(b.material),
                            (b.board.width_mm, b.board.length_mm), title)
    if fab.cam is None:
        return plan
    from antenna_cad.cam.plan import plan_cam
    cam = plan_cam(layup, plan.pieces, fab.cam, foam.name, panels, plan.placements)
    return replace(plan, files=plan.files | cam.files, cam=cam)


def layup_figures(layup: LayupPlan) -> dict[str, float]:
    return {"sheet_count": layup.count, "sheet_thickness_mm": layup.sheet_thickness_mm,
            "stack_thickness_mm": layup.stack_thickness_mm, "back_slab_mm": layup.back_slab_mm}


def cone_fit_check(layup: LayupPlan, cone_radius) -> Check:
    """Every taper-cut sheet's cone against the lens: its radii at the two faces vs the lens radius
    ``cone_radius(z)`` there (z in the layup's frame)."""
    fit = max(abs(r - float(cone_radius(z))) for s in layup.sheets
              for r, z in zip(s.cone_mm, (s.z_min_mm, s.z_max_mm)))
    return Check.upper("sheet_cone_fit", fit, 1e-6, "mm",
                       "taper-cut cone radii vs the lens radius at each sheet's two faces")


def neck_checks(layup: LayupPlan) -> list[Check]:
    """Material the layup adds inside the aperture cylinder (necks), as a warning with its volume."""
    added = sum(added_in_aperture_mm2(layup, s) * s.thickness_mm for s in layup.sheets)
    if added <= 0:
        return []
    return [Check("material_in_aperture", "warn", added, 0.0, "mm3",
                  f"necks add {added / 1e6:.3f} dm³ of foam inside the aperture cylinder "
                  "(phase error where rays cross them; use joining: dowels to avoid it)")]
