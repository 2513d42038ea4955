"""A sheet layup seen in its meridional section: the slabs the as-built ray trace crosses (issue 6).

Section plane: x = 0 of the sheet frame (:mod:`antenna_cad.fabrication.layup`), the vertical plane
that holds the pedestal foot and, with ``joining: neck``, the necks; the trace's y is the sheet's y
(+Y up). The foam dowels are the lens material and fill their holes, so the trace does not see them.
"""

from __future__ import annotations

from shapely.geometry import LineString
from shapely.ops import unary_union

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.fabrication.outline import hole_polygons
from antenna_cad.fabrication.sheets import FabPlan
from antenna_cad.raytrace.trace2d import Slabs


def _z_edges(layup: LayupPlan) -> list[float]:
    return [s.z_min_mm for s in layup.sheets] + [layup.sheets[-1].z_max_mm]


def stepped_section(layup: LayupPlan, n: float) -> Slabs:
    """The stack as cut, before sanding: every sheet's nominal lens disc (seed-000 §6.2 step 4)."""
    return Slabs.from_intervals(_z_edges(layup), [[(-s.radius_mm, s.radius_mm)] for s in layup.sheets], n)


def fabricated_section(layup: LayupPlan, fab: FabPlan, n: float) -> Slabs:
    """The stack as fabricated: the cut pieces of every sheet (disc, foot, neck, board strips) with
    the dowels in their holes, cut by the plane x = 0."""
    reach = layup.lens_radius_mm + layup.pedestal_height_mm + 1.0
    line = LineString([(0.0, -reach), (0.0, reach)])
    intervals = []
    for s in layup.sheets:
        sheet = unary_union([p.polygon for p in fab.pieces if p.sheet_index == s.index]
                            + hole_polygons(s.lens_dowels + s.foot_dowels))
        cut = sheet.intersection(line)
        parts = getattr(cut, "geoms", [cut])
        intervals.append([(min(y for _, y in g.coords), max(y for _, y in g.coords)) for g in parts if g.length > 0])
    return Slabs.from_intervals(_z_edges(layup), intervals, n)
