"""Resource limits of a build: how many sheets, shells, slots, pieces, drawings, template
pages and STL triangles a design may make. Above ``soft`` the build goes on with a warning check (a workshop job of that size
is unusual — often a unit slip); above ``hard`` it stops with a DesignError naming the spec field to
change, before any CAD work (triangles: after the solid model, before meshing). New kinds need nothing: :func:`counts` reads the plans generically."""

from __future__ import annotations

import math
from dataclasses import dataclass

from antenna_cad.synthesis.checks import Check, DesignError


@dataclass(frozen=True)
class Limit:
    what: str          # "sheets"
    field: str         # the spec field that sets the count
    soft: int
    hard: int

    def check(self, count: int) -> list[Check]:
        """[] within ``soft``; a warning check up to ``hard``; DesignError above it."""
        if count > self.hard:
            raise DesignError(self.field, f"{count} {self.what} exceed the limit of {self.hard} "
                                          f"(a unit slip? change {self.field})")
        if count > self.soft:
            return [Check(f"{self.what.lower().replace(' ', '_')}_count", "warn", float(count), float(self.soft), "",
                          f"{count} {self.what} (more than the usual {self.soft}; check {self.field})")]
        return []


LIMITS = {
    "sheets": Limit("sheets", "fabrication.sheet_thickness_mm", soft=60, hard=400),
    "shells": Limit("shells", "design.layers.count", soft=30, hard=100),
    "slots": Limit("slots", "array.count", soft=20_000, hard=100_000),
    "pieces": Limit("pieces", "fabrication.board", soft=400, hard=4000),
    "drawings": Limit("drawings", "fabrication.board", soft=300, hard=3000),
    "pages": Limit("template pages", "outputs.templates", soft=5000, hard=100_000),
    "triangles": Limit("STL triangles", "outputs.mesh_tolerance_mm", soft=5_000_000, hard=20_000_000),
    "cells": Limit("lattice cells", "fabrication.cell_mm", soft=50_000, hard=500_000),   # printed: 24–48 triangles each
    # the gyroid's level set: ~3 µs a point and a triangle per point, one core (benchmarks/printed_lattice.py)
    "gyroid_points": Limit("gyroid level-set points", "fabrication.min_wall_mm", soft=4_000_000, hard=30_000_000),
}


def counts(design, layup, fab=None) -> dict[str, int]:
    """The counts a plan holds (sheets of a layup, shells of a graded lens, slots of an array;
    pieces and drawings of a fabrication plan), whatever the kind."""
    found = {}
    if layup is not None and hasattr(layup, "sheets"):
        found["sheets"] = len(layup.sheets)
    if isinstance(getattr(design, "layers", None), (list, tuple)):
        found["shells"] = len(design.layers)
    slots = getattr(design, "slots", None)
    if slots is not None and hasattr(slots, "x_mm"):
        found["slots"] = len(slots.x_mm)
    if fab is not None:
        found["pieces"] = len(fab.rows)
        found["drawings"] = len(fab.drawings)
    return found


def template_pages(drawings) -> int:
    """Estimated A4 pages of the tiled templates, before drawing: per drawing the tile grid over its
    CUT outline (an upper bound: empty tiles are dropped when tiling); a lazily drawn layup's from
    its sheets' weights (Σ r², the area of each sheet's disc and rings over π)."""
    from antenna_cad.fabrication.templates import OVERLAP_MM, WINDOW_MM
    step_w, step_h = WINDOW_MM[0] - OVERLAP_MM, WINDOW_MM[1] - OVERLAP_MM
    if hasattr(drawings, "weights"):
        return len(drawings) + math.ceil(4 * sum(drawings.weights) / (step_w * step_h))
    pages = 0
    for drawing in drawings:
        x0, y0, x1, y1 = drawing.cut_bounds()
        pages += math.ceil(max(x1 - x0, 0) / step_w + 1) * math.ceil(max(y1 - y0, 0) / step_h + 1)
    return pages


def limit_checks(found: dict[str, int]) -> list[Check]:
    return [c for what, n in found.items() for c in LIMITS[what].check(n)]
