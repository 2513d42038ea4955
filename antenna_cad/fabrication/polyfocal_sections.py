"""1:1 section gauges of the port surfaces of a 3-D polyfocal lens (seed-001 §2, §8.1 item 3): for
each surface, the sections by the planes x = k·pitch, each a gauge whose working edge is the
surface's section and whose back edge is a straight datum ``depth_mm`` beyond the surface's extreme
(toward the feeds for the entry surface, away from them for the exit surface), for forming and
checking the B-spline port plates.

Frame: the synthesis frame in mm (+Z the lens axis, feeds at z < 0). Each gauge is drawn with
drawing x = y and drawing y = z (datum line at the gauge's foot), gauges stacked along the
drawing's y with a gap. The section of a surface is interpolated (C¹ Clough–Tocher) from its exact
synthesized points — the dense grid, the element points and the rim grid the CAD surface passes
through; the check compares the interpolant with exact points it was not built from.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator
from shapely.geometry import LineString, MultiPoint, Polygon

from antenna_cad.fabrication.templates import Drawing
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.polyfocal import ConstrainedLens
from antenna_cad.synthesis.polyfocal_design import PolyfocalDesign

GAUGE_POINTS = 201           # samples of one section curve
GAUGE_GAP_MM = 15.0          # between stacked gauges on the drawing
CHECK_FRACTION = 1 / 200     # read-back limit: λ/200 (digest §8.3 "export validation")


@dataclass(frozen=True)
class Gauge:
    surface: str                         # "entry" | "exit"
    x_mm: float                          # section plane x
    y_mm: np.ndarray                     # section samples
    z_mm: np.ndarray
    datum_z_mm: float                    # the gauge's straight back edge


def _points(design: PolyfocalDesign, extra: ConstrainedLens, which: int) -> np.ndarray:
    """Exact points of one surface (mm, N×3): the design's dense grid, its rim grid and ``extra``
    (a denser solve of the same lens whose nodes miss the element points, held out for the check)."""
    dense = (design.dense.r1, design.dense.r2, extra.r1, extra.r2)
    grid = design.surfaces[which].reshape(-1, 3)
    return np.concatenate([dense[which], dense[which + 2], grid]) * design.unit_mm


def _interpolant(pts: np.ndarray) -> CloughTocher2DInterpolator:
    xy, keep = np.unique(np.round(pts[:, :2], 9), axis=0, return_index=True)
    return CloughTocher2DInterpolator(xy, pts[keep, 2])


def section_gauges(design: PolyfocalDesign, extra: ConstrainedLens, pitch_mm: float,
                   depth_mm: float) -> tuple[list[Gauge], Check]:
    """Gauges of both surfaces at x = k·pitch inside each surface's footprint, and the read-back
    check: interpolated z at the element points (exact, not used by the interpolant) vs their z."""
    gauges, worst = [], 0.0
    for which, name in enumerate(("entry", "exit")):
        pts = _points(design, extra, which)
        interp = _interpolant(pts)
        held = (design.r1_mm, design.r2_mm)[which]
        dev = np.abs(interp(held[:, 0], held[:, 1]) - held[:, 2])
        worst = max(worst, float(np.nanmax(dev)))
        hull = MultiPoint([tuple(p) for p in pts[:, :2]]).convex_hull.buffer(-1e-6)
        zmin, zmax = float(pts[:, 2].min()), float(pts[:, 2].max())
        datum = zmin - depth_mm if name == "entry" else zmax + depth_mm
        xmin, _, xmax, _ = hull.bounds
        for k in range(int(np.ceil(xmin / pitch_mm)), int(np.floor(xmax / pitch_mm)) + 1):
            x = k * pitch_mm
            chord = LineString([(x, -1e9), (x, 1e9)]).intersection(hull)
            if chord.is_empty or chord.length <= 0:
                continue
            _, y0, _, y1 = chord.bounds
            y = np.linspace(y0, y1, GAUGE_POINTS)
            z = interp(np.full_like(y, x), y)
            if np.all(np.isfinite(z)):
                gauges.append(Gauge(name, x, y, z, datum))
    limit = design.wavelength_mm * CHECK_FRACTION
    check = Check.upper("section_gauge_readback", worst, limit, "mm",
                        "section gauges' surface (interpolated from the exact points) vs the exact element points")
    return gauges, check


def gauge_polygon(g: Gauge) -> Polygon:
    """The gauge in (y, z): the section curve closed by its datum edge."""
    return Polygon(list(zip(g.y_mm, g.z_mm)) + [(g.y_mm[-1], g.datum_z_mm), (g.y_mm[0], g.datum_z_mm)])


def gauges_drawing(gauges: list[Gauge], surface: str, pitch_mm: float, title: str) -> Drawing:
    """One drawing per surface: its gauges stacked, each labelled with its plane x."""
    d = Drawing(f"gauges-{surface}")
    offset = 0.0
    for g in (g for g in gauges if g.surface == surface):
        sign = 1.0 if surface == "entry" else -1.0          # every gauge drawn datum-down
        poly = gauge_polygon(g)
        ring = [(y, offset + sign * (z - g.datum_z_mm)) for y, z in list(poly.exterior.coords)[:-1]]
        d.cut.append([(round(a, 4), round(b, 4)) for a, b in ring])
        top = max(b for _, b in ring)
        d.marks.append([(0.0, offset), (0.0, top + 3.0)])                    # the plane y = 0
        d.texts.append((f"{surface} x = {g.x_mm:+.1f} mm (datum z = {g.datum_z_mm:.2f} mm)",
                        float(g.y_mm[0]), offset - 7.0, 4.0))
        offset = top + GAUGE_GAP_MM
    x0, y0, _, y1 = d.bounds()
    d.add_title([f"{title}: {surface}-surface section gauges 1:1 at x = k·{pitch_mm:g} mm; working edge = the "
                 f"surface's section, straight edge = datum plane {'behind (toward the feeds)' if surface == 'entry' else 'beyond'} "
                 "the surface; vertical mark at y = 0"], x0, y1 + 20.0)
    d.add_check_bar(x0, y0 - 30.0)
    return d
