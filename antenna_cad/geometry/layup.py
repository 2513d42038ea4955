"""Solids of a sheet layup (seed-000 §6): sheets with their pedestal feet, the pedestal and the box.

Renders :class:`antenna_cad.fabrication.layup.LayupPlan` in 3-D: every sheet is its 2-D outline
(disc ∪ foot [∪ neck] minus dowel holes) extruded by the stock thickness. The box (seed-000 §6.1
option 3) clamps the pedestal; its panels are rendered from ``fabrication.box`` (outside the
aperture cylinder; screws join box panels only — none enters the foam).
"""

from __future__ import annotations

from build123d import Box, Circle, Cylinder, Pos, Rectangle, Rot, Shape, Sketch, extrude

from antenna_cad.fabrication.box import Panel
from antenna_cad.fabrication.layup import Hole, LayupPlan, SheetPlan


def _holes(holes: tuple[Hole, ...]) -> Sketch | None:
    shapes = [Pos(h.x_mm, h.y_mm) * Circle(h.diameter_mm / 2) for h in holes]
    if not shapes:
        return None
    sk = shapes[0]
    for s in shapes[1:]:
        sk = sk + s
    return sk


def foot_sketch(plan: LayupPlan) -> Sketch:
    """Pedestal share of one sheet: w × (y_corner − y_bottom) minus the aperture disc (a cradle)."""
    yb, yc = plan.foot_bottom_y_mm, plan.foot_corner_y_mm
    rect = Pos(0, (yb + yc) / 2) * Rectangle(plan.pedestal_width_mm, yc - yb)
    return rect - Circle(plan.lens_radius_mm)


def sheet_sketch(plan: LayupPlan, sheet: SheetPlan) -> Sketch:
    """The whole sheet in its own plane: lens disc, foot, optional neck, minus dowel holes."""
    sk = Circle(sheet.radius_mm) + foot_sketch(plan)
    if sheet.has_neck:
        R = plan.lens_radius_mm
        sk = sk + Pos(0, -R / 2) * Rectangle(plan.neck_width_mm, R)
    holes = _holes(sheet.lens_dowels + sheet.foot_dowels)
    return sk - holes if holes is not None else sk


def sheet_solid(plan: LayupPlan, sheet: SheetPlan) -> Shape:
    return Pos(0, 0, sheet.z_min_mm) * extrude(sheet_sketch(plan, sheet), sheet.thickness_mm)


def pedestal_solid(plan: LayupPlan) -> Shape:
    """All feet together: the prism the box clamps (reference body; the sheets carry it)."""
    return Pos(0, 0, plan.z_origin_mm) * extrude(foot_sketch(plan), plan.stack_thickness_mm)


def panel_solid(panel: Panel) -> Shape:
    """A box panel with all its screw holes cut in one batched boolean."""
    solid = Pos(*panel.center_mm) * Box(*panel.size_mm)
    tools = [Pos(h.x_mm, h.y_mm, h.z_mm) * (Rot(90, 0, 0) if h.axis == "y" else Rot(0, 0, 0))
             * Cylinder(h.diameter_mm / 2, h.depth_mm) for h in panel.holes]
    if not tools:
        return solid
    tool = tools[0]
    for t in tools[1:]:
        tool = tool + t
    return solid - tool
