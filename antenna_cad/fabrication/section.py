"""A sheet layup seen in its meridional section: the slabs the as-built ray trace crosses.

Section plane: x = 0 of the sheet frame (:mod:`antenna_cad.fabrication.layup`), the vertical plane
that holds the pedestal foot and, with ``joining: neck``, the necks; the trace's y is the sheet's y
(+Y up). The foam dowels are the lens material and fill their holes, so the trace does not see them.
A taper-cut sheet (``edge: taper``) is sliced into sub-slabs ``TAPER_SLICE_MM`` thick, each with
its cone's radius at mid-depth: a staircase far finer than a wavelength, which the fast model and
the full-wave stage see as the cone (the GO trace takes the cones as faces instead,
:func:`antenna_cad.asbuilt.lens.lens_variants`).
"""

from __future__ import annotations

import math

import numpy as np
from shapely.geometry import LineString
from shapely.ops import unary_union

from antenna_cad.fabrication.layup import LayupPlan, SheetPlan
from antenna_cad.fabrication.outline import circle_polygon, hole_polygons
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.raytrace.trace2d import Slabs

TAPER_SLICE_MM = 2.0


def _slices(layup: LayupPlan) -> tuple[list[float], list[tuple[SheetPlan, float]]]:
    """z edges of the section's slabs and each slab's (sheet, rim radius): one slab per stepped
    sheet, sub-slabs with the cone's mid-depth radius for a taper-cut one."""
    edges, slabs = [layup.sheets[0].z_min_mm], []
    for s in layup.sheets:
        m = math.ceil(s.thickness_mm / TAPER_SLICE_MM - 1e-9) if s.tapered else 1
        z = s.z_min_mm + s.thickness_mm * np.arange(m + 1) / m
        edges += list(z[1:])
        slabs += [(s, float(s.radius_at_z(mid))) for mid in (z[:-1] + z[1:]) / 2]
    return edges, slabs


def stepped_section(layup: LayupPlan, n: float) -> Slabs:
    """The stack as cut, before sanding: every sheet's nominal lens disc (seed-000 §6.2 step 4), or
    its cone when taper-cut."""
    edges, slabs = _slices(layup)
    return Slabs.from_intervals(edges, [[(-r, r)] for _, r in slabs], n)


def fabricated_section(layup: LayupPlan, fab: FabPlan, n: float) -> Slabs:
    """The stack as fabricated: the cut pieces of every sheet (disc, foot, neck, board strips) with
    the dowels in their holes, cut by the plane x = 0."""
    reach = layup.lens_radius_mm + layup.pedestal_height_mm + 1.0
    line = LineString([(0.0, -reach), (0.0, reach)])
    edges, slabs = _slices(layup)
    intervals = []
    for s, r in slabs:
        # a taper-cut sheet's lens pieces are its cone at this depth (its feet stay as cut)
        pieces = [p.polygon for p in fab.pieces if p.sheet_index == s.index and not (s.tapered and "-foot" not in p.label)]
        disc = [circle_polygon(0.0, 0.0, r)] if s.tapered and r > 0 else []
        sheet = unary_union(pieces + disc + hole_polygons(s.foot_dowels + (() if s.tapered else s.lens_dowels)))
        cut = sheet.intersection(line)
        parts = getattr(cut, "geoms", [cut])
        intervals.append([(min(y for _, y in g.coords), max(y for _, y in g.coords)) for g in parts if g.length > 0])
    return Slabs.from_intervals(edges, intervals, n)
