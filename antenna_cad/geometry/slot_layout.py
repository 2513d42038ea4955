"""Layout of the slot-array solids in numbers (numpy/shapely, no CAD kernel): the z stack, guide
extents with their loads, plate outlines, mirror backing side, coupling slots, horn outlines and
slot outlines — shared by the model and the templates so both describe the same parts."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely.geometry import Polygon
from shapely.geometry.polygon import orient
from shapely.ops import unary_union

from antenna_cad.fabrication.outline import CHORD_TOL_MM
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.slot_array import Curve, SlotArrayDesign, offset_curve

END_WEB_MM = 0.2      # metal left between the body start and the first slot


def slot_bulges(x: float, y: float, length: float, width: float, angle: float) -> list[tuple[float, float, float]]:
    """The same slot with true round ends: a closed DXF bulge path (x, y, bulge to the next vertex),
    counter-clockwise, each end one half circle (bulge 1), the sides straight."""
    u = np.array([np.sin(angle), np.cos(angle)])
    nrm = np.array([-u[1], u[0]])
    r, s = width / 2, max(length / 2 - width / 2, 0.0)
    path = []
    for sign in (1.0, -1.0):
        centre = np.array([x, y]) + sign * s * u
        start, end = centre - sign * r * nrm, centre + sign * r * nrm
        path += [(float(start[0]), float(start[1]), 1.0)] + ([(float(end[0]), float(end[1]), 0.0)] if s > 0 else [])
    return path


@dataclass(frozen=True)
class Stack:
    """z extents (mm) of the layers and plates; layer N is the guide layer."""
    n_layers: int
    t: float                 # plate / broad wall thickness
    layer_h: float
    guide_h: float

    def layer(self, k: int) -> tuple[float, float]:
        if k == self.n_layers:
            return 0.0, 2 * self.t + self.guide_h
        top = -(self.n_layers - k) * self.t - (self.n_layers - 1 - k) * self.layer_h
        return top - self.layer_h, top

    def plate(self, k: int) -> tuple[float, float]:
        """Plate under layer k + 1 (k = 0: base plate under layer 1)."""
        z0 = self.layer(k + 1)[0] if k + 1 < self.n_layers else 0.0
        return z0 - self.t, z0


def layer_indices(curve: Curve) -> tuple[int, ...]:
    return tuple(int(p.removeprefix("layer")) for p in curve.layer.split("-"))


def mirror_back_sign(design: SlotArrayDesign, curve: Curve) -> float:
    """+1 if the mirror's metal backing lies toward +y (away from the wave it reflects)."""
    if curve is design.beamformer.guide_curve:
        return -1.0
    foci_y = float(np.mean(design.beamformer.foci_mm[:, 1]))
    return 1.0 if float(np.mean(curve.points_mm[:, 1])) > foci_y else -1.0


def coupling_edge(design: SlotArrayDesign, curve: Curve) -> Curve:
    if curve is design.beamformer.guide_curve:
        return design.coupling_slot_edge
    return offset_curve(curve, -mirror_back_sign(design, curve) * design.coupling_slot_mm,
                        f"{curve.name}_coupling")


def slot_outline(x: float, y: float, length: float, width: float, angle: float,
                 tol_mm: float = CHORD_TOL_MM) -> np.ndarray:
    """Rounded-end rectangle (ring of points, counter-clockwise) for templates.

    Each round end is circumscribed (edges tangent to the arc, like
    :func:`antenna_cad.fabrication.outline.circle_polygon`): the cut slot is never smaller than
    nominal and no vertex lies more than ``tol_mm`` outside it.
    """
    u = np.array([np.sin(angle), np.cos(angle)])
    nrm = np.array([-u[1], u[0]])
    r, s = width / 2, max(length / 2 - width / 2, 0.0)
    n = max(2, int(np.ceil(np.pi / (2 * np.arccos(1.0 / (1.0 + tol_mm / r))))))
    q = np.concatenate([[0.0], (np.arange(n) + 0.5) * np.pi / n, [np.pi]])
    rad = np.concatenate([[r], np.full(n, r / np.cos(np.pi / (2 * n))), [r]])
    c = np.array([x, y])
    ends = []
    for sign in (1.0, -1.0):
        ang = np.arctan2(*(sign * -nrm)[::-1]) + q
        ends.append(c + sign * s * u + rad[:, None] * np.stack([np.cos(ang), np.sin(ang)], -1))
    return np.concatenate(ends)


@dataclass(frozen=True)
class PartSizes:
    """Sizes of the machined parts that the synthesis does not fix (spec ``fabrication``/``feeds``)."""
    broad_wall_mm: float          # slotted lid, guide bottom and end walls, beam-former plates, horn E-walls
    mirror_wall_mm: float
    plate_margin_mm: float
    horn_wall_mm: float           # horn H-plane side walls
    flange_mm: float              # horn flange collar beyond the side walls
    flange_thickness_mm: float    # flange / throat section along the horn axis


@dataclass(frozen=True)
class GuideExtent:
    """Per guide (y along the guides, mm): body start ``y0`` (coupling-slot end), end of the slotted
    section ``y_slots_end``, end of the load wedge ``y_load_end`` (= ``y_slots_end`` for a short)
    and outer end ``y_end`` (after the end wall); ``half`` = outer half-width."""
    y0: np.ndarray
    y_slots_end: np.ndarray
    y_load_end: np.ndarray
    y_end: np.ndarray
    half: float


def guide_extent(design: SlotArrayDesign, wall_mm: float, end_wall_mm: float) -> GuideExtent:
    """Extent of every guide body.

    The rectangular body starts beyond the (curved) coupling slot, at the highest point of its far
    edge across the body width, but never past the first slot (less END_WEB_MM): on steep outer
    guides a corner of the bottom wall then overlaps the coupling slot (see :func:`end_overlap_mm`).
    The slotted section ends a quarter period after the last cell; a matched load adds its wedge
    (``design.load_length_mm``); the end wall is ``end_wall_mm`` thick.
    """
    s = design.slots
    half = design.guide_width_mm / 2 + wall_mm
    _, hy = s.half_extents_mm()
    low = np.full(len(s.guide_x_mm), np.inf)
    np.minimum.at(low, s.guide_index, s.y_mm - hy)
    y0 = np.minimum(_coupling_edge_top(design, half), low - END_WEB_MM)
    y1 = s.guide_end_y_mm + 0.25 * s.period_mm
    y_load = y1 + design.load_length_mm
    return GuideExtent(y0, y1, y_load, y_load + end_wall_mm, half)


def _coupling_edge_top(design: SlotArrayDesign, half: float) -> np.ndarray:
    """Highest point of the coupling slot's far edge across each guide body's width."""
    return np.array([float(design.coupling_slot_edge.y_at(np.linspace(x - half, x + half, 9)).max())
                     for x in design.slots.guide_x_mm])


def end_overlap_mm(design: SlotArrayDesign, wall_mm: float) -> float:
    """Largest length by which a guide body's start overlaps the coupling slot's far edge."""
    ext = guide_extent(design, wall_mm, 0.0)
    return float(np.max(_coupling_edge_top(design, ext.half) - ext.y0))


def core_and_load_rings(a: float, y0: float, y1: float, y_load: float) -> tuple[list, list]:
    """Dielectric core and absorber wedge of one guide in its local frame (x from the axis).

    Matched load (y_load > y1): the core tapers over the load length to the +x side wall and the
    absorber fills the complementary right triangle (a single-sided H-plane wedge); for a short
    (y_load = y1) the core is the rectangle and there is no absorber.
    """
    core = [(-a / 2, y0), (a / 2, y0), (a / 2, y_load), (-a / 2, y1)]
    if y_load <= y1:
        return [(-a / 2, y0), (a / 2, y0), (a / 2, y1), (-a / 2, y1)], []
    return core, [(-a / 2, y1), (a / 2, y_load), (-a / 2, y_load)]


@dataclass(frozen=True)
class HornOutline:
    """One H-plane sectoral horn in the feed-layer plane (seed-003 §8.1 item 8), mm.

    ``footprint``: outline of the metal body (side walls, flange collar and the E-plane walls above
    and below), clipped on the bisector with each neighbour so adjacent horns share a boundary and
    never overlap. ``channel``: the hollow — throat port through the flange (throat width), then
    the flare to the aperture; open at the flange back and at the aperture. ``channel_cut`` is the
    channel extended past both open ends (for the boolean). ``clipped_mm2``: channel area lost to
    the neighbours (0 unless the horns are closer than their apertures).
    """
    footprint: Polygon
    channel: Polygon
    channel_cut: Polygon
    clipped_mm2: float


def _side(aim: np.ndarray) -> np.ndarray:
    return np.array([-aim[1], aim[0]])


def horn_outlines(design: SlotArrayDesign, sizes: PartSizes) -> tuple[HornOutline, ...]:
    """Horn outlines: aperture centre on the focal locus, axis toward the mirror centre (``aim``).

    In each horn's frame (u along the axis from the aperture, v across): channel from the flange
    back u = −L − t_f (throat width) to the throat u = −L, flare to the aperture u = 0; side walls
    of normal thickness w; flange collar w + flange beyond the channel over the flange length.
    """
    f = design.feeds
    th, ap, L = f.throat_mm[0], f.aperture_mm[0], f.length_mm
    w, fl, ft = sizes.horn_wall_mm, sizes.flange_mm, sizes.flange_thickness_mm
    slope = (ap - th) / (2 * L)
    wo = w * np.hypot(1.0, slope)                        # lateral offset of a wall of normal thickness w
    outer = [(-L - ft, th / 2 + w + fl), (-L, th / 2 + w + fl), (-L, th / 2 + wo), (0.0, ap / 2 + wo)]
    chan = [(-L - ft, th / 2), (-L, th / 2), (0.0, ap / 2)]
    cut = [(-L - 2 * ft, th / 2), (-L, th / 2), (1.0, ap / 2 + slope)]   # past both open ends
    sym = lambda half: half + [(u, -v) for u, v in half[::-1]]
    big = 10.0 * (L + ft + ap) + float(np.abs(f.aperture_centres_mm).max())
    clips = [Polygon([(-big, -big), (big, -big), (big, big), (-big, big)]) for _ in f.aim]
    corners = _aperture_corners(design)
    for k in range(len(f.aim) - 1):               # neighbours share the bisector through the junction
        J = 0.5 * (corners[k, 1] + corners[k + 1, 0])
        back = _unit2(-(f.aim[k] + f.aim[k + 1]))
        nxt = _side(back) * np.sign(_side(back) @ (f.aperture_centres_mm[k + 1] - J))
        strip = lambda sgn: Polygon([tuple(J + back * big), tuple(J - back * big),
                                     tuple(J - back * big + sgn * nxt * big), tuple(J + back * big + sgn * nxt * big)])
        clips[k] = clips[k].intersection(strip(-1.0))
        clips[k + 1] = clips[k + 1].intersection(strip(1.0))
    out = []
    for c, aim, clip in zip(f.aperture_centres_mm, f.aim, clips):
        sd = _side(aim)
        poly = lambda pts: Polygon([tuple(c + aim * u + sd * v) for u, v in sym(pts)])
        channel = poly(chan)
        kept = channel.intersection(clip)
        out.append(HornOutline(poly(outer).intersection(clip), kept, poly(cut).intersection(clip),
                               float(channel.area - kept.area)))
    return tuple(out)


def _unit2(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _aperture_corners(design: SlotArrayDesign) -> np.ndarray:
    """(K, 2, 2): the two aperture edge points of every horn, ordered along the feed row."""
    f = design.feeds
    sd = np.stack([-f.aim[:, 1], f.aim[:, 0]], -1) * f.aperture_mm[0] / 2
    order = np.sign(np.sum(sd * (f.aperture_centres_mm[-1] - f.aperture_centres_mm[0]), -1, keepdims=True))
    sd = sd * np.where(order == 0, 1.0, order)
    return np.stack([f.aperture_centres_mm - sd, f.aperture_centres_mm + sd], 1)


def feed_keepout(design: SlotArrayDesign, horns: tuple[HornOutline, ...]) -> Polygon:
    """Region of the feed-layer plates taken by the horns: everything behind the chain of horn
    aperture edges, out to the outer horns' widest lateral extent, and the horn footprints."""
    f = design.feeds
    corners = _aperture_corners(design)
    far = 10.0 * (f.length_mm + f.aperture_mm[0]) + float(np.abs(f.aperture_centres_mm).max())
    ends = []
    for k, h in ((0, horns[0]), (-1, horns[-1])):
        out = _unit2(corners[k, -k] - corners[k, 1 + k])      # outward along the aperture line
        reach = max(float(out @ (np.array(p) - f.aperture_centres_mm[k])) for p in h.footprint.exterior.coords)
        ends.append(f.aperture_centres_mm[k] + out * reach)
    chain = [ends[0], *corners.reshape(-1, 2), ends[1]]
    ring = chain + [ends[1] - f.aim[-1] * far, ends[0] - f.aim[0] * far]
    region = Polygon([tuple(p) for p in ring]).buffer(0)
    return unary_union([region, *(h.footprint for h in horns)])


def plate_polygon(design: SlotArrayDesign, k: int, sizes: PartSizes,
                  horns: tuple[HornOutline, ...]) -> Polygon:
    """Outline of beam-former plate k: the rectangle of :func:`plate_rect`; the two plates that
    bound the feed layer (k = 0, 1) are notched by :func:`feed_keepout` (the horns' own E-plane
    walls continue them there)."""
    x0, y0, x1, y1 = plate_rect(design, sizes.plate_margin_mm)
    rect = Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    if k > 1:
        return rect
    poly = rect.difference(feed_keepout(design, horns))
    if poly.geom_type == "MultiPolygon":
        poly = max(poly.geoms, key=lambda g: g.area)
    return orient(poly)


def clip_curve(curve: Curve, lo: float, hi: float) -> Curve:
    """``curve`` restricted to lo ≤ x ≤ hi (end points interpolated): a lens surface within the
    span of the mirror behind it."""
    x = curve.points_mm[:, 0]
    lo, hi = max(lo, float(x[0])), min(hi, float(x[-1]))
    keep = (x > lo) & (x < hi)
    xs = np.concatenate([[lo], x[keep], [hi]])
    t = np.stack([np.ones_like(xs), curve.slope_at(xs)], -1)
    return Curve(curve.name, curve.layer, np.stack([xs, curve.y_at(xs)], -1),
                 t / np.linalg.norm(t, axis=1, keepdims=True))


def band_ring(a: Curve, b: Curve, n: int = 241) -> list[tuple[float, float]]:
    """Closed ring between two curves over their common x span (a left to right, b back)."""
    lo, hi = max(a.x_range_mm[0], b.x_range_mm[0]), min(a.x_range_mm[1], b.x_range_mm[1])
    xs = np.linspace(lo, hi, n)
    pts = np.concatenate([np.stack([xs, a.y_at(xs)], -1), np.stack([xs[::-1], b.y_at(xs[::-1])], -1)])
    return [(round(float(x), 4), round(float(y), 4)) for x, y in pts]


def horn_checks(design: SlotArrayDesign, horns: tuple[HornOutline, ...], mirror_wall_mm: float) -> tuple[Check, ...]:
    """Horns vs each other (channels trimmed where apertures overlap) and vs the feed layer's
    mirror walls and lens (no overlap allowed)."""
    lost = max(h.clipped_mm2 / (h.channel.area + h.clipped_mm2) for h in horns)
    bf = design.beamformer
    obstacles = [Polygon(band_ring(m, offset_curve(m, mirror_back_sign(design, m) * mirror_wall_mm, "back")))
                 for m in bf.mirrors if 1 in layer_indices(m)]
    obstacles += [Polygon(band_ring(bf.mirrors[0], lens)) for lens in bf.lenses]
    feeds = unary_union([h.footprint for h in horns])
    hit = max((feeds.intersection(o.buffer(0)).area for o in obstacles), default=0.0)
    return (Check.upper("feed_horn_channels_trimmed", lost, 0.05, "",
                        "largest share of a horn channel cut away where neighbouring apertures overlap",
                        warn_margin=0.04),
            Check.upper("feed_horns_clear_of_beamformer", hit, 0.0, "mm²",
                        "overlap of the horn bodies with the feed layer's mirror walls / lens"))


def plate_rect(design: SlotArrayDesign, margin: float) -> tuple[float, float, float, float]:
    """Bounding rectangle of the beam-former curves, the design foci and the horn apertures, plus
    ``margin`` (the horn bodies lie behind the apertures, in the plates' notch)."""
    bf = design.beamformer
    pts = [c.points_mm for c in (*bf.mirrors, *bf.lenses)]
    f = design.feeds
    ends = [f.aperture_centres_mm + sgn * f.aperture_mm[0] / 2 * np.stack([-f.aim[:, 1], f.aim[:, 0]], -1)
            for sgn in (-1.0, 1.0)]
    pts += [*ends, bf.foci_mm]
    allp = np.vstack(pts)
    (x0, y0), (x1, y1) = allp.min(0), allp.max(0)
    return x0 - margin, y0 - margin, x1 + margin, y1 + margin
