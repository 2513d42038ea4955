"""Layout of the slot-array solids in numbers (numpy only, no CAD kernel): the z stack, guide
extents, plate rectangle, mirror backing side, coupling slots, slot outlines for templates."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.synthesis.slot_array import Curve, SlotArrayDesign, offset_curve

END_WEB_MM = 0.2      # metal left between the body start and the first slot


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
                 n_arc: int = 8) -> np.ndarray:
    """Rounded-end rectangle (ring of points, counter-clockwise) for templates."""
    u = np.array([np.sin(angle), np.cos(angle)])
    nrm = np.array([-u[1], u[0]])
    r, s = width / 2, max(length / 2 - width / 2, 0.0)
    c = np.array([x, y])
    pts = []
    for sign in (1.0, -1.0):
        centre = c + sign * s * u
        phi0 = np.arctan2(*(sign * -nrm)[::-1])
        for q in np.linspace(0, np.pi, n_arc + 1):
            ang = phi0 + q
            pts.append(centre + r * np.array([np.cos(ang), np.sin(ang)]))
    return np.array(pts)


def guide_extent(design: SlotArrayDesign, wall_mm: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Per guide: body start y, end y; outer half-width.

    The rectangular body starts beyond the (curved) coupling slot, at the highest point of its far
    edge across the body width, but never past the first slot (less END_WEB_MM): on steep outer
    guides a corner of the bottom wall then overlaps the coupling slot (see :func:`end_overlap_mm`).
    """
    s = design.slots
    half = design.guide_width_mm / 2 + wall_mm
    _, hy = s.half_extents_mm()
    low = np.full(len(s.guide_x_mm), np.inf)
    np.minimum.at(low, s.guide_index, s.y_mm - hy)
    edge = np.array([float(design.coupling_slot_edge.y_at(np.linspace(x - half, x + half, 9)).max())
                     for x in s.guide_x_mm])
    y0 = np.minimum(edge, low - END_WEB_MM)
    y1 = s.guide_end_y_mm + 0.25 * s.period_mm
    return y0, y1, half


def end_overlap_mm(design: SlotArrayDesign, wall_mm: float) -> float:
    """Largest length by which a guide body's start overlaps the coupling slot's far edge."""
    y0, _, half = guide_extent(design, wall_mm)
    edge = np.array([float(design.coupling_slot_edge.y_at(np.linspace(x - half, x + half, 9)).max())
                     for x in design.slots.guide_x_mm])
    return float(np.max(edge - y0))


def plate_rect(design: SlotArrayDesign, margin: float) -> tuple[float, float, float, float]:
    bf = design.beamformer
    pts = [c.points_mm for c in (*bf.mirrors, *bf.lenses)]
    f = design.feeds
    back = f.aperture_centres_mm - f.aim * f.length_mm
    pts += [f.aperture_centres_mm, back, bf.foci_mm]
    allp = np.vstack(pts)
    (x0, y0), (x1, y1) = allp.min(0), allp.max(0)
    return x0 - margin, y0 - margin, x1 + margin, y1 + margin
