"""The graded sheet gyroid as one level set meshed by manifold3d (marching tetrahedra on a
body-centred grid: watertight, oriented, no self-intersection by construction).

The solid is |g(p/a)| ≤ t(r), g the gyroid of :mod:`antenna_cad.printed.lattice` (the sheet the
unit-cell table was computed for, the gyroid infill slicers print), its level t following the fill
the law asks at the lens radius r (continuously, not cell by cell). The level-set function
F = (t(r) − |g|)/|∇g| (mm, near the sheet its signed distance, so the grid's linear interpolation
places the surface well) is cut off just outside the kept body, so no triangles are made beyond it; the parts
path (:mod:`antenna_cad.printed.parts`) trims the flat face and the body exactly.

The lattice is shifted by a/4 along z: the rotation by π about the x axis through the lens centre
maps the gyroid onto itself (g(x, −y, ½ − z) = g(x, y, z) in cell units), so a sphere's lower
hemisphere turned over is the upper one, as for the cubic lattice.

The grid's edge must resolve the thinnest sheet and the narrowest gap (a sheet thinner than the grid
spacing tears): ``edge_mm`` is :func:`antenna_cad.printed.lattice.gyroid_edge_mm`. manifold3d calls F once per grid
point (about 2·(a/edge)³ calls per cell) from Python, which sets the cost: linear in cells.
"""

from __future__ import annotations

import math

from manifold3d import Manifold

from antenna_cad.printed.fill import FillMap
from antenna_cad.printed.lattice import parameter_for

GRAD_MIN = 0.2              # |∇g| floor (cell units /2π) away from the sheet, where g is flat
Z_SHIFT = 0.25              # cells: puts the gyroid's two-fold axis on the lens's equator


def level_function(fmap: FillMap, shape: str, r_out_mm: float):
    """F(x, y, z) (mm): (t(r) − |g|)/|∇g|, positive in the sheet, cut off beyond ``r_out_mm`` (sphere: radius
    from the centre; cylinder: in the plane)."""
    k = 2 * math.pi / fmap.cell_mm
    dz = Z_SHIFT * fmap.cell_mm
    t_table = parameter_for("gyroid", fmap.fill).tolist() + [0.0]
    step = float(fmap.r_mm[1] - fmap.r_mm[0])
    last = len(fmap.r_mm) - 1
    sin, cos, sqrt = math.sin, math.cos, math.sqrt
    sphere = shape == "sphere"

    def f(x: float, y: float, z: float) -> float:
        r = sqrt(x * x + y * y + (z * z if sphere else 0.0))
        if r > r_out_mm:
            return -1.0
        u = r / step
        i = min(int(u), last - 1)
        t = t_table[i] + (u - i) * (t_table[i + 1] - t_table[i])
        sx, cx, sy, cy = sin(k * x), cos(k * x), sin(k * y), cos(k * y)
        sz, cz = sin(k * (z + dz)), cos(k * (z + dz))
        gx, gy, gz = cx * cy - sz * sx, cy * cz - sx * sy, cz * cx - sy * sz
        return (t - abs(sx * cy + sy * cz + sz * cx)) / (k * max(sqrt(gx * gx + gy * gy + gz * gz), GRAD_MIN))
    return f


def gyroid_lattice(shape: str, r_keep_mm: float, z0_mm: float, z1_mm: float, fmap: FillMap,
                   edge_mm: float) -> Manifold:
    """The graded sheet gyroid inside radius ``r_keep_mm`` (+ one edge) between z0 and z1 (the grid
    reaches one edge beyond; the caller trims exactly)."""
    r = r_keep_mm + 2 * edge_mm
    bounds = [-r, -r, z0_mm - 2 * edge_mm, r, r, z1_mm + 2 * edge_mm]
    m = Manifold.level_set(level_function(fmap, shape, r), bounds, edge_mm, 0.0)
    if m.status().name != "NoError":
        raise RuntimeError(f"gyroid level set rejected by manifold3d: {m.status().name}")
    return m

