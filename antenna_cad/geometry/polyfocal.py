"""Model of a polyfocal constrained lens (seed-001 §6, §8.1): one labelled channel per element whose
electrical length equals the synthesized one, and the lens body.

Frame: the synthesis frame scaled to mm — +Z the lens axis (feeds at z < 0), +Y transverse in the
section; 2-D lenses are the YZ section extruded along X by the plate spacing, centred on x = 0.

* 2-D: ``channel-NNN`` (straight prism from the entry point to the exit point, width a_i, height h,
  flat ends normal to its axis: volume = a_i·h·d_i), ``septa`` (metal: the region between the entry
  and the exit surface minus the channels; its two curved faces are the lens surfaces), and
  ``plate-top`` / ``plate-bottom`` (metal, the outline plus a margin).
* 3-D: ``entry-surface`` / ``exit-surface`` (B-spline surfaces through the synthesized points,
  thickened to sheet-metal port plates) and ``channel-NNN`` (rectangular guides a_i × h, the broad
  wall a_i along x).
"""

from __future__ import annotations

import numpy as np
from build123d import Align, Box, Face, Plane, Solid, Vector

from antenna_cad.fabrication.polyfocal import channel_quads, outline_polygon
from antenna_cad.geometry.model import Model, ModelPart
from antenna_cad.geometry.profiles import yz_prism
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check
from antenna_cad.synthesis.polyfocal_design import PolyfocalDesign

PORT_PLATE_MM = 1.0         # 3-D port plates (B-spline surfaces thickened)
READBACK_LIMIT = 1e-6       # relative error of a channel's electrical length read back from its solid


def _channel_3d(p: np.ndarray, q: np.ndarray, w: float, h: float) -> Solid:
    axis = Vector(*(q - p))
    x_dir = Vector(1, 0, 0) if abs(axis.normalized().X) < 0.9 else Vector(0, 1, 0)
    plane = Plane(origin=tuple(p), x_dir=x_dir - axis.normalized() * x_dir.dot(axis.normalized()), z_dir=axis)
    return plane.location * Box(w, h, axis.length, align=(Align.CENTER, Align.CENTER, Align.MIN))


def _fill(base: Material, eps: float) -> Material:
    return Material(f"{base.name} εr {eps:.4f}", float(eps), base.tan_delta, base.density_kg_m3,
                    "channel fill of the synthesized phase index (density and loss of the base material)")


def build_model(design: PolyfocalDesign, fill: Material, metal: Material, plate_mm: float, margin_mm: float) -> Model:
    h = design.height_mm
    parts, channels = [], []
    if design.case.startswith("2d"):
        for quad in channel_quads(design):
            channels.append(yz_prism(quad, -h / 2, h))
        outline = outline_polygon(design)
        body = yz_prism(list(outline.exterior.coords)[:-1], -h / 2, h).cut(*channels)   # one boolean, not 40
        parts.append(ModelPart("septa", metal, "fabricated", body))
        plate = list(outline.buffer(margin_mm, join_style=2).exterior.coords)[:-1]
        parts.append(ModelPart("plate-bottom", metal, "fabricated", yz_prism(plate, -h / 2 - plate_mm, plate_mm)))
        parts.append(ModelPart("plate-top", metal, "fabricated", yz_prism(plate, h / 2, plate_mm)))
    else:
        for name, grid in zip(("entry", "exit"), design.surfaces):
            pts = (grid * design.unit_mm).tolist()
            face = Face.make_surface_from_array_of_points([[tuple(p) for p in row] for row in pts], tol=1e-3)
            side = -PORT_PLATE_MM if name == "entry" else PORT_PLATE_MM
            parts.append(ModelPart(f"{name}-surface", metal, "fabricated", Solid.thicken(face, side)))
        for p, q, w in zip(design.r1_mm, design.r2_mm, design.width_mm):
            channels.append(_channel_3d(p, q, float(w), h))
    for i, (c, eps) in enumerate(zip(channels, design.fill_eps_r)):
        parts.append(ModelPart(f"channel-{i + 1:03d}", _fill(fill, eps), "fabricated", c))
    read = np.array([c.volume for c in channels]) / (design.width_mm * h) * design.index
    error = float(np.max(np.abs(read / design.electrical_mm - 1.0)))
    checks = [Check.upper("channel_electrical_length", error, READBACK_LIMIT, "",
                          "channel solid volume / cross-section × phase index vs the synthesized electrical "
                          "length (relative, worst channel)")]
    return Model(tuple(parts), tuple(checks))
