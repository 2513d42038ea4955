"""The two-storey lens–mirror antenna (seed-001 §1.5, Realisation; §8.1 item 2): the equal-line
trifocal lens realised with straight waveguides folded by a 180° U-bend "mirror".

Frame: the lens frame in mm (y transverse, z the axis, feeds at z < 0); x is the stacking direction
(layer 1 x ∈ [−h/2, h/2], the septum above it, layer 2 above that).

Every line of the §1.5 lens (entry point (y1, z1), exit point (y2, z2), all of one electrical length)
becomes one TE10 guide of the same width a and height h (so one phase index at every frequency:
equal physical lengths are equal electrical lengths across the band, the thesis' broadband claim):

* layer 1: a straight guide from the entry point P1 = (y1, z1) to the kink K = (y2, z_k) — the guides
  are not parallel, their walls thicken toward the mirror, which realises the mapping y1 → y2 — then
  an axial run ``run`` to the bend at z_m (the H-plane kink is a mitre: its centre line is the path);
* the U-bend: a 180° E-plane bend of centre-line radius R = (h + septum)/2 about the septum's edge,
  the same for every guide (its electrical length is a common constant, whatever its dispersion);
* layer 2: an axial guide at y2 back to the folded exit point E = (y2, z_e), z_e = z_v − (z2 − d/2):
  the output half reflected in z (a rigid move of the output half, §1.1: every plane-wave focus stays
  perfect, the beams leave toward −z), opening into a parallel-plate region and an E-plane flare.

The mirror is the curve of the bend points z_m: each guide's kink is placed so that
|P1 K| + run + πR + (z_m − z_e) is the same for every guide (closed form below). The feeds are
H-plane sectoral horns with their aperture centres on the foci F, F1, F2 (on the focal circle),
aimed at the entry-surface centre.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Polygon

from antenna_cad.synthesis.checks import Check, DesignError

FIELD = "design.lens_mirror"
C_MM_GHZ = 299.792458        # speed of light, mm·GHz


@dataclass(frozen=True)
class TwoStoreyParams:
    """Realisation parameters (mm): guide a × h, metal septum between the layers, least wall, the
    axial run before each bend, the least axial distance from an entry point to its kink, the exit
    setback (None: the flare's mouth flush with the back of the layer-1 feeds), the feed horns and
    the output flare, the band of single-mode operation (GHz)."""
    guide_width: float
    height: float
    septum: float
    wall: float
    run: float
    clearance: float
    setback: float | None
    horn_aperture: float
    horn_length: float
    horn_stub: float
    flare_length: float
    mouth_height: float
    band_ghz: tuple[float, float]

    @property
    def bend_radius(self) -> float:
        """Centre-line radius of the U-bend: the septum's rounded edge (radius septum/2) inside."""
        return (self.height + self.septum) / 2


@dataclass(frozen=True)
class TwoStorey:
    p: TwoStoreyParams
    y1: np.ndarray
    z1: np.ndarray
    y2: np.ndarray
    z2: np.ndarray
    ze: np.ndarray             # folded exit point z (layer 2)
    zk: np.ndarray             # kink (end of the slanted run)
    zm: np.ndarray             # bend plane (the mirror point)
    l1: np.ndarray             # layer-1 centre-line length: |P1 K| + run
    l2: np.ndarray             # layer-2 centre-line length: z_m − z_e
    entry_curve: np.ndarray    # (n, 2) dense (y, z) of the entry surface
    exit_curve: np.ndarray     # (n, 2) dense (y, z_e) of the folded exit surface
    feeds: tuple[tuple[np.ndarray, np.ndarray], ...]   # (aperture centre, unit axis toward the lens)
    z_flare: float             # start of the E-plane flare (the nearest exit point)
    z_mouth: float             # the radiating mouth

    @property
    def l_bend(self) -> float:
        return float(np.pi * self.p.bend_radius)

    @property
    def total(self) -> np.ndarray:
        return self.l1 + self.l_bend + self.l2

    @property
    def bend_outer(self) -> np.ndarray:
        """z of each bend's outer wall (inner radius septum/2 + h)."""
        return self.zm + self.p.septum / 2 + self.p.height

    def footprint(self, i: int, layer: int, mouth: float = 0.0, to_bend: bool = False) -> Polygon:
        """Plan (y, z) of guide i's air in ``layer`` (1 or 2) up to its bend's outer wall (``to_bend``:
        up to the bend plane z_m); ``mouth`` extends it that far back past its entry (exit) point."""
        a, y2 = self.p.guide_width / 2, self.y2[i]
        top = self.zm[i] if to_bend else self.bend_outer[i]
        if layer == 2:
            z0 = self.ze[i] - mouth
            return Polygon([(y2 - a, z0), (y2 + a, z0), (y2 + a, top), (y2 - a, top)])
        p = np.array([self.y1[i], self.z1[i]])
        v = np.array([y2, self.zk[i]]) - p
        v /= np.linalg.norm(v)
        n = np.array([v[1], -v[0]]) * a
        start = p - v * mouth
        mitre = [self._mitre(p + s * n, v, y2 + s * a, i) for s in (1, -1)]
        return Polygon([tuple(start + n), mitre[0], (y2 + a, top), (y2 - a, top), mitre[1], tuple(start - n)])

    def _mitre(self, q: np.ndarray, v: np.ndarray, y_edge: float, i: int) -> tuple[float, float]:
        """Where the slanted edge line q + s·v meets the axial edge line y = y_edge."""
        if abs(v[0]) < 1e-12:
            return y_edge, float(self.zk[i])
        s = (y_edge - q[0]) / v[0]
        return y_edge, float(q[1] + s * v[1])

    def horn(self, k: int, extra: float = 0.0) -> Polygon:
        """Plan of feed k's H-plane sectoral horn and its guide stub (aperture on the focus), the stub
        lengthened by ``extra`` (to pierce the block's face)."""
        c, v = self.feeds[k]
        n = np.array([v[1], -v[0]])
        a, w = self.p.guide_width / 2, self.p.horn_aperture / 2
        throat, back = c - v * self.p.horn_length, c - v * (self.p.horn_length + self.p.horn_stub + extra)
        return Polygon([tuple(c + n * w), tuple(throat + n * a), tuple(back + n * a), tuple(back - n * a),
                        tuple(throat - n * a), tuple(c - n * w)])

    def feed_region(self) -> Polygon:
        """Layer-1 parallel-plate region: the entry curve (guides opening on it), the outer corners of
        the edge guides, the horn apertures from +y round to −y."""
        ring = [tuple(q) for q in self.entry_curve]
        k = len(self.y1) - 1
        edge = self.footprint(k, 1).exterior.coords[0]
        ring.append(tuple(edge))
        for c, v in sorted(self.feeds, key=lambda fv: -fv[0][0]):
            n = np.array([v[1], -v[0]]) * self.p.horn_aperture / 2
            ring += [tuple(c + n), tuple(c - n)]
        ring.append(tuple(self.footprint(0, 1).exterior.coords[-2]))
        return Polygon(ring)

    def output_region(self, mouth: float) -> Polygon:
        """Layer-2 parallel-plate region from the folded exit curve to the mouth."""
        half = float(np.max(np.abs(self.exit_curve[:, 0]))) + self.p.guide_width / 2
        edge = float(self.exit_curve[-1, 1]) - mouth
        ring = [(-half, self.z_mouth), (half, self.z_mouth), (half, edge)]
        ring += [tuple(q) for q in self.exit_curve[::-1]] + [(-half, edge)]
        return Polygon(ring)


def _lens_xy(r: np.ndarray, unit: float) -> tuple[np.ndarray, np.ndarray]:
    return r[:, 1] * unit, r[:, 2] * unit


def _trimmed(y: np.ndarray, z: np.ndarray, ys: np.ndarray, zs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A dense surface curve cut to the guides' span: its points strictly between the edge guides'
    ordinates, the edge guides' own points at both ends."""
    inside = (y > ys[0]) & (y < ys[-1])
    return np.r_[ys[0], y[inside], ys[-1]], np.r_[zs[0], z[inside], zs[-1]]


def _feeds(foci_mm: list[np.ndarray], target: np.ndarray) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
    out = []
    for f in foci_mm:
        v = target - f
        out.append((f, v / np.linalg.norm(v)))
    return tuple(out)


def layout(r1: np.ndarray, r2: np.ndarray, dense_r1: np.ndarray, dense_r2: np.ndarray, foci: np.ndarray,
           unit_mm: float, thickness: float, p: TwoStoreyParams) -> TwoStorey:
    """The two-storey antenna of the §1.5 lens lines (normalised (x, y, z) rows r1, r2, ordered in
    y; ``foci`` the design foci's points, normalised). Raises DesignError when it cannot be built."""
    y1, z1 = _lens_xy(r1, unit_mm)
    y2, z2 = _lens_xy(r2, unit_mm)
    if not (np.all(np.diff(y1) > 0) and np.all(np.diff(y2) > 0)):
        raise DesignError(FIELD, "the lens mapping y1 → y2 is not monotonic: straight guides would cross")
    half_d = thickness / 2 * unit_mm
    feeds = _feeds([f[1:] * unit_mm for f in foci], np.array([0.0, -half_d]))
    depth = p.horn_length + p.horn_stub
    z_back = min(float(c[1] - v[1] * depth) for c, v in feeds)
    z_back = min(z_back, float(np.min(z1)) - 2 * p.guide_width)
    dense_y2, dense_z2 = _trimmed(*_lens_xy(dense_r2, unit_mm), y2, z2)
    if p.setback is None:
        vertex = z_back + p.flare_length + float(np.max(dense_z2 - half_d))
    else:
        vertex = -half_d - p.setback
    ze = vertex - (z2 - half_d)
    exit_curve = np.column_stack([dense_y2, vertex - (dense_z2 - half_d)])
    z_flare = float(np.min(exit_curve[:, 1]))
    z_mouth = z_flare - p.flare_length
    # equal total length T = sqrt(Δy² + u²) + u + 2·run + πR + z1 − z_e, u = z_k − z1 (closed form in u);
    # each u at least the clearance, and the layer-2 run z_m − z_e at least one guide width
    dy = y2 - y1
    c = np.maximum(p.clearance, ze - z1 - p.run + p.guide_width)
    need = c + np.sqrt(c**2 + dy**2)                      # Q that gives u = c
    rest = 2 * p.run + np.pi * p.bend_radius + z1 - ze
    total = float(np.max(need + rest))
    q = total - rest
    u = (q**2 - dy**2) / (2 * q)
    zk = z1 + u
    zm = zk + p.run
    l1 = np.hypot(dy, u) + p.run
    l2 = zm - ze
    dense_y1, dense_z1 = _trimmed(*_lens_xy(dense_r1, unit_mm), y1, z1)
    return TwoStorey(p, y1, z1, y2, z2, ze, zk, zm, l1, l2, np.column_stack([dense_y1, dense_z1]), exit_curve,
                     feeds, z_flare, z_mouth)


def clearances(ts: TwoStorey) -> dict[str, float]:
    """Least metal between guides (mm): in layer 1 (slanted walls, mitres and bends), in layer 2,
    between neighbouring bends' footprints; and the least overlap-free gap between any two guides
    of a layer (negative: they cross)."""
    n = len(ts.y1)
    out = {}
    for layer in (1, 2):
        prints = [ts.footprint(i, layer) for i in range(n)]
        gaps = [prints[i].distance(prints[j]) - prints[i].intersection(prints[j]).area ** 0.5
                for i in range(n) for j in range(i + 1, n)]
        out[f"layer{layer}_wall_min_mm"] = float(min(gaps))
    bends = [Polygon([(y - ts.p.guide_width / 2, z), (y + ts.p.guide_width / 2, z),
                      (y + ts.p.guide_width / 2, zo), (y - ts.p.guide_width / 2, zo)])
             for y, z, zo in zip(ts.y2, ts.zm, ts.bend_outer)]
    out["bend_gap_min_mm"] = float(min(a.distance(b) for a, b in zip(bends, bends[1:])))
    return out


def checks(ts: TwoStorey) -> tuple[list[Check], dict[str, float]]:
    """Realisability of the layout (seed-001 §8.3), refusing what cannot be built: walls thinner than
    the least wall (guides crossing give a negative wall), the feed region cutting a guide wall;
    checks of the band's single-mode limits; figures of the layout."""
    p = ts.p
    gaps = clearances(ts)
    for key in ("layer1_wall_min_mm", "layer2_wall_min_mm", "bend_gap_min_mm"):
        if gaps[key] < p.wall - 1e-9:
            what = "guides cross" if gaps[key] < 0 else f"a wall is {gaps[key]:.4g} mm thin"
            raise DesignError(f"{FIELD}.guide_width_mm", f"{key.split('_')[0]}: {what} (least wall "
                              f"{p.wall:g} mm, design.lines.wall_mm); widen design.lines.pitch_mm or narrow the guides")
    region = ts.feed_region()
    horns = [ts.horn(k) for k in range(len(ts.feeds))]
    near = min(h.distance(ts.footprint(i, 1)) for h in horns for i in range(len(ts.y1)))
    bite = _feed_bite(ts, region) if region.is_valid else float("inf")
    if near < p.wall - 1e-9 or bite > 1e-9 * p.guide_width**2:
        raise DesignError(f"{FIELD}.horn_aperture_mm", f"the feed horns come {near:.3g} mm from a guide (least wall "
                          f"{p.wall:g} mm) or open the feed region {bite:.3g} mm² in front of the entry surface: "
                          "narrow or shorten the horns")
    mapping = float(min(np.min(np.diff(ts.y1)), np.min(np.diff(ts.y2))))
    checks_ = [Check("mapping_monotonic", "pass" if mapping > 0 else "fail", mapping, 0.0, "mm",
                     f"least step of y1 and y2 between neighbouring guides: {mapping:.4g} mm (> 0: y2(y1) monotonic)")]
    for key, what in (("layer1_wall_min_mm", "thinnest layer-1 wall (slanted guides, kinks, bends)"),
                      ("layer2_wall_min_mm", "thinnest layer-2 wall"),
                      ("bend_gap_min_mm", "least metal between neighbouring U-bends")):
        checks_.append(Check(key.removesuffix("_mm"), "pass", gaps[key], p.wall, "mm",
                             f"{what}: {gaps[key]:.4g} mm (minimum {p.wall:g} mm; no two guides cross)"))
    lo, hi = p.band_ghz
    cutoff = C_MM_GHZ / (2 * p.guide_width)
    checks_ += [Check.upper("te10_cutoff_below_band", cutoff / lo, 1.0, "", "TE10 cutoff c/2a / lowest frequency"),
               Check.upper("te20_above_band", hi / (2 * cutoff), 1.0, "", "highest frequency / TE20 cutoff c/a"),
               Check.upper("plates_single_mode", 2 * p.height * hi / C_MM_GHZ, 1.0, "",
                           "plate spacing / (λ_min / 2): the parallel-plate TE1 and guide TE01 cut off"),
               Check.upper("equal_line_length_synthesis", float(np.ptp(ts.total)), 1e-9 * float(ts.total.max()), "mm",
                           "spread of |P1K| + run + πR + (z_m − z_e) over the guides (synthesis)")]
    pitch = float(np.max(np.diff(ts.y2)))
    figures = gaps | {"guide_count": len(ts.y1), "bend_radius_mm": p.bend_radius, "bend_length_mm": ts.l_bend,
                      "line_length_mm": float(ts.total.max()),
                      "line_length_spread_mm": float(np.ptp(ts.total)),
                      "layer1_length_min_mm": float(ts.l1.min()), "layer1_length_max_mm": float(ts.l1.max()),
                      "layer2_length_min_mm": float(ts.l2.min()), "layer2_length_max_mm": float(ts.l2.max()),
                      "kink_angle_max_deg": float(np.degrees(np.max(np.arctan2(np.abs(ts.y2 - ts.y1), ts.zk - ts.z1)))),
                      "mirror_depth_mm": float(np.ptp(ts.zm)), "exit_pitch_max_mm": pitch,
                      "entry_pitch_min_mm": float(np.min(np.hypot(np.diff(ts.y1), np.diff(ts.z1)))),
                      "grating_lobe_free_scan_deg_at_band_top": _grating_free(pitch, C_MM_GHZ / hi),
                      "te10_cutoff_ghz": cutoff, "mouth_z_mm": ts.z_mouth}
    return checks_, figures


def _feed_bite(ts: TwoStorey, region: Polygon) -> float:
    """Area of the feed region in front of the entry surface (the curve continued level past its
    ends), outside the guides' own mouths: metal the feed region would take from the walls."""
    curve = ts.entry_curve
    far = 1e3 * (1.0 + float(np.max(np.abs(curve))))
    top = float(np.max(ts.bend_outer)) + far
    front = Polygon([(-far, curve[0, 1]), *map(tuple, curve), (far, curve[-1, 1]), (far, top), (-far, top)])
    mouths = shapely.unary_union([ts.footprint(i, 1, 2 * ts.p.guide_width) for i in range(len(ts.y1))])
    return float(region.difference(mouths).intersection(front).area)


def _grating_free(pitch: float, lam: float) -> float:
    """Largest scan angle without a grating lobe for an exit pitch (−90 when there is one at broadside)."""
    s = lam / pitch - 1.0
    return float(np.degrees(np.arcsin(s))) if s >= -1 else -90.0


def focus_spreads(ts: TwoStorey, lengths: np.ndarray, foci: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """Eikonal spread (mm) over the guides for each design focus (point, output direction in the lens
    frame, mm): |F − P1| + L − E·k', with k' the direction folded by the mirror (z reversed) and the
    guide lengths ``lengths`` (read back from the solids)."""
    p1 = np.column_stack([ts.y1, ts.z1])
    e = np.column_stack([ts.y2, ts.ze])
    out = []
    for point, direction in foci:
        k = np.array([direction[0], -direction[1]])
        path = np.linalg.norm(p1 - point, axis=1) + lengths - e @ k
        out.append(float(np.ptp(path)))
    return np.array(out)


def pierce(margin: float) -> float:
    """How much longer the feed stubs are cut than drawn, to pierce the block's grown outline."""
    return 3 * margin + 1.0


def layer_air(ts: TwoStorey, layer: int, mouth: float, stub: float = 0.0) -> list[Polygon]:
    """Plan polygons of a layer's air: the guides (opened ``mouth`` past their ends), and the feed
    region with its horns, stubs lengthened by ``stub`` (layer 1), or the output region (layer 2)."""
    guides = [ts.footprint(i, layer, mouth) for i in range(len(ts.y1))]
    if layer == 1:
        return guides + [ts.feed_region()] + [ts.horn(k, stub) for k in range(len(ts.feeds))]
    return guides + [ts.output_region(mouth)]


def outlines(ts: TwoStorey, mouth: float, margin: float) -> tuple[Polygon, Polygon]:
    """(lower, upper) plan outlines of the block: the hull of both layers' air grown by ``margin``,
    the upper one cut at the radiating mouth, the lower one at the mouth or the feeds' backs."""
    air = shapely.unary_union(layer_air(ts, 1, mouth) + layer_air(ts, 2, mouth))
    hull = air.convex_hull.buffer(margin, join_style=2)
    x0, _, x1, z1 = hull.bounds
    back = min(ts.z_mouth, min(ts.horn(k).bounds[1] for k in range(len(ts.feeds))))
    lower = hull.intersection(shapely.box(x0 - 1, back, x1 + 1, z1 + 1))
    upper = hull.intersection(shapely.box(x0 - 1, ts.z_mouth, x1 + 1, z1 + 1))
    return lower, upper


def _lower_bend_section(ts: TwoStorey) -> float:
    """Area (xz) of a U-bend's half annulus below the septum (x − x_c ≤ −r_i): the rest is in the
    septum and layer 2."""
    ri, ro = ts.p.septum / 2, ts.p.septum / 2 + ts.p.height
    prim = lambda x: (x * np.sqrt(ro**2 - x**2) + ro**2 * np.arcsin(x / ro)) / 2     # noqa: E731
    return float(prim(-ri) - prim(-ro))


def slab_volumes(ts: TwoStorey, mouth: float, margin: float, plate: float) -> dict[str, float]:
    """Volumes (mm³) of the three machined plates from the plan alone: outline × thickness less the
    pockets (plan areas × h), the U-bends' parts (xz sections × a) and the flare (its triangle × width)."""
    p, n = ts.p, len(ts.y1)
    lower, upper = outlines(ts, mouth, margin)
    half_annulus = np.pi / 2 * ((p.septum / 2 + p.height) ** 2 - (p.septum / 2) ** 2)
    bend_low = _lower_bend_section(ts) * p.guide_width * n
    bend_up = half_annulus * p.guide_width * n - bend_low

    def pockets(layer: int, outline: Polygon) -> float:
        air = [ts.footprint(i, layer, mouth, to_bend=True) for i in range(n)]
        air += layer_air(ts, layer, mouth, pierce(margin))[n:]
        return shapely.unary_union(air).intersection(outline).area * p.height

    half = float(np.max(np.abs(ts.exit_curve[:, 0]))) + p.guide_width / 2
    flare = (p.mouth_height - p.height) * p.flare_length / 2 * 2 * half
    cover = plate + p.mouth_height - p.height
    return {"block-lower": lower.area * (plate + p.height) - pockets(1, lower) - bend_low,
            "block-upper": upper.area * (p.septum + p.height) - pockets(2, upper) - bend_up,
            "cover": upper.area * cover - flare}
