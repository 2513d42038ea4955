"""Lattices a printer makes from one filament: fill fraction ↔ geometry parameter, wall and gap.

Lengths are in units of the cell size a (multiply by ``cell_mm``). Two lattices:

- ``cubic``: three orthogonal square rods of width w (the rectilinear grid of FDM infill stacked in
  z). Fill f = 3w² − 2w³ (three rods less the twice-counted centre cube); wall = w, gap = 1 − w.
- ``gyroid``: the sheet |g(x, y, z)| ≤ t of the gyroid g = sin X cos Y + sin Y cos Z + sin Z cos X
  (X = 2πx …), the infill slicers print. Its fill is tabulated by sampling. Its wall is the thinnest
  sheet, its gap the narrowest channel between sheets, both measured along the surface normal over the
  whole surface (:data:`GYROID_WIDTHS`; the global minimum of a width is met along a common normal).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

LATTICES = ("cubic", "gyroid")
# (t, thinnest sheet, narrowest channel), in cells: from 30 000 points of g = 0 marched along the normal in
# steps of 2.5e-4 (tests re-measure them); the channels close at t ≈ 1.41
GYROID_WIDTHS = np.array([
    (0.0, 0.0, 0.4318), (0.1, 0.0185, 0.4125), (0.2, 0.037, 0.3932), (0.3, 0.056, 0.3738), (0.4, 0.0745, 0.3538),
    (0.5, 0.094, 0.333), (0.6, 0.1135, 0.3117), (0.7, 0.134, 0.2898), (0.8, 0.1555, 0.2662), (0.9, 0.1775, 0.2412),
    (1.0, 0.2015, 0.214), (1.1, 0.227, 0.1832), (1.2, 0.256, 0.1465), (1.3, 0.2895, 0.097), (1.4, 0.332, 0.0003)])


def gyroid(x, y, z):
    """The gyroid's level-set function, period 1 in each coordinate."""
    X, Y, Z = 2 * np.pi * np.asarray(x), 2 * np.pi * np.asarray(y), 2 * np.pi * np.asarray(z)
    return np.sin(X) * np.cos(Y) + np.sin(Y) * np.cos(Z) + np.sin(Z) * np.cos(X)


@lru_cache(maxsize=None)
def _gyroid_fill_table(samples: int = 96) -> tuple[np.ndarray, np.ndarray]:
    """(t, fill) of the sheet gyroid from the distribution of |g| over a midpoint grid of samples³."""
    s = (np.arange(samples) + 0.5) / samples
    g = np.sort(np.abs(gyroid(*np.meshgrid(s, s, s, indexing="ij"))).ravel())
    t = np.linspace(0.0, 1.5, 301)
    return t, np.searchsorted(g, t, side="right") / g.size


def fill_fraction(lattice: str, parameter) -> np.ndarray:
    """Solid volume fraction of a cell for the lattice parameter (w for cubic, t for gyroid)."""
    p = np.asarray(parameter, float)
    if lattice == "cubic":
        return 3 * p**2 - 2 * p**3
    t, f = _gyroid_fill_table()
    return np.interp(p, t, f)


def parameter_for(lattice: str, fill) -> np.ndarray:
    """The lattice parameter that gives ``fill`` (inverse of :func:`fill_fraction`, monotone)."""
    f = np.clip(np.asarray(fill, float), 0.0, 1.0)
    if lattice == "cubic":
        w = np.linspace(0.0, 1.0, 2001)
        return np.interp(f, fill_fraction("cubic", w), w)
    t, ft = _gyroid_fill_table()
    keep = np.concatenate(([True], np.diff(ft) > 0))
    return np.interp(f, ft[keep], t[keep])


def gyroid_wall(t) -> np.ndarray:
    """Thinnest sheet of the gyroid |g| ≤ t, in cells."""
    return np.interp(t, GYROID_WIDTHS[:, 0], GYROID_WIDTHS[:, 1])


def gyroid_gap(t) -> np.ndarray:
    """Narrowest channel between the sheets of the gyroid |g| ≤ t, in cells."""
    return np.interp(t, GYROID_WIDTHS[:, 0], GYROID_WIDTHS[:, 2])


EDGE_PER_WALL = 0.7     # level-set grid edge / thinnest sheet or channel: the sheet's fill within 1 % (tests)


def gyroid_edge_mm(cell_mm: float, fill_range: tuple[float, float]) -> float:
    """The level-set grid edge (mm) that resolves the thinnest sheet and the narrowest channel of the
    printable fill range (:mod:`antenna_cad.printed.gyroid_mesh`)."""
    t_lo, t_hi = parameter_for("gyroid", np.array(fill_range))
    return EDGE_PER_WALL * min(float(gyroid_wall(t_lo)), float(gyroid_gap(t_hi))) * cell_mm


def gyroid_grid_points(shape: str, radius_mm: float, height_mm: float, edge_mm: float) -> int:
    """Level-set evaluations of one part (a hemisphere, or a cylinder of ``height_mm``): the body-centred
    grid's two points per edge³ of the bounding box. Sets the gyroid's meshing time (linear in it)."""
    return round(2 * (2 * radius_mm) ** 2 * height_mm / edge_mm**3)


@dataclass(frozen=True)
class Printable:
    """What a printer can make of a lattice of cell ``cell_mm``: the fill range between the thinnest wall
    (``min_wall_mm``, a nozzle's line) and the narrowest gap (``min_gap_mm``)."""
    lattice: str
    cell_mm: float
    min_wall_mm: float
    min_gap_mm: float

    def wall_mm(self, fill) -> np.ndarray:
        f = np.asarray(fill, float)
        if self.lattice == "cubic":
            return parameter_for("cubic", f) * self.cell_mm
        return gyroid_wall(parameter_for("gyroid", f)) * self.cell_mm

    def gap_mm(self, fill) -> np.ndarray:
        f = np.asarray(fill, float)
        if self.lattice == "cubic":
            return (1 - parameter_for("cubic", f)) * self.cell_mm
        return gyroid_gap(parameter_for("gyroid", f)) * self.cell_mm

    @property
    def fill_range(self) -> tuple[float, float]:
        """(lowest, highest) printable fill: wall ≥ min_wall and gap ≥ min_gap (0, 0 when none is)."""
        f = np.linspace(0.0, 1.0, 4001)
        ok = (self.wall_mm(f) >= self.min_wall_mm) & (self.gap_mm(f) >= self.min_gap_mm)
        return (float(f[ok][0]), float(f[ok][-1])) if ok.any() else (0.0, 0.0)
