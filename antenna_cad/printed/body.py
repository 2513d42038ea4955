"""A lattice lens body of any section: a graded (or uniform) cubic lattice inside a solid skin, split
to the printer bed, with the mesh booleans only where the lattice meets the skin.

The body is a 2-D section, ``revolved`` about z (a body of revolution, section (r, z)) or
``extruded`` along z between two plates (section (x, y), height a whole number of cells). Cells are
sorted by where they lie: *inner* cells, whose whole cube is inside the skin's inner surface, are
meshed cell by cell (:mod:`lattice_mesh`) and never pass through a boolean; *boundary* cells are
meshed, trimmed at mid-skin and joined to the skin by manifold3d. The two meshes meet on cell faces:
the end caps there are dropped from both and the square ring between unequal rods added, so the
welded part is closed. Bed cuts lie on cell faces, so a cut only partitions the cells (each part's
lattice is capped there) and cuts the skin. Cost: the boolean grows with the body's surface, the
rest linearly with its cells.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from manifold3d import CrossSection, Manifold, OpType
from shapely.geometry import Polygon, box

from antenna_cad.printed.lattice_mesh import WELD_BITS, WELD_MM, _square, cross_rows, lattice_triangles, weld
from antenna_cad.printed.parts import (Pins, PrintedLens, PrintedPart, cut_pin_points, cut_pin_solids, mesh_arrays,
                                      mesh_volume, pin_part, to_manifold)
from antenna_cad.printed.parts import segments as circle_segments

_DIRS = np.array([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)], np.int64)


@dataclass(frozen=True)
class Envelope:
    """The body's section: ``revolved`` — (r, z) with r ≥ 0, about z; ``extruded`` — (x, y), from
    z = 0 to ``height_mm``."""
    kind: str
    section: Polygon
    height_mm: float | None = None

    @property
    def full(self) -> Polygon:
        """The section a point's distance to the surface is measured in: a revolved section mirrored
        about the axis (the axis is no surface)."""
        if self.kind == "extruded":
            return self.section
        mirrored = shapely.affinity.scale(self.section, -1.0, 1.0, origin=(0.0, 0.0))
        return self.section.union(mirrored).buffer(0)

    def coords(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points (n, 3) in the section's plane: (r, z) or (x, y)."""
        if self.kind == "revolved":
            return np.hypot(p[:, 0], p[:, 1]), p[:, 2]
        return p[:, 0], p[:, 1]

    def polygon(self, offset_mm: float, tolerance_mm: float) -> Polygon:
        """The full section grown by ``offset_mm`` (negative: shrunk), simplified to ``tolerance_mm``."""
        poly = self.full.buffer(offset_mm, join_style="mitre") if offset_mm else self.full
        return poly.simplify(tolerance_mm)

    def solid(self, offset_mm: float, segments: int, tolerance_mm: float) -> Manifold:
        """The body grown by ``offset_mm`` as a closed solid (section as :meth:`polygon`)."""
        poly = self.polygon(offset_mm, tolerance_mm)
        if self.kind == "revolved":
            poly = poly.intersection(box(0.0, -1e6, 1e6, 1e6))
        polys = [shapely.geometry.polygon.orient(g, 1.0) for g in getattr(poly, "geoms", [poly])]
        contours = [np.asarray(g.exterior.coords[:-1], float) for g in polys] + \
            [np.asarray(h.coords[:-1], float) for g in polys for h in g.interiors]
        cs = CrossSection(contours)
        if self.kind == "revolved":
            return Manifold.revolve(cs, segments)
        return Manifold.extrude(cs, self.height_mm)


def section_volume_mm3(env: Envelope, offset_mm: float = 0.0) -> float:
    """Volume of the body grown by ``offset_mm``: Pappus for a revolved section, area × height else."""
    poly = env.full.buffer(offset_mm, join_style="mitre") if offset_mm else env.full
    if env.kind == "extruded":
        return float(poly.area * env.height_mm)
    half = poly.intersection(box(0.0, -1e6, 1e6, 1e6))
    return float(2 * math.pi * half.area * half.centroid.x)


def reference_volume_mm3(env: Envelope, fill_at, skin_mm: float, step_mm: float) -> float:
    """∫ fill dV over the skin's inner surface plus the skin, the analytic reference of the meshed
    body: ``fill_at(u, w)`` on a midpoint grid of ``step_mm`` over the section (r, z) or (x, y)."""
    poly = env.full.buffer(-skin_mm, join_style="mitre") if skin_mm else env.full
    u0, w0, u1, w1 = poly.bounds
    if env.kind == "revolved":
        u0 = 0.0
    u = np.arange(u0 + step_mm / 2, u1, step_mm)
    w = np.arange(w0 + step_mm / 2, w1, step_mm)
    U, W = np.meshgrid(u, w, indexing="ij")
    inside = shapely.contains_xy(poly, U, W)
    f = np.where(inside, fill_at(U, W), 0.0)
    weight = 2 * math.pi * U if env.kind == "revolved" else env.height_mm
    lattice = float((f * weight).sum() * step_mm * step_mm)
    return lattice + section_volume_mm3(env) - section_volume_mm3(env, -skin_mm)


def lattice_origin(env: Envelope, cell_mm: float) -> np.ndarray:
    """Cell centres are origin + index·a: on the axis (revolved) or the section's y = 0 line, and half a
    cell above the lower plate (extruded: whole cells between the plates)."""
    return np.array([0.0, 0.0, cell_mm / 2 if env.kind == "extruded" else 0.0])


def _cube_boxes(env: Envelope, centre: np.ndarray, a: float):
    """Rectangles of the section plane that hold each cell's cube: (r, z) of a revolved body (its
    radial span from the nearest to the farthest point of the cube's square), (x, y) of an extruded one."""
    h = a / 2
    if env.kind == "extruded":
        return shapely.box(centre[:, 0] - h, centre[:, 1] - h, centre[:, 0] + h, centre[:, 1] + h)
    near = np.maximum(np.abs(centre[:, :2]) - h, 0.0)
    far = np.abs(centre[:, :2]) + h
    return shapely.box(np.hypot(*near.T), centre[:, 2] - h, np.hypot(*far.T), centre[:, 2] + h)


def body_cells(env: Envelope, cell_mm: float, skin_mm: float,
               tolerance_mm: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(index (n, 3), centres (n, 3) mm, inner (n,) bool) of the cells whose cube reaches into the
    lattice's trim (mid-skin); ``inner``: the whole cube inside the skin's inner surface (these are
    never trimmed). Sections as :meth:`Envelope.polygon`."""
    a = cell_mm
    full = env.full
    margin = a * (math.sqrt(3) if env.kind == "revolved" else math.sqrt(2)) / 2 + 1e-6
    u0, w0, u1, w1 = full.bounds
    if env.kind == "revolved":
        n = int(math.ceil(u1 / a)) + 1
        gx = gy = np.arange(-n, n + 1)
        gz = np.arange(int(math.floor(w0 / a)) - 1, int(math.ceil(w1 / a)) + 2)
    else:
        gx = np.arange(int(math.floor(u0 / a)) - 1, int(math.ceil(u1 / a)) + 2)
        gy = np.arange(int(math.floor(w0 / a)) - 1, int(math.ceil(w1 / a)) + 2)
        gz = np.arange(round(env.height_mm / a))
    i, j, k = np.meshgrid(gx, gy, gz, indexing="ij")
    idx = np.stack([i, j, k], -1).reshape(-1, 3)
    centre = idx * a + lattice_origin(env, a)
    trim, hole = env.polygon(-skin_mm / 2, tolerance_mm), env.polygon(-skin_mm, tolerance_mm)
    u, w = env.coords(centre)
    near = shapely.contains_xy(trim.buffer(margin), u, w)          # the cube may reach the trim
    idx, centre, u, w = idx[near], centre[near], u[near], w[near]
    sure = shapely.contains_xy(hole.buffer(-margin), u, w)          # the cube is surely inside the hole
    band = np.nonzero(~sure)[0]
    boxes = _cube_boxes(env, centre[band], a)
    shapely.prepare(trim)
    shapely.prepare(hole)
    keep = np.ones(len(idx), bool)
    keep[band] = shapely.intersects(trim, boxes)
    inner = sure.copy()
    inner[band] = shapely.contains_properly(hole, boxes)
    return idx[keep], centre[keep], inner[keep]


def _face_keys(index: np.ndarray, step: np.ndarray) -> np.ndarray:
    """Packed key of the face between cell ``index`` and its neighbour ``index + step`` (doubled
    coordinates of the face centre)."""
    d = 2 * index + step + (1 << 20)
    return (d[:, 0] << 42) | (d[:, 1] << 21) | d[:, 2]


def _seam_pairs(index: np.ndarray, inner: np.ndarray, boundary: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(p, q): rows of ``index``, p in ``inner`` and q in ``boundary``, that are face neighbours."""
    zero = np.zeros(3, np.int64)
    keys = _face_keys(index[boundary], zero)
    order = np.argsort(keys)
    ks = keys[order]
    ps, qs = [], []
    for e in _DIRS:
        k = _face_keys(index[inner] + e, zero)
        at = np.searchsorted(ks, k).clip(0, max(len(ks) - 1, 0))
        hit = ks[at] == k if len(ks) else np.zeros(len(k), bool)
        ps.append(inner[hit])
        qs.append(boundary[order[at[hit]]])
    return np.concatenate(ps), np.concatenate(qs)


def _on_faces(tris: np.ndarray, keys: np.ndarray, origin: np.ndarray, a: float) -> np.ndarray:
    """Triangles lying on one of the cell faces ``keys`` (sorted; axis-aligned, on the face plane,
    inside the face square)."""
    flat = (tris[:, 0] == tris[:, 1]) & (tris[:, 0] == tris[:, 2])   # (m, 3): the axis it is flat in (caps: exact)
    hit = np.zeros(len(tris), bool)
    for ax in range(3):
        sel = np.nonzero(flat[:, ax])[0]
        if not len(sel):
            continue
        c = (tris[sel].mean(axis=1) - origin) / a                  # centroids of the flat ones only
        d = 2 * np.round(c).astype(np.int64)                   # the cell line, doubled
        d[:, ax] = np.round(2 * c[:, ax]).astype(np.int64)      # the face plane, doubled (odd)
        on_plane = (np.abs(2 * c[:, ax] - d[:, ax]) < 1e-6) & (d[:, ax] % 2 != 0)
        d += 1 << 20
        k = (d[:, 0] << 42) | (d[:, 1] << 21) | d[:, 2]
        at = np.searchsorted(keys, k).clip(0, len(keys) - 1)
        hit[sel] = on_plane & (keys[at] == k)
    return hit


def _rings(idx_p, idx_q, s_p, s_q, origin, a) -> np.ndarray:
    """Square rings between unequal rods meeting on the face between cells p and q = p + e."""
    out = []
    for ax in range(3):
        for sg in (1, -1):
            e = np.zeros(3, np.int64)
            e[ax] = sg
            sel = np.nonzero(np.all(idx_q - idx_p == e, axis=1) & (s_p != s_q))[0]
            if not len(sel):
                continue
            line = idx_p[sel]
            wide, narrow = np.maximum(s_p[sel], s_q[sel]), np.minimum(s_p[sel], s_q[sel])
            plane = line[:, ax] + 0.5 * sg
            outer = _square(plane, ax, line, wide, a)
            inner = _square(plane, ax, line, narrow, a)
            normal = np.where((s_p[sel] > s_q[sel])[:, None], e, -e).astype(float)
            for c in range(4):
                d = (c + 1) % 4
                t = np.concatenate([np.stack([outer[c], outer[d], inner[d]], 1), np.stack([outer[c], inner[d], inner[c]], 1)])
                n = cross_rows(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
                flip = np.einsum("ij,ij->i", n, np.concatenate([normal, normal])) < 0
                t[flip] = t[flip][:, ::-1]
                out.append(t)
    return np.concatenate(out) + origin if out else np.zeros((0, 3, 3))


def _grid_keys(v: np.ndarray, lo: np.ndarray) -> np.ndarray:
    q = np.round((v - lo) / WELD_MM).astype(np.int64)
    return (q[:, 0] << 2 * WELD_BITS) | (q[:, 1] << WELD_BITS) | q[:, 2]


def _join(grid_tris: np.ndarray, ov: np.ndarray, of: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One indexed mesh of the grid triangles (inner lattice and seam rings, welded on the cell grid)
    and the boolean's mesh (ov, of): a boolean vertex is the grid vertex it equals bit for bit, or
    its own."""
    if not len(grid_tris):
        return ov, of
    gv, gf = weld(grid_tris)
    if not len(ov):
        return gv, gf
    lo = np.minimum(gv.min(axis=0), ov.min(axis=0))
    gk = _grid_keys(gv, lo)
    order = np.argsort(gk)
    at = order[np.searchsorted(gk[order], _grid_keys(ov, lo)).clip(0, len(gk) - 1)]
    same = np.all(gv[at] == ov, axis=1)
    remap = np.where(same, at, np.cumsum(~same) - 1 + len(gv))
    v = np.concatenate([gv, ov[~same]])
    f = np.concatenate([gf, remap[of]])
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    return v[used], (np.cumsum(used) - 1)[f]


def _part(index, width_mm, inn, bnd, a, origin, trim: Manifold, shell: Manifold | None, pins: tuple | None):
    """(vertices, faces, lattice triangles before trimming) of one part: its inner cells meshed, its
    boundary cells trimmed and joined to its piece of skin and its halves of the pin bosses (``pins``:
    bosses, holes), the pin holes drilled, the two welded on their shared faces."""
    tris_in = lattice_triangles(index[inn], width_mm[inn], a) + origin if inn.any() else np.zeros((0, 3, 3))
    tris_bd = lattice_triangles(index[bnd], width_mm[bnd], a) + origin if bnd.any() else np.zeros((0, 3, 3))
    made = len(tris_in) + len(tris_bd)
    piece = to_manifold(*weld(tris_bd), double=True) ^ trim if len(tris_bd) else Manifold()
    if shell is not None:
        piece = piece + shell
    if pins is not None:
        piece = (piece + pins[0]) - pins[1]
    pp, qq = _seam_pairs(index, np.nonzero(inn)[0], np.nonzero(bnd)[0])
    ov, of = mesh_arrays(piece, double=True) if not piece.is_empty() else (np.zeros((0, 3)), np.zeros((0, 3), np.int64))
    rings = np.zeros((0, 3, 3))
    if len(pp):
        seam = np.sort(_face_keys(index[pp], index[qq] - index[pp]))
        keep_in = ~_on_faces(tris_in, seam, origin, a)
        of = of[~_on_faces(ov[of], seam, origin, a)]
        rings = _rings(index[pp], index[qq], width_mm[pp] / 2, width_mm[qq] / 2, origin, a)
        tris_in = tris_in[keep_in]
    v, f = _join(np.concatenate([tris_in, rings]), ov, of)
    return v, f, made


def _placed_part(*args):
    """(lattice triangles made, None or (position key, vertices on the bed, faces, volume, offset)) of one part
    (:func:`_part`): what a child process hands back."""
    v, f, made = _part(*args)
    if not len(f):
        return made, None
    lo = v.min(axis=0)
    placed = v - lo
    return made, (tuple(np.round(np.r_[lo, v.max(axis=0)], 6)), placed, f, mesh_volume(placed, f),
                  tuple(float(x) for x in lo))


def _in_turn(fn, arguments):
    return (fn(*args) for args in arguments)


def _region_of(centre: np.ndarray, planes: dict[int, list[float]]) -> np.ndarray:
    return np.searchsorted(planes[0], centre[:, 0]) * (len(planes[1]) + 1) + np.searchsorted(planes[1], centre[:, 1])


def bed_planes(extent: tuple[float, float], bed: float, a: float, origin: float) -> list[float]:
    """Vertical cut planes over ``extent`` on cell faces (origin + (i + ½)·a), every part ≤ ``bed``
    where the cells allow it."""
    lo, hi = extent
    count = math.ceil((hi - lo) / bed - 1e-9)
    return [origin + (round((lo + (hi - lo) * q / count - origin) / a - 0.5) + 0.5) * a for q in range(1, count)]


def _boss_fits(env: Envelope, inside: Polygon, axis: int, c: float, span: float, radius: float,
               z_range: tuple[float, float]):
    """``fits(u, z)``: a boss of ``radius`` along ``axis`` from c − span to c + span, centred at (u, z) on
    the cut plane, lies inside ``inside`` (a section) and the height ``z_range`` (sampled on its surface)."""
    t, th = np.meshgrid(np.linspace(-span, span, 5), np.linspace(0.0, 2 * math.pi, 16, endpoint=False))
    ring = np.stack([t.ravel(), radius * np.cos(th.ravel()), radius * np.sin(th.ravel())], 1)
    shapely.prepare(inside)

    def fits(u: float, z: float) -> bool:
        p = np.zeros_like(ring)
        p[:, axis], p[:, 1 - axis], p[:, 2] = c + ring[:, 0], u + ring[:, 1], z + ring[:, 2]
        su, sw = env.coords(p)
        return bool(z_range[0] <= p[:, 2].min() and p[:, 2].max() <= z_range[1] and shapely.contains_xy(inside, su, sw).all())
    return fits


def body_pins(env: Envelope, planes: dict, pins: Pins, skin_mm: float, tolerance_mm: float):
    """(bosses, holes, [(axis, c, u, z) per pin], cuts without room for a pin): two pins across every
    bed cut, each boss 1 mm clear of the skin's inner surface (and of a plate of an extruded body)."""
    u0, w0, u1, w1 = env.full.bounds
    rb, span = pins.boss_radius, pins.depth + pins.wall_mm
    inside = env.polygon(-skin_mm - 1.0, tolerance_mm)
    u_range = (-u1, u1) if env.kind == "revolved" else None
    z_range = (w0, w1) if env.kind == "revolved" else (1.0, env.height_mm - 1.0)
    n = circle_segments(rb, tolerance_mm)
    bosses, holes, where, unpinned = [], [], [], 0
    for axis in (0, 1):
        for c in planes[axis]:
            span_u = u_range or ((u0, u1), (w0, w1))[1 - axis]
            points = cut_pin_points(axis, c, planes, pins, span_u, z_range,
                                    _boss_fits(env, inside, axis, c, span, rb, z_range))
            unpinned += not points
            b, h = cut_pin_solids(axis, c, points, pins, n)
            bosses += b
            holes += h
            where += [(axis, c, u, z) for u, z in points]
    return bosses, holes, where, unpinned


def _cells_near_pins(centre: np.ndarray, where, pins: Pins, a: float) -> np.ndarray:
    """Cells whose cube comes within a quarter cell of a pin boss's box: they pass through the
    boolean with the boss, so no boss surface lies on a face between them and the inner cells."""
    near = np.zeros(len(centre), bool)
    reach = np.array([pins.depth + pins.wall_mm, pins.boss_radius, pins.boss_radius]) + a / 4 + a / 2
    for axis, c, u, z in where:
        at = np.array([c, u, z]) if axis == 0 else np.array([u, c, z])
        half = reach if axis == 0 else reach[[1, 0, 2]]
        near |= np.all(np.abs(centre - at) < half, axis=1)
    return near


def build_lattice_body(env: Envelope, index: np.ndarray, centre: np.ndarray, inner: np.ndarray, width_mm: np.ndarray,
                       cell_mm: float, *, skin_mm: float, bed_mm: tuple[float, float, float], tolerance_mm: float,
                       segments: int, reference_volume_mm3: float, pins: Pins | None = None,
                       map_parts=None) -> PrintedLens:
    """The printable parts of the body: cells ``index`` (centres ``centre``, ``inner`` as from
    :func:`body_cells`) with rod widths ``width_mm``; parts on the bed, sorted by position, registered
    by ``pins`` across every bed cut (two a cut where the body has room; printed as a part of their own).
    The parts are independent: ``map_parts(fn, arguments)`` (values in order; one after the other when
    None) may mesh them at once, e.g. in child processes; the parts are the same either way."""
    a = cell_mm
    origin = lattice_origin(env, a)
    full = env.full
    u0, w0, u1, w1 = full.bounds
    x_ext = (-u1, u1) if env.kind == "revolved" else (u0, u1)
    y_ext = (-u1, u1) if env.kind == "revolved" else (w0, w1)
    planes = {0: bed_planes(x_ext, bed_mm[0], a, origin[0]), 1: bed_planes(y_ext, bed_mm[1], a, origin[1])}
    z_lo = w0 if env.kind == "revolved" else 0.0
    z_hi = w1 if env.kind == "revolved" else env.height_mm
    if z_hi - z_lo > bed_mm[2] + 1e-6:
        raise ValueError(f"fabrication.bed.z_mm: the body is {z_hi - z_lo:.1f} mm tall, the bed {bed_mm[2]:g} mm "
                         "(horizontal cuts are not made)")
    trim = env.solid(-skin_mm / 2, segments, tolerance_mm)
    shell = env.solid(0.0, segments, tolerance_mm) - env.solid(-skin_mm, segments, tolerance_mm) if skin_mm > 0 else None
    bosses = holes = None
    pin_count = unpinned = 0
    if pins is not None and (planes[0] or planes[1]):
        boss_list, hole_list, where, unpinned = body_pins(env, planes, pins, skin_mm, tolerance_mm)
        pin_count = len(where)
        if where:
            bosses = Manifold.batch_boolean(boss_list, OpType.Add)
            holes = Manifold.batch_boolean(hole_list, OpType.Add)
            inner = inner & ~_cells_near_pins(centre, where, pins, a)
    region = _region_of(centre, planes)
    xs, ys = [-1e6] + planes[0] + [1e6], [-1e6] + planes[1] + [1e6]
    jobs = []
    for r in range(len(xs) - 1):
        for q in range(len(ys) - 1):
            mine = region == r * (len(ys) - 1) + q
            if not mine.any():
                continue
            cut = Manifold.cube([xs[r + 1] - xs[r], ys[q + 1] - ys[q], 4e6]).translate([xs[r], ys[q], -2e6])
            jobs.append((index, width_mm, mine & inner, mine & ~inner, a, origin, trim, None if shell is None else shell ^ cut,
                         None if bosses is None else (bosses ^ cut, holes)))
    meshes, tri_count = [], 0
    for made, placed in (map_parts or _in_turn)(_placed_part, jobs):
        tri_count += made
        if placed is not None:
            meshes.append(placed)
    meshes.sort(key=lambda placed: placed[0])
    out = tuple(PrintedPart(f"lens-{n + 1:02d}" if len(meshes) > 1 else "lens", "lens", 1, v, f, volume, offset)
                for n, (_, v, f, volume, offset) in enumerate(meshes))
    cuts = len(planes[0]) + len(planes[1])
    volume = sum(p.volume_mm3 for p in out)
    if pin_count:
        out += (pin_part(pins, pin_count, tolerance_mm),)
    return PrintedLens(out, len(index), tri_count, volume, reference_volume_mm3, pin_count, cuts, unpinned)
