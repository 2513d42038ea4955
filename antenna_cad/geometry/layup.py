"""Solids of a sheet layup (seed-000 §6): sheets with their pedestal feet, the pedestal and the box.

Renders :class:`antenna_cad.fabrication.layup.LayupPlan` in 3-D: every sheet is its 2-D outline
(disc ∪ foot [∪ neck] minus dowel holes) extruded by the stock thickness; a taper-cut sheet's disc
is the truncated cone of its rim. The box (seed-000 §6.1
option 3) clamps the pedestal; its panels are rendered from ``fabrication.box`` (outside the
aperture cylinder; screws join box panels only — none enters the foam).
"""

from __future__ import annotations

from antenna_cad.fabrication.box import Panel
from antenna_cad.fabrication.layup import Hole, LayupPlan, SheetPlan
from antenna_cad.geometry import kernel


def _holes(holes: tuple[Hole, ...]) -> list[kernel.Shape]:
    return [kernel.disc(h.x_mm, h.y_mm, h.diameter_mm / 2) for h in holes]


def foot_sketch(plan: LayupPlan) -> kernel.Shape:
    """Pedestal share of one sheet: w × (y_corner − y_bottom) minus the aperture disc (a cradle),
    a planar face at z = 0."""
    yb, yc = plan.foot_bottom_y_mm, plan.foot_corner_y_mm
    rect = kernel.rectangle(0, (yb + yc) / 2, plan.pedestal_width_mm, yc - yb)
    return kernel.cut(rect, [kernel.disc(0, 0, plan.lens_radius_mm)])


def sheet_sketch(plan: LayupPlan, sheet: SheetPlan) -> kernel.Shape:
    """The whole sheet in its own plane: lens disc, foot, optional neck, minus dowel holes."""
    pieces = [kernel.disc(0, 0, sheet.radius_mm), foot_sketch(plan)]
    if sheet.has_neck:
        R = plan.lens_radius_mm
        pieces.append(kernel.rectangle(0, -R / 2, plan.neck_width_mm, R))
    return kernel.cut(kernel.fuse(pieces), _holes(sheet.lens_dowels + sheet.foot_dowels))


def sheet_solid(plan: LayupPlan, sheet: SheetPlan) -> kernel.Shape:
    if sheet.tapered:
        return _taper_solid(plan, sheet)
    return kernel.translate(kernel.extrude(sheet_sketch(plan, sheet), (0, 0, sheet.thickness_mm)),
                            (0, 0, sheet.z_min_mm))


def _taper_solid(plan: LayupPlan, sheet: SheetPlan) -> kernel.Shape:
    """A taper-cut sheet: the truncated cone of its rim with its foot, dowel holes drilled from the
    wider face (blind where a through hole would break the cone)."""
    z0, z1 = sheet.z_min_mm, sheet.z_max_mm
    r0, r1 = sheet.cone_mm
    outline = ([(0, 0, z0)] + ([(r0, 0, z0)] if r0 > 1e-6 else []) + ([(r1, 0, z1)] if r1 > 1e-6 else [])
               + [(0, 0, z1)])
    cone = kernel.revolve_z(kernel.face(kernel.polygon(outline)))
    foot = kernel.translate(kernel.extrude(foot_sketch(plan), (0, 0, sheet.thickness_mm)), (0, 0, z0))
    holes = [kernel.cylinder(h.diameter_mm / 2, d, (h.x_mm, h.y_mm, z0 if sheet.drilled_from_front else z1 - d))
             for h in sheet.lens_dowels + sheet.foot_dowels if (d := sheet.hole_depth_mm(h)) > 0]
    return kernel.cut(kernel.fuse([cone, foot]), holes)


def pedestal_solid(plan: LayupPlan) -> kernel.Shape:
    """All feet together: the prism the box clamps (reference body; the sheets carry it)."""
    return kernel.translate(kernel.extrude(foot_sketch(plan), (0, 0, plan.stack_thickness_mm)),
                            (0, 0, plan.z_origin_mm))


def panel_solid(panel: Panel) -> kernel.Shape:
    """A box panel with all its screw holes cut in one batched boolean."""
    size = panel.size_mm
    solid = kernel.box([c - s / 2 for c, s in zip(panel.center_mm, size)], size)
    tools = [kernel.cylinder(h.diameter_mm / 2, h.depth_mm, _hole_base(h), (0, -1, 0) if h.axis == "y" else (0, 0, 1))
             for h in panel.holes]
    return kernel.cut(solid, tools)


def _hole_base(h) -> tuple[float, float, float]:
    """The base centre of a screw hole's cylinder, which is centred on the hole's point."""
    if h.axis == "y":
        return h.x_mm, h.y_mm + h.depth_mm / 2, h.z_mm
    return h.x_mm, h.y_mm, h.z_mm - h.depth_mm / 2
