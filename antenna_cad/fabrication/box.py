"""The clamping box as plain numbers (seed-000 §6.1 option 3): panels, sizes and screw holes.

Inner size = pedestal + clearance; walls stop at y = −R so the box stays outside the aperture
cylinder. Screws join box panels only: through the floor into the side walls' lower edges every
``screw_spacing_mm``, and through the end walls into the side walls' ends (two per corner).
"""

from __future__ import annotations

from dataclasses import dataclass

from antenna_cad.fabrication.layup import LayupPlan

SCREW_PILOT_DEPTH_MM = 30.0


@dataclass(frozen=True)
class ScrewHole:
    x_mm: float
    y_mm: float
    z_mm: float           # centre of the hole segment
    axis: str             # "y" or "z"
    depth_mm: float
    diameter_mm: float


@dataclass(frozen=True)
class Panel:
    label: str
    center_mm: tuple[float, float, float]
    size_mm: tuple[float, float, float]       # extents along x, y, z
    holes: tuple[ScrewHole, ...]

    @property
    def thickness_mm(self) -> float:
        return min(self.size_mm)

    @property
    def face_mm(self) -> tuple[float, float]:
        """The two larger extents: the rectangle cut from a board."""
        a, b = sorted(self.size_mm)[1:]
        return b, a

    @property
    def volume_mm3(self) -> float:
        x, y, z = self.size_mm
        return x * y * z


def plan_box(plan: LayupPlan, *, wall_mm: float, clearance_mm: float, screw_diameter_mm: float,
             screw_spacing_mm: float) -> tuple[Panel, ...]:
    R, T, c = plan.lens_radius_mm, wall_mm, clearance_mm
    half_in = plan.pedestal_width_mm / 2 + c
    z0, z1 = plan.z_origin_mm - c, plan.z_origin_mm + plan.stack_thickness_mm + c
    yb, ytop = plan.foot_bottom_y_mm, -R
    wall_h = ytop - yb
    xw = half_in + T / 2
    n_floor = max(2, int((z1 - z0) // screw_spacing_mm) + 1)
    zs = [z0 + (z1 - z0) * (k + 0.5) / n_floor for k in range(n_floor)]
    d = screw_diameter_mm
    heights = (yb + wall_h / 3, yb + 2 * wall_h / 3)

    def vertical(sx, y_from, depth):
        return tuple(ScrewHole(sx * xw, y_from + depth / 2, z, "y", depth, d) for z in zs)

    def axial(sx, z_mid, depth):
        return tuple(ScrewHole(sx * xw, y, z_mid, "z", depth, d) for y in heights)

    outer_w = 2 * (half_in + T)
    p = SCREW_PILOT_DEPTH_MM
    panels = [Panel("box-floor", (0.0, yb - T / 2, (z0 + z1) / 2), (outer_w, T, z1 - z0 + 2 * T),
                    vertical(-1, yb - T, T) + vertical(1, yb - T, T))]
    for side, sx in (("left", -1), ("right", 1)):
        panels.append(Panel(f"box-wall-{side}", (sx * xw, yb + wall_h / 2, (z0 + z1) / 2), (T, wall_h, z1 - z0),
                            vertical(sx, yb, p) + axial(sx, z0 + p / 2, p) + axial(sx, z1 - p / 2, p)))
    panels.append(Panel("box-wall-front", (0.0, yb + wall_h / 2, z0 - T / 2), (outer_w, wall_h, T),
                        axial(-1, z0 - T / 2, T) + axial(1, z0 - T / 2, T)))
    panels.append(Panel("box-wall-back", (0.0, yb + wall_h / 2, z1 + T / 2), (outer_w, wall_h, T),
                        axial(-1, z1 + T / 2, T) + axial(1, z1 + T / 2, T)))
    return tuple(panels)
