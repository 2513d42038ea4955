"""Solids of the multilayer Luneburg lens (seed-002 §5.1): shells as front/back hemispheres with
equatorial foam pins, a dielectric feed-arm boss, cylinder rings, or the layup's rings.

Frame: lens centre at the origin, +Z the beam, feed at z = −b; "front" is the z ≥ 0 half
(toward the beam), "back" the z ≤ 0 half (toward the feed). Cylinder lenses have their axis
(plate normal) along +Y so rays travel in the XZ plane. +Y is up; the feed boss hangs toward −Y.
"""

from __future__ import annotations

import math


from antenna_cad.geometry import kernel
from antenna_cad.geometry.layup import foot_sketch
from antenna_cad.geometry.model import Model, ModelPart, RingPrism, relative_volume_check
from antenna_cad.geometry.profiles import polyline_edges, revolve_closed
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check

PIN_START_DEG = 30.0      # away from the revolve seam at +X


def _arc(r: float, sign: float, reverse: bool = False):
    """Quarter arc of radius r in the XZ plane from (r, 0) to (0, ±r) (or back, ``reverse``)."""
    c = math.sqrt(0.5)
    a, b = (r, 0, 0), (0, 0, sign * r)
    return kernel.arc(*((b, (r * c, 0, sign * r * c), a) if reverse else (a, (r * c, 0, sign * r * c), b)))


def hemisphere_shell(r_in: float, r_out: float, sign: float) -> kernel.Shape:
    """One closed (r, z) profile (annular quarter disc) revolved once; sign +1 front, −1 back."""
    edges = [*polyline_edges([(r_in, 0.0), (r_out, 0.0)]), _arc(r_out, sign),
             *polyline_edges([(0.0, sign * r_out), (0.0, sign * r_in)])]
    if r_in > 0:
        edges.append(_arc(r_in, sign, reverse=True))
    return revolve_closed(edges)


def annulus_solid(r_in: float, r_out: float, z_lo: float, z_hi: float) -> kernel.Shape:
    """Flat ring (or disc) about Z, revolved from its closed rectangle profile."""
    pts = [(r_in, z_lo), (r_out, z_lo), (r_out, z_hi), (r_in, z_hi), (r_in, z_lo)]
    return revolve_closed(polyline_edges(pts))


def cone_ring_solid(inner: tuple[float, float], outer: tuple[float, float], z_lo: float, z_hi: float) -> kernel.Shape:
    """A taper-cut ring about Z: its inner and outer cones (radii at z_lo, z_hi) revolved."""
    pts = [(inner[0], z_lo), (outer[0], z_lo), (outer[1], z_hi), (inner[1], z_hi), (inner[0], z_lo)]
    pts = [p for k, p in enumerate(pts) if k == 0 or math.dist(p, pts[k - 1]) > 1e-9]
    return revolve_closed(polyline_edges(pts))


def pin_layout(r_in: float, r_out: float, count: int, d_max: float) -> tuple[float, float, float] | None:
    """(radius of the pin circle, pin diameter, hole depth per half) or None when no pin fits."""
    if count <= 0:
        return None
    rp = 0.5 * (r_in + r_out) if r_in > 0 else 0.5 * r_out
    d = min(d_max, 0.5 * (r_out - r_in) if r_in > 0 else 0.5 * r_out)
    lo, hi = rp - d / 2, rp + d / 2
    height = math.sqrt(max(r_out**2 - hi**2, 0.0)) - math.sqrt(max(r_in**2 - lo**2, 0.0))
    depth = min(1.5 * d, 0.5 * height)
    if d < 2.0 or depth < 1.0:
        return None
    return rp, d, depth


def build_model(design, grades: list[Material], fab, base: Material) -> Model:
    """Shells (sphere: hemispheres + pins + boss; cylinder: rings) for ``fabrication.method: shells``."""
    parts: list[ModelPart] = []
    checks: list[Check] = []
    R = design.radius_mm
    if design.shape == "cylinder":
        h = design.height_mm
        for L, m in zip(design.layers, grades):
            solid = kernel.rotate(annulus_solid(L.r_inner_mm, L.r_outer_mm, -h / 2, h / 2), (1, 0, 0), -90)
            parts.append(ModelPart(f"shell-{L.index:02d}", m, "fabricated", solid))
        total = sum(p.volume_mm3 for p in parts)
        checks.append(relative_volume_check("shell_volume_sum", total, math.pi * R * R * h,
                                            "cylinder rings vs the full cylinder"))
        return Model(tuple(parts), tuple(checks))
    total = 0.0
    for L, m in zip(design.layers, grades):
        pins = pin_layout(L.r_inner_mm, L.r_outer_mm, fab.pins_per_shell, fab.pin_diameter_mm)
        pin_solids = []
        if pins:
            rp, d, depth = pins
            for k in range(fab.pins_per_shell):
                a = math.radians(PIN_START_DEG + 360.0 * k / fab.pins_per_shell)
                x, y = rp * math.cos(a), rp * math.sin(a)
                pin = kernel.cylinder(d / 2, 2 * depth, (x, y, -depth))
                pin_solids.append(pin)
        for side, sign in (("front", 1.0), ("back", -1.0)):
            shell = hemisphere_shell(L.r_inner_mm, L.r_outer_mm, sign)
            if pin_solids:
                shell = kernel.cut(shell, pin_solids)
                if not kernel.is_valid(shell):
                    raise RuntimeError(f"shell-{L.index:02d}-{side}: pin holes gave an invalid solid")
            parts.append(ModelPart(f"shell-{L.index:02d}-{side}", m, "fabricated", shell))
            total += kernel.volume(shell)
        for k, pin in enumerate(pin_solids):
            parts.append(ModelPart(f"shell-{L.index:02d}-pin-{k + 1}", m, "fabricated", pin))
            total += kernel.volume(pin)
    checks.append(relative_volume_check("shell_volume_sum", total, 4.0 / 3.0 * math.pi * R**3,
                                        "hemispheres + pins vs the sphere"))
    if fab.feed_boss is not None:
        rb, length = fab.feed_boss.diameter_mm / 2, fab.feed_boss.length_mm
        if rb >= R:
            raise RuntimeError("feed boss diameter must be smaller than the lens")
        y_top = -math.sqrt(R * R - rb * rb)
        tall = length + (R + y_top)
        boss = kernel.cut(kernel.cylinder(rb, tall, (0, y_top, 0), (0, -1, 0)), [kernel.sphere(R)])
        if not kernel.is_valid(boss) or kernel.volume(boss) <= 0:
            raise RuntimeError("feed boss: invalid solid")
        parts.append(ModelPart("feed-boss", grades[-1], "fabricated", boss))
        checks.append(Check("feed_arm_outside_aperture", "pass", -R - length, -R, "mm",
                            f"metal feed arm fixed at y = {-R - length:g} mm, below the aperture "
                            f"(|y| > R = {R:g} mm); the boss is foam of the outer grade"))
    front = tuple(p.label for p in parts if p.label.endswith("-front"))   # pictures: the grades as rings
    return Model(tuple(parts), tuple(checks), cutaway=front)


def build_layup_model(plan, base: Material) -> Model:
    """The layup's rings as flat solids (as cut, before turning; dowel holes refilled by their
    dowels) or, taper-cut, as their cones, one part per ring, and the stand's feet (the spine's
    cradle, ``geometry.layup``)."""
    parts = []
    foot = foot_sketch(plan) if plan.pedestal_height_mm is not None else None
    for s in plan.sheets:
        for r in s.rings:
            if r.cone_outer_mm is not None:
                parts.append(ModelPart(r.label, r.material, "fabricated",
                                       cone_ring_solid(r.cone_inner_mm, r.cone_outer_mm, s.z_min_mm, s.z_max_mm)))
                continue
            solid = annulus_solid(r.r_inner_mm, r.r_outer_mm, s.z_min_mm, s.z_max_mm)
            if plan.shape == "cylinder":
                solid = kernel.rotate(solid, (1, 0, 0), -90)
            ring = RingPrism(r.r_inner_mm, r.r_outer_mm, s.z_min_mm, s.z_max_mm, plan.shape == "cylinder")
            parts.append(ModelPart(r.label, r.material, "fabricated", solid, ring))
        if foot is not None:
            parts.append(ModelPart(f"{s.label}-foot", plan.stand_material, "fabricated",
                                   kernel.translate(kernel.extrude(foot, (0, 0, s.thickness_mm)), (0, 0, s.z_min_mm))))
    return Model(tuple(parts), ())
