"""Printable parts of a lattice lens: the graded cubic lattice (:mod:`lattice_mesh`) or sheet gyroid
(:mod:`gyroid_mesh`) trimmed to the lens body by manifold3d, its solid skin, registration pins, and the split to the printer bed.

Frame: the printer's; z up from the bed. A sphere is printed as two identical hemispheres on their
flat faces (the lattice grid is offset by half a cell so the equator is a cell-face plane and the
hemisphere is its own mirror image; pins at 0°, 120°, 240° map onto themselves when the lower half
is turned over). A cylinder (parallel-plate lens) is printed flat, its plates' faces on the bed.
Parts larger than the bed are cut by vertical planes, pins across every cut.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import math
from dataclasses import dataclass

import numpy as np
from manifold3d import Manifold, Mesh, Mesh64, OpType

from antenna_cad.printed.fill import FillMap, rod_width_mm
from antenna_cad.printed.gyroid_mesh import gyroid_lattice
from antenna_cad.printed.lattice import gyroid_edge_mm
from antenna_cad.printed.lattice_mesh import cross_rows, lattice_triangles, weld

MAX_SEGMENTS = 256


@dataclass(frozen=True)
class Pins:
    diameter_mm: float
    length_mm: float
    clearance_mm: float
    wall_mm: float

    @property
    def hole_radius(self) -> float:
        return (self.diameter_mm + self.clearance_mm) / 2

    @property
    def boss_radius(self) -> float:
        return self.hole_radius + self.wall_mm

    @property
    def depth(self) -> float:
        """Blind-hole depth on each side of a cut (half a pin and 0.5 mm to spare)."""
        return self.length_mm / 2 + 0.5


@dataclass(frozen=True)
class PrintedPart:
    label: str
    role: str                   # "lens" or "pin"
    count: int                  # copies to print
    vertices: np.ndarray        # placed on the bed: bounding box from the origin
    faces: np.ndarray
    volume_mm3: float | None = None     # the mesh's (:func:`mesh_volume`): computed when not given

    def __post_init__(self):
        if self.volume_mm3 is None:
            object.__setattr__(self, "volume_mm3", mesh_volume(self.vertices, self.faces))
    offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)   # vertices + offset_mm: the part in the lens frame

    @property
    def size_mm(self) -> tuple[float, float, float]:
        ext = self.vertices.max(axis=0) - self.vertices.min(axis=0)
        return float(ext[0]), float(ext[1]), float(ext[2])


@dataclass(frozen=True)
class PrintedLens:
    parts: tuple[PrintedPart, ...]
    cells: int                  # lattice cells (all copies)
    lattice_triangles: int      # before trimming (all copies)
    body_volume_mm3: float      # lattice + skin (all copies); a sphere's before its pins, a body's with its
                                # pin bosses and holes (a few mm³ a pin: the boss's solid less its lattice and hole)
    reference_volume_mm3: float  # ∫ fill dV + skin, analytic
    pins: int                   # pins across all cuts
    cuts: int                   # bed cuts (besides a sphere's equator)
    unpinned_cuts: int          # cuts with no room for a pin boss (aligned by hand)


def mesh_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    t = vertices[faces]
    return float(np.einsum("ij,ij->i", t[:, 0], cross_rows(t[:, 1], t[:, 2])).sum() / 6.0)


def closed_and_oriented(faces: np.ndarray) -> bool:
    """Every directed edge once and its reverse once: watertight, consistently oriented, 2-manifold edges."""
    f = np.asarray(faces, np.int64)
    n = int(f.max()) + 1
    nxt = np.roll(f, -1, axis=1)
    fwd = np.sort((f * n + nxt).ravel())
    if np.any(fwd[1:] == fwd[:-1]):
        return False
    return bool(np.array_equal(fwd, np.sort((nxt * n + f).ravel())))    # the reverses: the same set


def segments(radius_mm: float, tolerance_mm: float) -> int:
    """Facets around a circle of ``radius_mm`` for a chord deviation ≤ ``tolerance_mm``."""
    n = math.pi / math.acos(max(1 - tolerance_mm / radius_mm, -1.0))
    return int(min(MAX_SEGMENTS, max(16, 4 * math.ceil(n / 4))))


def _cells(shape: str, r_in: float, height: float | None, cell: float) -> tuple[np.ndarray, np.ndarray]:
    """Integer indices of the cells (centres (i, j, k + ½)·a, k ≥ 0) touching the inner body, and their
    centres' radius of the law (sphere: |c|; cylinder: in the plane)."""
    n = int(math.ceil(r_in / cell)) + 1
    top = n if shape == "sphere" else int(math.ceil(height / cell))
    g = np.arange(-n, n + 1)
    i, j, k = np.meshgrid(g, g, np.arange(top), indexing="ij")
    idx = np.stack([i, j, k], -1).reshape(-1, 3)
    c = idx * cell + np.array([0.0, 0.0, cell / 2])
    rad = np.linalg.norm(c if shape == "sphere" else c[:, :2], axis=1)
    keep = rad < r_in + cell * (math.sqrt(3) / 2 if shape == "sphere" else math.sqrt(2) / 2)
    return idx[keep], rad[keep]


def rounded_widths(fmap: FillMap, rad: np.ndarray, step: float, wall: float, gap: float) -> np.ndarray:
    """Rod widths at the cell centres, rounded to ``step`` and kept printable."""
    w = rod_width_mm(fmap, rad)
    lo, hi = math.ceil(wall / step) * step, math.floor((fmap.cell_mm - gap) / step) * step
    return np.clip(np.round(w / step) * step, lo, hi)


def to_manifold(vertices: np.ndarray, faces: np.ndarray, double: bool = False) -> Manifold:
    """A closed mesh as a manifold3d solid (``double``: float64 vertices, as a body joined to its grid bit
    for bit needs); a mesh manifold3d rejects raises."""
    if double:
        mesh = Mesh64(vert_properties=np.ascontiguousarray(vertices, np.float64),
                      tri_verts=np.ascontiguousarray(faces, np.uint64))
    else:
        mesh = Mesh(vert_properties=np.ascontiguousarray(vertices, np.float32),
                    tri_verts=np.ascontiguousarray(faces, np.uint32))
    m = Manifold(mesh)
    if m.status().name != "NoError":
        raise RuntimeError(f"lattice mesh rejected by manifold3d: {m.status().name}")
    return m


def mesh_arrays(m: Manifold, double: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of a manifold3d solid (``double``: from its float64 mesh, int64 faces)."""
    mesh = m.to_mesh64() if double else m.to_mesh()
    return np.asarray(mesh.vert_properties[:, :3], float), np.asarray(mesh.tri_verts, np.int64 if double else np.int32)


M_MMAP_THRESHOLD = -3       # glibc mallopt parameter
MMAP_THRESHOLD = 1 << 20    # bytes: blocks from 1 MiB up are mapped apart and unmapped when freed


def bound_heap() -> None:
    """Keep large blocks out of the C heap (glibc; nothing elsewhere). glibc raises its mmap threshold
    to the largest block freed (up to 32 MB), after which the lattice's and the parts' temporaries
    (numpy arrays of 1–100 MB) are carved from the heap and, freed, stay resident behind what is kept
    (a build of the Ø120 mm sphere then peaks 100–200 MB higher). A fixed threshold stops that."""
    libc = ctypes.util.find_library("c")
    mallopt = getattr(ctypes.CDLL(libc), "mallopt", None) if libc else None
    if mallopt is not None:
        mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)


def _cylinder_along(axis: int, radius: float, z0: float, z1: float, n: int) -> Manifold:
    """A cylinder of ``radius`` from z0 to z1 along ``axis`` (0 x, 2 z), through the origin."""
    c = Manifold.cylinder(z1 - z0, radius, radius, n).translate([0.0, 0.0, z0])
    return c if axis == 2 else c.rotate([0.0, 90.0, 0.0])


def _bed_planes(extent: float, bed: float, lo: float) -> list[float]:
    count = math.ceil(extent / bed - 1e-9)
    return [lo + extent * q / count for q in range(1, count)]


def cut_pin_points(axis: int, c: float, planes: dict, pins: Pins, u_range: tuple[float, float],
                   z_range: tuple[float, float], fits) -> list[tuple[float, float]]:
    """Two pin positions (u along the other horizontal axis, z) on the cut plane x_axis = c where
    ``fits(u, z)`` holds, clear of the other cuts: the farthest-apart pair of a grid of candidates."""
    rb = pins.boss_radius
    cand = [(u, z) for u in np.arange(*u_range, rb) if all(abs(u - q) >= rb + pins.depth for q in planes[1 - axis])
            for z in np.arange(*z_range, rb) if fits(u, z)]
    if len(cand) < 2:
        return cand
    p = np.array(cand)
    d = np.linalg.norm(p[:, None] - p[None], axis=2)
    a, b = np.unravel_index(np.argmax(d), d.shape)
    return [tuple(p[a]), tuple(p[b])]


def cut_pin_solids(axis: int, c: float, points, pins: Pins, n: int) -> tuple[list, list]:
    """(bosses, holes) of the pins at ``points`` (u, z) across the cut plane x_axis = c: a solid boss
    one wall around each blind hole, the hole half a pin deep (and 0.5 mm to spare) on each side."""
    span = pins.depth + pins.wall_mm
    rot = [0.0, 0.0, 0.0] if axis == 0 else [0.0, 0.0, 90.0]
    bosses, holes = [], []
    for u, z in points:
        at = [0.0, 0.0, z]
        at[axis], at[1 - axis] = c, u
        bosses.append(_cylinder_along(0, pins.boss_radius, -span, span, n).rotate(rot).translate(at))
        holes.append(_cylinder_along(0, pins.hole_radius, -pins.depth, pins.depth, n).rotate(rot).translate(at))
    return bosses, holes


def pin_part(pins: Pins, count: int, tolerance_mm: float) -> PrintedPart:
    """The registration pin, printed ``count`` times."""
    pv, pf = mesh_arrays(_cylinder_along(2, pins.diameter_mm / 2, 0.0, pins.length_mm,
                                         segments(pins.diameter_mm / 2, tolerance_mm)))
    return PrintedPart("pin", "pin", count, pv - pv.min(axis=0), pf)


def _pin_solids(shape: str, pins: Pins, planes: dict, r_in: float, height: float, copies: int,
                tolerance_mm: float) -> tuple[list, list, int, int]:
    """(bosses, holes, pins to print, cuts without room for a pin): a sphere's three equator pins at
    0°, 120°, 240° against the skin, and two across every vertical bed cut."""
    bosses, holes = [], []
    count = unpinned = 0
    pn = segments(pins.boss_radius, tolerance_mm)
    rb = pins.boss_radius
    if shape == "sphere":
        rho = r_in - rb
        for q in range(3):
            t = 2 * math.pi * q / 3
            at = [rho * math.cos(t), rho * math.sin(t), 0.0]
            bosses.append(_cylinder_along(2, rb, 0.0, pins.depth + pins.wall_mm, pn).translate(at))
            holes.append(_cylinder_along(2, pins.hole_radius, -1.0, pins.depth, pn).translate(at))
        count += 3
    for axis in (0, 1):
        for c in planes[axis]:
            fits = lambda u, z: math.sqrt(c * c + u * u + (z * z if shape == "sphere" else 0.0)) < r_in - rb - 1
            points = cut_pin_points(axis, c, planes, pins, (-r_in, r_in), (rb + 1, height - rb), fits)
            unpinned += not points
            b, h = cut_pin_solids(axis, c, points, pins, pn)
            bosses += b
            holes += h
            count += copies * len(points)
    return bosses, holes, count, unpinned


def build_printed_lens(shape: str, radius_mm: float, height_mm: float | None, fmap: FillMap, *, skin_mm: float,
                       wall_mm: float, gap_mm: float, width_step_mm: float, bed_mm: tuple[float, float, float],
                       pins: Pins | None, tolerance_mm: float, reference_volume_mm3: float) -> PrintedLens:
    """The printable parts of a sphere (two hemispheres) or a parallel-plate cylinder of ``radius_mm``."""
    bound_heap()
    a = fmap.cell_mm
    r_in = radius_mm - skin_mm
    height = radius_mm if shape == "sphere" else height_mm
    copies = 2 if shape == "sphere" else 1
    if fmap.lattice == "gyroid":
        body = gyroid_lattice(shape, r_in + skin_mm / 2, 0.0, height, fmap, gyroid_edge_mm(a, fmap.fill_range))
        body = body.trim_by_plane([0.0, 0.0, 1.0], 0.0)
        cells = round((2 / 3 * math.pi * r_in**3 if shape == "sphere" else math.pi * r_in**2 * height) / a**3)
        triangles = body.num_tri()
    else:
        idx, rad = _cells(shape, r_in, height_mm, a)
        w = rounded_widths(fmap, rad, width_step_mm, wall_mm, gap_mm)
        v, f = weld(lattice_triangles(idx, w, a))
        body = to_manifold(v + np.array([0.0, 0.0, a / 2]), f)
        cells, triangles = len(idx), len(f)
        del v, f
    n = segments(radius_mm, tolerance_mm)
    keep = Manifold.sphere(r_in + skin_mm / 2, n) if shape == "sphere" else \
        _cylinder_along(2, r_in + skin_mm / 2, 0.0, height, n)
    body = body ^ keep
    if skin_mm > 0:
        if shape == "sphere":
            shell = (Manifold.sphere(radius_mm, n) - Manifold.sphere(r_in, n)).trim_by_plane([0.0, 0.0, 1.0], 0.0)
        else:
            shell = _cylinder_along(2, radius_mm, 0.0, height, n) - _cylinder_along(2, r_in, -1.0, height + 1, n)
        body = body + shell
    body_volume = body.volume() * copies
    planes = {0: _bed_planes(2 * radius_mm, bed_mm[0], -radius_mm), 1: _bed_planes(2 * radius_mm, bed_mm[1], -radius_mm)}
    if height > bed_mm[2]:
        raise ValueError(f"fabrication.bed.z_mm: a part {height:.1f} mm tall does not fit the bed "
                         f"({bed_mm[2]:g} mm); horizontal cuts are not made")
    pin_count = unpinned = 0
    if pins is not None:
        bosses, holes, pin_count, unpinned = _pin_solids(shape, pins, planes, r_in, height, copies, tolerance_mm)
        if bosses:
            inner = Manifold.sphere(radius_mm, n) if shape == "sphere" else _cylinder_along(2, radius_mm, 0, height, n)
            body = (body + (Manifold.batch_boolean(bosses, OpType.Add) ^ inner)) - Manifold.batch_boolean(holes, OpType.Add)
    pieces = [body]
    del body
    for axis in (0, 1):
        normal = [0.0, 0.0, 0.0]
        normal[axis] = 1.0
        for c in planes[axis]:
            pieces = [p for piece in pieces for p in piece.split_by_plane(normal, c) if not p.is_empty()]
    parts = []
    pieces.sort(key=lambda m: tuple(np.round(m.bounding_box(), 6)))
    for q in range(len(pieces)):
        pv, pf = mesh_arrays(pieces[q])
        pieces[q] = None                                          # one copy of each part at a time
        label = f"lens-{q + 1:02d}" if len(pieces) > 1 or shape == "sphere" else "lens"
        lo = pv.min(axis=0)
        parts.append(PrintedPart(label, "lens", copies, pv - lo, pf, offset_mm=tuple(float(x) for x in lo)))
    if pin_count:
        parts.append(pin_part(pins, pin_count, tolerance_mm))
    return PrintedLens(tuple(parts), cells * copies, triangles * copies, body_volume, reference_volume_mm3,
                       pin_count, len(planes[0]) + len(planes[1]), unpinned)

