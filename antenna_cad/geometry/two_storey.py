"""Solids of the two-storey lens–mirror antenna (seed-001 §1.5 Realisation, §8.1 item 2): a split
block a machinist mills from three plates, and one reference solid per guide.

Frame: the lens frame in mm — y transverse, z the axis (feeds at z < 0), x the stacking direction:
layer 1 x ∈ [−h/2, h/2], the septum [h/2, h/2 + t], layer 2 [h/2 + t, 3h/2 + t].

* ``block-lower`` — bottom plate with the layer-1 pockets (feed region, horns, guides, the lower
  halves of the U-bends), depth h;
* ``block-upper`` — the septum with the layer-2 pockets (guides, output region) and the bends' upper
  halves;
* ``cover`` — the top plate with the E-plane flare (plate spacing h → mouth height) milled into it;
* ``guide-NNN`` (reference, the guide's air) — the layer-1 run (slanted prism with its mitred kink
  and axial run), the U-bend (a half annulus swept across the guide width) and the layer-2 run, with
  flat ends at the entry and exit points: volume / (a·h) is the guide's centre-line length exactly
  (a mitred strip's area is its width times its centre line; the bend's by Pappus), so the
  equal-length condition is read back from the solids.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import Polygon

from antenna_cad.geometry import kernel
from antenna_cad.geometry.model import Model, ModelPart, relative_volume_check
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.two_storey import (TwoStorey, focus_spreads, layer_air, outlines, pierce,
                                              slab_volumes)

READBACK_LIMIT = 1e-9       # relative spread of the guides' lengths read back from their solids
FOCUS_LIMIT = 1e-9          # eikonal spread / D at the design foci through the read-back lengths


def _plan_prism(poly: Polygon, x0: float, height: float) -> kernel.Shape:
    """A plan polygon (y, z) extruded along x from ``x0`` by ``height``."""
    ring = np.asarray(poly.exterior.coords)[:-1]
    face = kernel.face(kernel.polygon([(x0, y, z) for y, z in ring]))
    return kernel.extrude(face, (height, 0.0, 0.0))


def _bend(ts: TwoStorey, i: int) -> kernel.Shape:
    """The U-bend of guide i: a half annulus in the xz plane (inner radius septum/2 about the septum's
    edge, outer + h) beyond z_m, swept across the guide width along y."""
    h, t, a = ts.p.height, ts.p.septum, ts.p.guide_width
    xc, zm, y0 = h / 2 + t / 2, float(ts.zm[i]), float(ts.y2[i]) - a / 2
    ri, ro = t / 2, t / 2 + h
    inner = kernel.arc((xc - ri, y0, zm), (xc, y0, zm + ri), (xc + ri, y0, zm))
    outer = kernel.arc((xc - ro, y0, zm), (xc, y0, zm + ro), (xc + ro, y0, zm))
    ends = [kernel.line((xc - ro, y0, zm), (xc - ri, y0, zm)), kernel.line((xc + ri, y0, zm), (xc + ro, y0, zm))]
    return kernel.extrude(kernel.face(kernel.wire([inner, outer, *ends])), (0.0, a, 0.0))


def _layer2_run(ts: TwoStorey, i: int, mouth: float) -> kernel.Shape:
    h, t, a = ts.p.height, ts.p.septum, ts.p.guide_width
    z0 = float(ts.ze[i]) - mouth
    return kernel.box((h / 2 + t, float(ts.y2[i]) - a / 2, z0), (h, a, float(ts.zm[i]) - z0))


def _guide(ts: TwoStorey, i: int, mouth: float = 0.0) -> list[kernel.Shape]:
    """Guide i's air: layer-1 run, bend, layer-2 run (opened ``mouth`` past its ends)."""
    h = ts.p.height
    return [_plan_prism(ts.footprint(i, 1, mouth, to_bend=True), -h / 2, h), _bend(ts, i),
            _layer2_run(ts, i, mouth)]


def _flare(ts: TwoStorey, half_width: float) -> kernel.Shape:
    """The E-plane flare's air above layer 2: the upper plate rises from h to the mouth height."""
    top = 1.5 * ts.p.height + ts.p.septum
    rise = ts.p.mouth_height - ts.p.height
    pts = [(top, -half_width, ts.z_flare), (top, -half_width, ts.z_mouth), (top + rise, -half_width, ts.z_mouth)]
    return kernel.extrude(kernel.face(kernel.polygon(pts)), (0.0, 2 * half_width, 0.0))


def build_model(ts: TwoStorey, air: Material, metal: Material, plate_mm: float, margin_mm: float,
                foci: list[tuple[np.ndarray, np.ndarray]], aperture_mm: float) -> Model:
    h, t = ts.p.height, ts.p.septum
    mouth = ts.p.guide_width * 2
    lower, upper = outlines(ts, mouth, margin_mm)
    tools = [s for i in range(len(ts.y1)) for s in _guide(ts, i, mouth)]
    tools += [_plan_prism(q, -h / 2, h) for q in layer_air(ts, 1, mouth, pierce(margin_mm))[len(ts.y1):]]
    tools += [_plan_prism(layer_air(ts, 2, mouth)[-1], h / 2 + t, h)]
    half = float(np.max(np.abs(ts.exit_curve[:, 0]))) + ts.p.guide_width / 2
    tools.append(_flare(ts, half))
    cover = plate_mm + ts.p.mouth_height - h
    slabs = (("block-lower", lower, -h / 2 - plate_mm, plate_mm + h), ("block-upper", upper, h / 2, t + h),
             ("cover", upper, 1.5 * h + t, cover))
    parts = [ModelPart(label, metal, "fabricated", kernel.cut(_plan_prism(poly, x0, dx), tools))
             for label, poly, x0, dx in slabs]
    guides = [kernel.fuse(_guide(ts, i)) for i in range(len(ts.y1))]
    parts += [ModelPart(f"guide-{i + 1:03d}", air, "reference", g) for i, g in enumerate(guides)]
    lengths = np.array([kernel.volume(g) for g in guides]) / (ts.p.guide_width * h)
    spread = float(np.ptp(lengths) / lengths.max())
    error = float(np.max(np.abs(lengths / ts.total - 1.0)))
    sigma = focus_spreads(ts, lengths, foci) / aperture_mm
    checks = [Check.upper("guide_length_readback_spread", spread, READBACK_LIMIT, "",
                          "spread of the guides' centre-line lengths read back from their solids (volume / a·h), "
                          "relative: the equal-length condition on the built geometry"),
              Check.upper("guide_length_readback_error", error, READBACK_LIMIT, "",
                          "guide solid's length vs the line table's (relative, worst guide)"),
              Check.upper("two_storey_focus_spread", float(sigma.max()), FOCUS_LIMIT, "",
                          "eikonal spread / D at F, F1, F2 through the built guides (entry point, solid's length, "
                          "folded exit point; seed-001 (1.15)–(1.17)): " + ", ".join(f"{s:.1e}" for s in sigma))]
    checks += [Check(f"{p.label}_valid", "pass" if kernel.is_valid(p.shape) else "fail", 1.0, 1.0, "",
                     f"{p.label}: BRepCheck of the machined plate") for p in parts[:3]]
    plan = slab_volumes(ts, mouth, margin_mm, plate_mm)
    checks += [relative_volume_check(f"{p.label}_volume_vs_plan", kernel.volume(p.shape), plan[p.label],
                                     f"{p.label} solid vs its plan (outline less pockets, bends, flare)")
               for p in parts[:3]]
    return Model(tuple(parts), tuple(checks), cutaway=("cover", "block-upper"))
