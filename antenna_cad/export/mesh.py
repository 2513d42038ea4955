"""Meshing with an absolute chord tolerance and STL writing (DESIGN.md pitfalls).

build123d's own tolerances are relative; here OCCT's BRepMesh runs with an absolute linear
deflection in mm after the cached triangulation is cleaned. The Delabella triangulator is tried
first: it meets the same deflection and is several times faster than the default (Watson) on our
rings and shells (benchmarks/mesh_speed.py), but leaves some B-spline faces untriangulated (the
machined bifocal lens), so a shape it does not close is meshed again with Watson; the mesher used
is recorded in the mesh's metadata. Each solid's triangulation is written by OCCT's own STL
writer and read back by trimesh (numpy, no per-node Python loop), vertices merged and degenerate
faces dropped, so the STL is watertight for trimesh/manifold.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import trimesh
from build123d import Compound, Shape
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.IMeshTools import (IMeshTools_MeshAlgoType_Delabella, IMeshTools_MeshAlgoType_Watson,
                            IMeshTools_Parameters)
from OCP.StlAPI import StlAPI_Writer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS

ANGULAR_DEFLECTION_RAD = 0.3
MESHERS = {"delabella": IMeshTools_MeshAlgoType_Delabella, "watson": IMeshTools_MeshAlgoType_Watson}


def mesh_shape(shape: Shape, tolerance_mm: float, meshers: tuple[str, ...] = tuple(MESHERS)) -> trimesh.Trimesh:
    """Triangulate ``shape`` with absolute chord deviation ``tolerance_mm``, trying ``meshers`` in
    turn until every face is triangulated and every body closed; each solid is merged on its own
    (bodies that touch along an edge stay separate, so every body is watertight)."""
    for name in meshers:
        if not _triangulate(shape, tolerance_mm, name) and name != meshers[-1]:
            continue
        with tempfile.TemporaryDirectory(prefix="antenna_cad-mesh-") as scratch:
            path = str(Path(scratch) / "solid.stl")
            bodies = [_solid_mesh(solid.wrapped, path) for solid in shape.solids()]
        if all(b.is_watertight for b in bodies) or name == meshers[-1]:
            mesh = trimesh.util.concatenate(bodies)
            mesh.metadata |= {"mesher": name, "bodies": len(bodies),
                              "bodies_watertight": all(b.is_watertight for b in bodies)}
            return mesh
    raise ValueError("mesh_shape: no mesher given")


def picture_meshes(shapes: list[Shape], tolerance_mm: float) -> list[trimesh.Trimesh]:
    """Unmerged triangle soups of many shapes, meshed together in one pass (for pictures: no
    watertightness needed, no per-part meshing call)."""
    compound = Compound(shapes)                    # a plain wrapper: the parts are not re-parented
    for name in MESHERS:
        if _triangulate(compound, tolerance_mm, name):
            break
    with tempfile.TemporaryDirectory(prefix="antenna_cad-mesh-") as scratch:
        path = str(Path(scratch) / "part.stl")
        return [_stl_read_back(shape.wrapped, path) for shape in shapes]


def _triangulate(shape: Shape, tolerance_mm: float, mesher: str) -> bool:
    """(Re-)mesh ``shape`` in place; True when every face got a triangulation."""
    BRepTools.Clean_s(shape.wrapped)
    BRepMesh_IncrementalMesh(shape.wrapped, _parameters(tolerance_mm, MESHERS[mesher]))
    return _fully_triangulated(shape.wrapped)


def _fully_triangulated(shape) -> bool:
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        if BRep_Tool.Triangulation_s(TopoDS.Face(explorer.Current()), TopLoc_Location()) is None:
            return False
        explorer.Next()
    return True


def _parameters(tolerance_mm: float, algorithm) -> IMeshTools_Parameters:
    params = IMeshTools_Parameters()
    params.Deflection = tolerance_mm
    params.Angle = ANGULAR_DEFLECTION_RAD
    params.Relative = False
    params.InParallel = True
    params.MeshAlgo = algorithm
    return params


def _solid_mesh(solid, path: str) -> trimesh.Trimesh:
    """One solid's triangulation, merged and cleaned by trimesh."""
    mesh = _stl_read_back(solid, path)
    mesh.merge_vertices()
    mesh.update_faces(mesh.nondegenerate_faces())
    mesh.remove_unreferenced_vertices()
    return mesh


def _stl_read_back(shape, path: str) -> trimesh.Trimesh:
    """The triangulation of ``shape`` via OCCT's binary STL writer, read by trimesh as it is."""
    writer = StlAPI_Writer()
    writer.ASCIIMode = False
    if not writer.Write(shape, path):
        raise RuntimeError(f"OCCT could not write the triangulation to {path}")
    return trimesh.load(path, file_type="stl", process=False)


SNAP_MM = 1e-9       # coordinates below this are written as 0 (run-to-run noise of OCCT booleans)


def write_stl(shape: Shape, path: Path, tolerance_mm: float) -> trimesh.Trimesh:
    """Binary STL of ``shape``; near-zero coordinates snapped to 0 so the bytes are reproducible.
    ``metadata["watertight"]``: the file as any STL reader sees it (vertices merged by position)
    is a closed 2-manifold, False when bodies touch along edges (4 faces on an edge) even though
    each body (``bodies_watertight``) is closed."""
    mesh = mesh_shape(shape, tolerance_mm)
    mesh.vertices = np.where(np.abs(mesh.vertices) < SNAP_MM, 0.0, mesh.vertices)
    mesh.metadata["watertight"] = bool(trimesh.Trimesh(mesh.vertices, mesh.faces).is_watertight)
    path.write_bytes(trimesh.exchange.stl.export_stl(mesh))
    return mesh
