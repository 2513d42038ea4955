"""Lattices a printer makes from one filament: fill fraction ↔ geometry parameter, wall and gap.

Lengths are in units of the cell size a (multiply by ``cell_mm``). Two lattices:

- ``cubic``: three orthogonal square rods of width w (the rectilinear grid of FDM infill stacked in
  z). Fill f = 3w² − 2w³ (three rods less the twice-counted centre cube); wall = w, gap = 1 − w.
- ``gyroid``: the sheet |g(x, y, z)| ≤ t of the gyroid g = sin X cos Y + sin Y cos Z + sin Z cos X
  (X = 2πx …), the infill slicers print. Its fill is tabulated by sampling. Wall and gap are those of
  the equivalent stack of plates with the gyroid's area per volume A = 3.0924/a (its mid-surface area
  per cell): spacing 1/A, wall f/A, gap (1 − f)/A — the mean thickness of the sheet and of the space
  between sheets.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

LATTICES = ("cubic", "gyroid")
GYROID_AREA = 3.0924         # mid-surface area of the gyroid per unit cell (Schoen; checked by sampling in tests)
GYROID_T_MAX = 1.45          # |g| ≤ 1.5 everywhere; above ~1.41 the sheet closes the channels


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
        return f / GYROID_AREA * self.cell_mm

    def gap_mm(self, fill) -> np.ndarray:
        f = np.asarray(fill, float)
        if self.lattice == "cubic":
            return (1 - parameter_for("cubic", f)) * self.cell_mm
        return (1 - f) / GYROID_AREA * self.cell_mm

    @property
    def fill_range(self) -> tuple[float, float]:
        """(lowest, highest) printable fill: wall ≥ min_wall and gap ≥ min_gap (0, 0 when none is)."""
        f = np.linspace(0.0, 1.0, 4001)
        ok = (self.wall_mm(f) >= self.min_wall_mm) & (self.gap_mm(f) >= self.min_gap_mm)
        return (float(f[ok][0]), float(f[ok][-1])) if ok.any() else (0.0, 0.0)
