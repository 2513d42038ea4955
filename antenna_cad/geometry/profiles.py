"""Closed profiles into solids: meridional (r, z) profiles revolved once about +Z into exact solids
of revolution, and (y, z) sections extruded along X into prisms.

Meridional profiles live in the XZ plane (x = r ≥ 0); one closed wire is revolved once (DESIGN.md
pitfall: no revolve-then-cut on the seam). Conic arcs are exact OCC curves, not approximations.
"""

from __future__ import annotations

import math


from antenna_cad.geometry import kernel
from antenna_cad.synthesis.collimator import hyperbola_axes_mm


def hyperbola_edge(focal_length_mm: float, n: float, r_from_mm: float, r_to_mm: float):
    """Exact arc of the collimator profile (seed-000 (1.9) corrected) between two radii.

    The conic (z − z_c)²/A² − r²/B² = 1 is parametrized as z = z_c + A·cosh u, r = B·sinh u, and
    written as its exact rational quadratic B-spline (3 poles; equal to the conic to ~1e-13 mm).
    Portability: OCCT 7.x STEP readers (gmsh, FreeCAD, OCP 7.9) drop every face whose
    SURFACE_OF_REVOLUTION sweeps a HYPERBOLA ("Entity was not translated") and with it the solid;
    a B_SPLINE_CURVE generatrix reads everywhere. Pinned by tests/test_step_portable.py.
    """
    zc, a, b = hyperbola_axes_mm(focal_length_mm, n)
    return kernel.hyperbola_arc(zc, a, b, math.asinh(r_from_mm / b), math.asinh(r_to_mm / b))


def polyline_edges(points_rz: list[tuple[float, float]]) -> list:
    """Straight edges through (r, z) points, skipping zero-length ones."""
    pts = [(r, 0.0, z) for r, z in points_rz]
    return [kernel.line(a, b) for a, b in zip(pts, pts[1:])
            if math.dist(a, b) > 1e-9]


def revolve_closed(edges: list) -> kernel.Shape:
    """Revolve one closed (r, z) wire about the Z axis; asserts a valid solid."""
    solid = kernel.revolve_z(kernel.face(kernel.wire(edges)))
    if not kernel.is_valid(solid):
        raise RuntimeError("revolved profile is not a valid solid")
    return solid


def yz_prism(points_yz, x0: float, height: float) -> kernel.Shape:
    """The closed polygon of (y, z) points in the plane x = x0, extruded by ``height`` along +X: one
    planar face swept by OCCT as it is (no unification of coplanar side faces, 1 ms an edge on the
    parallel plates' 3,300-edge outlines)."""
    return kernel.plate(kernel.polygon([(x0, float(y), float(z)) for y, z in points_yz]), (), (height, 0, 0))
