"""The obvious implementations of our geometry, timed beside ours (not a test).

Each function builds the same parts the pipeline builds, the way a first version would:
- slotted lids: a plain plate, then one 3-D boolean cut per slot (ours: one face whose inner wires
  are the slots, extruded once — ``geometry.slot_array.slotted_plate``);
- layup sheets: the revolved lens solid intersected with one slab box per sheet (ours: each sheet's
  2-D outline extruded — ``geometry.layup.sheet_solid``);
- meshing: BRepMesh, then a Python loop over every face and node to collect the triangles (ours:
  OCCT's STL writer read back by trimesh — ``export.mesh.mesh_shape``).

Each returns ``(naive_seconds, ours_seconds, items)`` measured now on the same inputs.
"""

from __future__ import annotations

import time

import numpy as np


def _timed(fn):
    start = time.perf_counter()
    value = fn()
    return time.perf_counter() - start, value


def slotted_lids(design, broad_wall_mm: float, guides: int | None = None) -> tuple[float, float, int]:
    """Every guide's slotted lid: per-slot cuts vs one face with inner wires (first ``guides``;
    ``ours`` is also timed on every guide: ``(naive_s, ours_s, slots, ours_all_s, slots_all)``)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec

    from antenna_cad.geometry import kernel
    from antenna_cad.geometry.slot_array import slot_wire, slotted_plate
    from antenna_cad.geometry.slot_layout import guide_extent
    s, t, h = design.slots, broad_wall_mm, design.guide_height_mm
    ext = guide_extent(design, design.wall_mm, t)
    half = ext.half
    every = len(s.guide_x_mm)
    count = every if guides is None else min(guides, every)
    per_guide = [np.flatnonzero(s.guide_index == g) for g in range(every)]
    span = lambda g: (float(s.guide_x_mm[g]) - half, float(ext.y0[g]), float(s.guide_x_mm[g]) + half,
                      float(ext.y_end[g]))
    wires = lambda g: [slot_wire(float(s.x_mm[i]), float(s.y_mm[i]), float(s.length_mm[i]),
                                 float(s.width_mm[i]), float(s.angle_rad[i]), t + h) for i in per_guide[g]]

    def ours(count=count):
        return [slotted_plate(*span(g), t + h, t, wires(g)) for g in range(count)]

    def naive():
        lids = []
        for g in range(count):
            x0, y0, x1, y1 = span(g)
            lid = kernel.box((x0, y0, t + h), (x1 - x0, y1 - y0, t))
            for wire in wires(g):
                tool = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(wire, True).Face(), gp_Vec(0, 0, t)).Shape()
                lid = kernel.cut(lid, [tool])
            lids.append(lid)
        return lids

    t_ours, lids_ours = _timed(ours)
    t_naive, lids_naive = _timed(naive)
    _same_volume(lids_ours, lids_naive, "slotted lids")
    t_all, _ = _timed(lambda: ours(every))
    return t_naive, t_ours, int(sum(len(i) for i in per_guide[:count])), t_all, int(s.count)


def layup_sheets(plan, lens_solid) -> tuple[float, float, int]:
    """Every sheet of a collimator layup: lens ∩ slab per sheet vs outline extrusion."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common

    from antenna_cad.geometry import kernel
    from antenna_cad.geometry.layup import sheet_solid

    def naive():
        size = 4 * plan.lens_radius_mm
        return [BRepAlgoAPI_Common(lens_solid, kernel.box((-size / 2, -size / 2, s.z_min_mm),
                                                          (size, size, s.thickness_mm))).Shape()
                for s in plan.sheets]

    t_ours, _ = _timed(lambda: [sheet_solid(plan, s) for s in plan.sheets])
    t_naive, _ = _timed(naive)
    return t_naive, t_ours, len(plan.sheets)


def node_loop_mesh(shapes, tolerance_mm: float) -> tuple[float, float, int]:
    """Triangles of every shape: a Python loop per face and node vs the STL writer + trimesh."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.BRepTools import BRepTools
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    from antenna_cad.export.mesh import mesh_shape

    def naive():
        meshes = []
        for shape in shapes:
            BRepTools.Clean_s(shape)
            BRepMesh_IncrementalMesh(shape, tolerance_mm, False, 0.3, False)
            explorer = TopExp_Explorer(shape, TopAbs_FACE)
            while explorer.More():
                location = TopLoc_Location()
                tri = BRep_Tool.Triangulation_s(TopoDS.Face(explorer.Current()), location)
                if tri is not None:
                    nodes = [tri.Node(i).Transformed(location.Transformation()).Coord()
                             for i in range(1, tri.NbNodes() + 1)]
                    faces = [tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)]
                    meshes.append((np.array(nodes), np.array(faces) - 1))
                explorer.Next()
        return sum(len(faces) for _, faces in meshes)

    t_naive, triangles = _timed(naive)
    t_ours, _ = _timed(lambda: [mesh_shape(shape, tolerance_mm) for shape in shapes])
    return t_naive, t_ours, triangles


def _same_volume(ours, naive, what: str) -> None:
    """The baseline must build the same thing, or its time means nothing."""
    from antenna_cad.geometry.kernel import volume
    a = sum(volume(s) for s in ours)
    b = sum(volume(s) for s in naive)
    if abs(a - b) > 1e-6 * max(a, b):
        raise AssertionError(f"naive {what} differ from ours: {b:.6g} vs {a:.6g} mm³")
