"""Meshing with an absolute chord tolerance and STL writing (DESIGN.md pitfalls).

Here OCCT's BRepMesh runs with an absolute linear
deflection in mm after the cached triangulation is cleaned. The Delabella triangulator is tried
first: it meets the same deflection and is several times faster than the default (Watson) on our
rings and shells (benchmarks/mesh_speed.py), but leaves some B-spline faces untriangulated (the
machined bifocal lens), so a shape it does not close is meshed again with Watson; the mesher used
is recorded in the mesh's metadata. Each solid's triangulation is written by OCCT's own STL
writer and read back by trimesh (numpy, no per-node Python loop), vertices merged and degenerate
faces dropped, so the STL is watertight for trimesh/manifold.

A slotted plate (:class:`~antenna_cad.geometry.model.SlottedPrism`, the Ka lids: 3,200 slots; the
parallel plates of a bifocal lens: one polygon of 3,300 edges) or
a flat ring (:class:`~antenna_cad.geometry.model.RingPrism`, the Luneburg layups: thousands) is
meshed from its exact description instead (:func:`mesh_prism`): arcs divided by the same chord and
angle criteria as BRepMesh, vertices on the exact curves, faces triangulated in numpy (rings) or
once by manifold3d (plates), walls as quads — closed by construction and many times faster than
BRepMesh on the B-rep.

BRepMesh cannot be stopped once started, so its work is bounded before it starts: the triangles a
shape needs are estimated from its curved faces' areas and radii and the chord tolerance
(:func:`estimate_triangles`), and a shape above :data:`MAX_TRIANGLES` is refused naming
``outputs.mesh_tolerance_mm``. The scratch folders in /dev/shm carry the process id, and those of
processes no longer running (killed while meshing) are removed when the next one starts meshing.
"""

from __future__ import annotations

import ctypes
import errno
import functools
import math
import os
import shutil
import tempfile
from pathlib import Path

import manifold3d
import numpy as np
import trimesh
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
from OCP.GCPnts import GCPnts_TangentialDeflection
from OCP.GeomAbs import (GeomAbs_Cylinder, GeomAbs_Plane, GeomAbs_Sphere, GeomAbs_SurfaceOfExtrusion,
                         GeomAbs_Torus)
from OCP.IMeshTools import (IMeshTools_MeshAlgoType_Delabella, IMeshTools_MeshAlgoType_Watson,
                            IMeshTools_Parameters)
from OCP.StlAPI import StlAPI_Writer
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS

from antenna_cad.geometry import kernel
from antenna_cad.geometry.kernel import Shape
from antenna_cad.geometry.model import RingPrism, SlottedPrism
from antenna_cad.synthesis.checks import DesignError

ANGULAR_DEFLECTION_RAD = 0.3
MAX_TRIANGLES = 5_000_000       # one part: 250 MB of STL, ~1-2 CPU min of BRepMesh (44-75 k triangles/s measured)
BREPMESH_DENSITY = 2.8
SCRATCH_PREFIX = "antenna_cad-mesh-"
MESHERS = {"delabella": IMeshTools_MeshAlgoType_Delabella, "watson": IMeshTools_MeshAlgoType_Watson}


def mesh_shape(shape: Shape, tolerance_mm: float, meshers: tuple[str, ...] = tuple(MESHERS)) -> trimesh.Trimesh:
    """Triangulate ``shape`` with absolute chord deviation ``tolerance_mm``, trying ``meshers`` in
    turn until every face is triangulated and every body closed; each solid is merged on its own
    (bodies that touch along an edge stay separate, so every body is watertight). A solid swept
    straight along x is meshed as the prism it is (:func:`x_prism`)."""
    prism = x_prism(shape, tolerance_mm)
    if prism is not None:
        return mesh_prism(prism, tolerance_mm)
    within_limit(estimate_triangles(shape, tolerance_mm), tolerance_mm)
    for name in meshers:
        if not _triangulate(shape, tolerance_mm, name, parallel=False) and name != meshers[-1]:
            continue
        with _scratch() as scratch:
            paths = [_write_triangulation(solid, str(Path(scratch) / f"{i}.stl"))
                     for i, solid in enumerate(kernel.solids(shape))]
            _release(shape)                         # the triangulation is in the files: free it first
            bodies = [_solid_mesh(path) for path in paths]
        if all(b.is_watertight for b in bodies) or name == meshers[-1]:
            mesh = trimesh.util.concatenate(bodies)
            mesh.metadata |= {"mesher": name, "bodies": len(bodies),
                              "bodies_watertight": all(b.is_watertight for b in bodies)}
            return mesh
    raise ValueError("mesh_shape: no mesher given")


def within_limit(count: int, tolerance_mm: float, part: str = "a part") -> int:
    """``count`` (a part's estimated triangles), or DesignError naming ``outputs.mesh_tolerance_mm``
    when it is over :data:`MAX_TRIANGLES`."""
    if count > MAX_TRIANGLES:
        raise DesignError("outputs.mesh_tolerance_mm", f"{part} needs about {count:.3g} triangles at "
                          f"{tolerance_mm:g} mm, over the limit of {MAX_TRIANGLES:.3g} a part (a coarser tolerance?)")
    return count


def picture_meshes(shapes: list[Shape], tolerance_mm: float,
                   prisms: list[SlottedPrism | RingPrism | None] | None = None) -> list[trimesh.Trimesh]:
    """Unmerged triangle soups of many shapes, meshed together in one pass (for pictures: no
    watertightness needed, no per-part meshing call); a shape with its ``prisms`` entry is meshed
    from that (:func:`mesh_prism`)."""
    prisms = prisms or [None] * len(shapes)
    brep = [shape for shape, prism in zip(shapes, prisms) if prism is None]
    if brep:
        compound = kernel.compound(brep)
        for name in MESHERS:
            if _triangulate(compound, tolerance_mm, name):
                break
    with _scratch() as scratch:
        path = str(Path(scratch) / "part.stl")
        meshes = [mesh_prism(prism, tolerance_mm, picture=True) if prism is not None
                  else _snapped(_stl_read_back(shape, path)) for shape, prism in zip(shapes, prisms)]
    if brep:
        _release(compound)
    return meshes


def mesh_prism(prism: SlottedPrism | RingPrism, tolerance_mm: float, picture: bool = False) -> trimesh.Trimesh:
    """Closed triangle mesh of a slotted plate or a ring (:func:`_ring_mesh`); for a ``picture`` the
    slot ends (a pixel wide there) by the chord tolerance alone, without the angular deflection."""
    if isinstance(prism, RingPrism):
        vertices, faces = _ring_mesh(prism, tolerance_mm)
    else:
        vertices, faces = _plate_mesh(prism, tolerance_mm, math.pi if picture else ANGULAR_DEFLECTION_RAD)
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    mesh.metadata |= {"mesher": "prism", "bodies": 1}    # closed by construction: write_stl checks it
    return mesh


def _ring_mesh(ring: RingPrism, tolerance_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Both circles in the same n equal chords (n for the outer radius, the finer one), starting on
    +x like the revolve's seam; a disc's faces fan from its centre."""
    n = 2 * _arc_chords(ring.r_outer_mm, tolerance_mm)
    t = 2 * np.pi * np.arange(n) / n
    circle = np.column_stack([np.cos(t), np.sin(t)])
    j, k = np.arange(n), (np.arange(n) + 1) % n
    z0, z1 = ring.z0_mm, ring.z1_mm
    if ring.r_inner_mm > 0:
        rings = [ring.r_outer_mm * circle, ring.r_inner_mm * circle]      # o0 0..n-1, i0 n.., o1 2n.., i1 3n..
        vertices = np.vstack([np.column_stack([p, np.full(n, z)]) for z in (z0, z1) for p in rings])
        o0, i0, o1, i1 = j, n + j, 2 * n + j, 3 * n + j
        ok0, ik0, ok1, ik1 = k, n + k, 2 * n + k, 3 * n + k
        faces = np.vstack([np.column_stack([o1, ok1, ik1]), np.column_stack([o1, ik1, i1]),       # top
                           np.column_stack([o0, ik0, ok0]), np.column_stack([o0, i0, ik0]),       # bottom
                           np.column_stack([o0, ok0, ok1]), np.column_stack([o0, ok1, o1]),       # outer wall
                           np.column_stack([i0, ik1, ik0]), np.column_stack([i0, i1, ik1])])      # inner wall
    else:
        rim = ring.r_outer_mm * circle
        vertices = np.vstack([np.column_stack([rim, np.full(n, z0)]), np.column_stack([rim, np.full(n, z1)]),
                              [[0.0, 0.0, z0], [0.0, 0.0, z1]]])
        c0, c1 = np.full(n, 2 * n), np.full(n, 2 * n + 1)
        faces = np.vstack([np.column_stack([c1, n + j, n + k]), np.column_stack([c0, k, j]),
                           np.column_stack([j, k, n + k]), np.column_stack([j, n + k, n + j])])
    if ring.axis_y:                                  # turned −90° about x: (x, y, z) → (x, z, −y)
        vertices = np.column_stack([vertices[:, 0], vertices[:, 2], -vertices[:, 1]])
    return vertices, faces


def _plate_mesh(prism: SlottedPrism, tolerance_mm: float, angle_rad: float) -> tuple[np.ndarray, np.ndarray]:
    """Closed triangle mesh of a slotted plate: each semicircular slot end in n equal chords, n the
    least meeting both the chord deviation ``tolerance_mm`` and the angular deflection (as BRepMesh
    divides a circle), vertices on the exact arcs; the face triangulated by manifold3d (outer ring
    counter-clockwise, slots clockwise), bottom reversed, one quad (two triangles) per ring edge."""
    rings = [np.asarray(prism.outer_mm, float)]
    if len(prism.slots):
        c, u, s, r = prism.cores()
        n = np.column_stack([-u[:, 1], u[:, 0]])
        k = _arc_chords(float(r.min()), tolerance_mm, angle_rad)
        theta = np.pi * np.arange(k + 1) / k
        end = c + u * s[:, None]                   # +u end: from +n through +u to −n (clockwise)
        start = c - u * s[:, None]                 # −u end: from −n through −u back towards +n
        arc = lambda centre, a, b, t: centre[:, None, :] + r[:, None, None] * (
            np.cos(t)[None, :, None] * a[:, None, :] + np.sin(t)[None, :, None] * b[:, None, :])
        slot_rings = np.concatenate([arc(end, n, u, theta), arc(start, -n, -u, theta)], axis=1)
        rings += list(slot_rings)
    tri = manifold3d.triangulate(rings)
    flat = np.concatenate(rings)
    m = len(flat)
    vertices = np.vstack([np.column_stack([flat, np.full(m, prism.z0_mm)]),
                          np.column_stack([flat, np.full(m, prism.z1_mm)])])
    first = np.cumsum([0] + [len(ring) for ring in rings[:-1]])
    a = np.concatenate([f + np.arange(len(ring)) for f, ring in zip(first, rings)])
    b = np.concatenate([f + (np.arange(len(ring)) + 1) % len(ring) for f, ring in zip(first, rings)])
    faces = np.vstack([tri + m, tri[:, ::-1], np.column_stack([a, b, b + m]), np.column_stack([a, b + m, a + m])])
    if prism.axis_x:                                 # profile in (y, z), extruded along x: (u, v, w) → (w, u, v)
        vertices = vertices[:, [2, 0, 1]]
    return vertices, faces


def x_prism(shape: Shape, tolerance_mm: float) -> SlottedPrism | None:
    """One solid swept straight along x from a (y, z) face without holes (a cylindrical lens, a 2-D
    polyfocal part: two caps normal to x, every other face a plane or an extrusion along x) as a
    :class:`SlottedPrism`: the cap's boundary divided by OCCT's edge criteria (sagitta ≤
    ``tolerance_mm``, turning ≤ the angular deflection; vertices on the exact edges), so the walls
    are quads between the caps. BRepMesh took 0.5 s on each 3.4 mm strip of spline wall of the
    seed-001 lens. None for any other shape."""
    solids = kernel.solids(shape)
    if len(solids) != 1:
        return None
    caps = []
    for face in kernel.faces(solids[0]):
        surface = BRepAdaptor_Surface(face)
        kind = surface.GetType()
        along = (surface.Direction() if kind == GeomAbs_SurfaceOfExtrusion
                 else surface.Plane().Axis().Direction() if kind == GeomAbs_Plane else None)
        if along is None or kind == GeomAbs_SurfaceOfExtrusion and abs(abs(along.X()) - 1.0) > 1e-12:
            return None
        if kind == GeomAbs_Plane and abs(abs(along.X()) - 1.0) < 1e-12:
            caps.append(face)
        elif kind == GeomAbs_Plane and abs(along.X()) > 1e-12:
            return None
    if len(caps) != 2 or any(_wire_count(cap) != 1 for cap in caps):
        return None
    x0, x1 = sorted(float(kernel.vertices(cap)[0, 0]) for cap in caps)     # a cap lies in x = const
    ring = []
    walk = BRepTools_WireExplorer(BRepTools.OuterWire_s(caps[0]))
    while walk.More():
        edge = walk.Current()
        points = GCPnts_TangentialDeflection(BRepAdaptor_Curve(edge), ANGULAR_DEFLECTION_RAD, tolerance_mm)
        yz = [(points.Value(i).Y(), points.Value(i).Z()) for i in range(1, points.NbPoints() + 1)]
        ring += (yz[::-1] if edge.Orientation() == TopAbs_REVERSED else yz)[:-1]
        walk.Next()
    ring = np.array(ring)
    y, z = ring.T
    if np.dot(y, np.roll(z, -1)) - np.dot(z, np.roll(y, -1)) < 0:      # counter-clockwise in (y, z)
        ring = ring[::-1]
    return SlottedPrism(ring, np.empty((0, 5)), x0, x1, axis_x=True)


def estimate_triangles(shape: Shape, tolerance_mm: float) -> int:
    """Triangles BRepMesh makes on ``shape``'s curved faces: each face's area over that of an
    equilateral triangle whose side s meets the chord tolerance on the face's radius R (sagitta
    s²/8R ≤ tolerance, turning s/R ≤ the angular deflection). R: of the sphere or torus (minor);
    of other surfaces half their bounding box's middle side; a cylinder is two triangles per
    chord of its arc. Planes are meshed from their edges only (not counted). BRepMesh makes :data:`BREPMESH_DENSITY` times that count (measured:
    a Ø400 mm sphere at 0.05 mm, 40,298 triangles)."""
    total = 0.0
    for face in kernel.faces(shape):
        surface = BRepAdaptor_Surface(face)
        kind = surface.GetType()
        if kind == GeomAbs_Plane:
            continue
        if kind == GeomAbs_Cylinder:          # curved one way: strips along the axis, two triangles each
            radius = surface.Cylinder().Radius()
            side = min(math.sqrt(8 * radius * tolerance_mm), ANGULAR_DEFLECTION_RAD * radius)
            total += 2 * (surface.LastUParameter() - surface.FirstUParameter()) * radius / side / BREPMESH_DENSITY
            continue
        if kind == GeomAbs_Sphere:
            radius = surface.Sphere().Radius()
        elif kind == GeomAbs_Torus:
            radius = surface.Torus().MinorRadius()
        else:                                 # the middle extent: a thin band of a revolved face is as
            lo, hi = kernel.bounding_box([face])  # curved as its ring, not as its width
            radius = float(np.sort(hi - lo)[1]) / 2
        side = min(math.sqrt(8 * radius * tolerance_mm), ANGULAR_DEFLECTION_RAD * radius)
        if side > 0:
            total += kernel.area(face) / (math.sqrt(3) / 4 * side * side)
    return int(BREPMESH_DENSITY * total)


def prism_triangles(prism: SlottedPrism | RingPrism, tolerance_mm: float) -> int:
    """Triangles :func:`mesh_prism` makes on ``prism``, counted without meshing: a ring 8 per chord
    (a disc 4); a plate of m boundary vertices and h slots m + 2h − 2 on each face (a polygon with
    holes) and two per wall quad."""
    if isinstance(prism, RingPrism):
        return (8 if prism.r_inner_mm > 0 else 4) * 2 * _arc_chords(prism.r_outer_mm, tolerance_mm)
    vertices, holes = len(prism.outer_mm), len(prism.slots)
    if holes:
        radius = float(np.min(prism.slots[:, 3])) / 2
        vertices += holes * 2 * (_arc_chords(radius, tolerance_mm) + 1)
    return 2 * (vertices + 2 * holes - 2) + 2 * vertices


def part_triangles(shape: Shape, tolerance_mm: float, prism: SlottedPrism | RingPrism | None = None) -> int:
    """A part's STL triangles at ``tolerance_mm``, estimated before meshing (the count of its prism,
    else :func:`estimate_triangles`)."""
    return prism_triangles(prism, tolerance_mm) if prism is not None else estimate_triangles(shape, tolerance_mm)


def _wire_count(face) -> int:
    walk, count = TopExp_Explorer(face, TopAbs_WIRE), 0
    while walk.More():
        count, _ = count + 1, walk.Next()
    return count


def _arc_chords(radius_mm: float, tolerance_mm: float, angle_rad: float = ANGULAR_DEFLECTION_RAD) -> int:
    """Chords per semicircle: sagitta ≤ tolerance and turning angle ≤ ``angle_rad``."""
    half = math.acos(max(1.0 - tolerance_mm / radius_mm, -1.0))
    return max(2, math.ceil(math.pi / angle_rad - 1e-9), math.ceil(math.pi / (2 * half) - 1e-9))


def _scratch() -> tempfile.TemporaryDirectory:
    """A folder for OCCT's STL writer to hand a triangulation over: in memory (/dev/shm) where there
    is one — a disk folder cost 3–6 ms a part to make and remove, 0.7 s for a Ka array's 130 parts."""
    shm = Path("/dev/shm")
    memory = shm.is_dir() and os.access(shm, os.W_OK)
    if memory:
        _remove_stale(shm)
    return tempfile.TemporaryDirectory(prefix=f"{SCRATCH_PREFIX}{os.getpid()}-", dir=shm if memory else None)


@functools.cache
def _remove_stale(folder: Path) -> None:
    """Once per process: scratch folders of processes no longer running (SIGKILL skips their
    cleanup; /dev/shm keeps them until reboot)."""
    for path in folder.glob(f"{SCRATCH_PREFIX}*-*"):
        pid = path.name[len(SCRATCH_PREFIX):].split("-", 1)[0]
        if pid.isdigit() and not _running(int(pid)):
            shutil.rmtree(path, ignore_errors=True)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:          # another user's process
        return True
    return True


def _triangulate(shape: Shape, tolerance_mm: float, mesher: str, parallel: bool = True) -> bool:
    """(Re-)mesh ``shape`` in place; True when every face got a triangulation. Not ``parallel``: one
    face at a time — a part's STL (the 9 m lens: 130k triangles) then peaks 60 MB lower for the
    same CPU time, ~0.4 s more wall time (≤ 500 MB)."""
    BRepTools.Clean_s(shape)
    BRepMesh_IncrementalMesh(shape, _parameters(tolerance_mm, MESHERS[mesher], parallel))
    return _fully_triangulated(shape)


def _release(shape: Shape) -> None:
    """Drop the shape's triangulation once read (tens of MB for a spline lens, kept on the shape
    otherwise) and give the freed heap back to the system, so meshing part after part does not
    raise the build's peak memory (≤ 500 MB)."""
    BRepTools.Clean_s(shape)
    trim = getattr(ctypes.CDLL(None), "malloc_trim", None)       # glibc; elsewhere nothing to do
    if trim is not None:
        trim(0)


def _fully_triangulated(shape) -> bool:
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        if BRep_Tool.Triangulation_s(TopoDS.Face(explorer.Current()), TopLoc_Location()) is None:
            return False
        explorer.Next()
    return True


def _parameters(tolerance_mm: float, algorithm, parallel: bool) -> IMeshTools_Parameters:
    params = IMeshTools_Parameters()
    params.Deflection = tolerance_mm
    params.Angle = ANGULAR_DEFLECTION_RAD
    params.Relative = False
    params.InParallel = parallel
    params.MeshAlgo = algorithm
    return params


def _solid_mesh(path: str) -> trimesh.Trimesh:
    """One solid's triangulation (an STL file), merged and cleaned by trimesh."""
    mesh = trimesh.load(path, file_type="stl", process=False)
    mesh.merge_vertices()
    mesh.update_faces(mesh.nondegenerate_faces())
    mesh.remove_unreferenced_vertices()
    return mesh


def _stl_read_back(shape, path: str) -> trimesh.Trimesh:
    """The triangulation of ``shape`` via OCCT's binary STL writer, read by trimesh as it is."""
    return trimesh.load(_write_triangulation(shape, path), file_type="stl", process=False)


def _write_triangulation(shape, path: str) -> str:
    """``shape``'s triangulation as binary STL at ``path`` (OCCT's writer); returns ``path``."""
    writer = StlAPI_Writer()
    writer.ASCIIMode = False
    if not writer.Write(shape, path):
        raise OSError(errno.EIO, f"OCCT could not write the triangulation to {path} (disk full or a file-size "
                      "limit?)")
    return path


SNAP_MM = 1e-9       # coordinates below this are written as 0 (run-to-run noise of OCCT booleans)


def _snapped(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """``mesh`` with coordinates below :data:`SNAP_MM` set to 0: OCCT's parallel booleans leave ±1e-30
    on the same point from run to run, which reordered equal-depth triangles in the report's
    pictures (a few pixels one grey level apart between two builds of the same spec)."""
    mesh.vertices = np.where(np.abs(mesh.vertices) < SNAP_MM, 0.0, mesh.vertices)
    return mesh


def write_stl(shape: Shape, path: Path, tolerance_mm: float, prism: SlottedPrism | RingPrism | None = None) -> trimesh.Trimesh:
    """Binary STL of ``shape`` (meshed from ``prism`` when given, :func:`mesh_prism`); near-zero
    coordinates snapped to 0 so the bytes are reproducible.
    ``metadata["watertight"]``: the file as any STL reader sees it (vertices merged by position)
    is a closed 2-manifold, False when bodies touch along edges (4 faces on an edge) even though
    each body (``bodies_watertight``) is closed."""
    mesh = _snapped(mesh_prism(prism, tolerance_mm) if prism is not None else mesh_shape(shape, tolerance_mm))
    mesh.metadata["watertight"] = bool(trimesh.Trimesh(mesh.vertices, mesh.faces).is_watertight)
    mesh.metadata.setdefault("bodies_watertight", mesh.metadata["watertight"])     # one body (a prism)
    path.write_bytes(trimesh.exchange.stl.export_stl(mesh))
    return mesh
