"""Meshing with an absolute chord tolerance and STL writing (DESIGN.md pitfalls).

build123d's own tolerances are relative; here BRepMesh_IncrementalMesh runs with an absolute
linear deflection in mm after the cached triangulation is cleaned, the per-face triangulations
are gathered with their orientation, vertices merged and degenerate faces dropped, so the STL is
watertight for trimesh/manifold.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from build123d import Shape
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS

ANGULAR_DEFLECTION_RAD = 0.3


def mesh_shape(shape: Shape, tolerance_mm: float) -> trimesh.Trimesh:
    """Triangulate ``shape`` with absolute chord deviation ``tolerance_mm``; each solid is merged
    on its own (bodies that touch along an edge stay separate, so every body is watertight)."""
    BRepTools.Clean_s(shape.wrapped)
    BRepMesh_IncrementalMesh(shape.wrapped, tolerance_mm, False, ANGULAR_DEFLECTION_RAD, True)
    return trimesh.util.concatenate([_solid_mesh(solid.wrapped) for solid in shape.solids()])


def _solid_mesh(solid) -> trimesh.Trimesh:
    vertices, faces, offset = [], [], 0
    explorer = TopExp_Explorer(solid, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, loc)
        explorer.Next()
        if tri is None:
            continue
        trsf = loc.Transformation()
        pts = [tri.Node(i).Transformed(trsf) for i in range(1, tri.NbNodes() + 1)]
        vertices.append(np.array([(p.X(), p.Y(), p.Z()) for p in pts]))
        idx = np.array([tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)]) - 1 + offset
        if face.Orientation() == TopAbs_REVERSED:
            idx = idx[:, ::-1]
        faces.append(idx)
        offset += len(pts)
    mesh = trimesh.Trimesh(np.vstack(vertices), np.vstack(faces), process=False)
    mesh.merge_vertices()
    mesh.update_faces(mesh.nondegenerate_faces())
    mesh.remove_unreferenced_vertices()
    return mesh


def write_stl(shape: Shape, path: Path, tolerance_mm: float) -> trimesh.Trimesh:
    mesh = mesh_shape(shape, tolerance_mm)
    path.write_bytes(trimesh.exchange.stl.export_stl(mesh))
    return mesh
