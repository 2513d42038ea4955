"""Solids of a sheet layup (seed-000 §6): sheets with their pedestal feet, the pedestal and the box.

Renders :class:`antenna_cad.fabrication.layup.LayupPlan` in 3-D: every sheet is its 2-D outline
(disc ∪ foot [∪ neck] minus dowel holes) extruded by the stock thickness. The box (seed-000 §6.1
option 3) clamps the pedestal; it stays below y = −R (outside the aperture cylinder) and all its
screws join box panels only — none enters the foam.
"""

from __future__ import annotations

from dataclasses import dataclass

from build123d import Box, Circle, Cylinder, Pos, Rectangle, Rot, Shape, Sketch, extrude

from antenna_cad.fabrication.layup import Hole, LayupPlan, SheetPlan

SCREW_PILOT_DEPTH_MM = 30.0


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
    return extrude(foot_sketch(plan), plan.stack_thickness_mm)


@dataclass(frozen=True)
class BoxPanel:
    label: str
    shape: Shape


def box_panels(plan: LayupPlan, wall_mm: float, clearance_mm: float, screw_diameter_mm: float,
               screw_spacing_mm: float) -> tuple[BoxPanel, ...]:
    """Floor, two side walls and two end walls around the pedestal; inner size = pedestal + clearance.

    Screws: through the floor into the side walls' lower edges every ``screw_spacing_mm``, and
    through the end walls into the side walls' ends (two per corner). Holes are cut in one batched
    boolean per panel.
    """
    R, T, c = plan.lens_radius_mm, wall_mm, clearance_mm
    half_in = plan.pedestal_width_mm / 2 + c
    z0, z1 = -c, plan.stack_thickness_mm + c
    yb, ytop = plan.foot_bottom_y_mm, -R
    wall_h = ytop - yb
    x_wall = half_in + T / 2                         # side-wall mid-plane
    n_floor = max(2, int((z1 - z0) // screw_spacing_mm) + 1)
    zs = [z0 + (z1 - z0) * (k + 0.5) / n_floor for k in range(n_floor)]
    r = screw_diameter_mm / 2

    def screws_y(depth: float, y_start: float, sign: float):       # vertical holes
        return [Pos(sx * x_wall, y_start + sign * depth / 2, z) * Rot(90, 0, 0) * Cylinder(r, depth)
                for sx in (-1, 1) for z in zs]

    def screws_z(depth: float, z_start: float, sign: float):       # axial holes
        return [Pos(sx * x_wall, yb + wall_h * f, z_start + sign * depth / 2) * Cylinder(r, depth)
                for sx in (-1, 1) for f in (1 / 3, 2 / 3)]

    def cut(shape, holes):
        tool = holes[0]
        for h in holes[1:]:
            tool = tool + h
        return shape - tool

    floor = Pos(0, yb - T / 2, (z0 + z1) / 2) * Box(2 * (half_in + T), T, z1 - z0 + 2 * T)
    floor = cut(floor, screws_y(T, yb - T, 1))
    panels = [BoxPanel("box-floor", floor)]
    for side, sx in (("left", -1), ("right", 1)):
        wall = Pos(sx * x_wall, yb + wall_h / 2, (z0 + z1) / 2) * Box(T, wall_h, z1 - z0)
        pilots = [h for h in screws_y(SCREW_PILOT_DEPTH_MM, yb, 1) if h.center().X * sx > 0]
        pilots += [h for h in screws_z(SCREW_PILOT_DEPTH_MM, z0, 1) + screws_z(SCREW_PILOT_DEPTH_MM, z1, -1)
                   if h.center().X * sx > 0]
        panels.append(BoxPanel(f"box-wall-{side}", cut(wall, pilots)))
    for end, zc, zs_start in (("front", z0 - T / 2, z0 - T), ("back", z1 + T / 2, z1)):
        wall = Pos(0, yb + wall_h / 2, zc) * Box(2 * (half_in + T), wall_h, T)
        panels.append(BoxPanel(f"box-wall-{end}", cut(wall, screws_z(T, zs_start, 1))))
    return tuple(panels)
