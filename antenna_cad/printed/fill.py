"""Fill mapping: the local lattice fill whose homogenized εr follows a lens law, clipped to what the
printer can make, and the εr error where it is clipped.

εr_eff(fill) comes from the shipped unit-cell table (:func:`antenna_cad.printed.homogenization.homogenized`);
the printable fill range from the thinnest wall and the narrowest gap
(:class:`antenna_cad.printed.lattice.Printable`). A fill below the range (law εr near 1, the outer
shells of a Luneburg lens) is raised to the thinnest printable wall, one above it lowered to the
narrowest gap: the lens there is denser or lighter than the law, and the table says by how much.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from antenna_cad.printed.homogenization import homogenized
from antenna_cad.printed.lattice import Printable, fill_fraction, parameter_for


@dataclass(frozen=True)
class FillMap:
    """Fill along the lens law's coordinate r (mm), sampled on ``r_mm``."""
    lattice: str
    eps_f: float
    cell_mm: float
    fill_range: tuple[float, float]
    eps_range: tuple[float, float]         # εr_eff of the printable fill range
    r_mm: np.ndarray
    eps_law: np.ndarray
    fill: np.ndarray                       # chosen (clipped) fill
    eps_printed: np.ndarray                # εr_eff of the chosen fill
    anisotropy: float                      # |εx − εy| of the table (0: isotropic lattice)

    @property
    def eps_error(self) -> np.ndarray:
        return self.eps_printed - self.eps_law

    def clipped_regions(self) -> list[dict]:
        """Contiguous radius intervals where the fill is clipped: the law's εr there, the printed
        εr, and the largest |εr error|."""
        bad = np.abs(self.eps_error) > 1e-9
        rows = []
        i = 0
        while i < len(bad):
            if not bad[i]:
                i += 1
                continue
            j = i
            while j + 1 < len(bad) and bad[j + 1]:
                j += 1
            sl = slice(i, j + 1)
            rows.append({"r_from_mm": float(self.r_mm[i]), "r_to_mm": float(self.r_mm[j]),
                         "eps_law_min": float(self.eps_law[sl].min()), "eps_law_max": float(self.eps_law[sl].max()),
                         "eps_printed": float(self.eps_printed[i]),
                         "max_abs_eps_error": float(np.abs(self.eps_error[sl]).max()),
                         "side": "below the thinnest wall" if self.fill[i] <= self.fill_range[0] + 1e-12
                         else "above the narrowest gap"})
            i = j + 1
        return rows


def fill_map(law: Callable[[np.ndarray], np.ndarray], r_max_mm: float, lattice: str, eps_f: float,
             printable: Printable, samples: int = 401) -> FillMap:
    """The fill that makes εr_eff(fill) = law(r) on 0 ≤ r ≤ ``r_max_mm``, clipped to the printable range."""
    h = homogenized(lattice, eps_f)
    lo, hi = printable.fill_range
    r = np.linspace(0.0, r_max_mm, samples)
    eps = np.asarray(law(r), float)
    fill = np.clip(h.fill_for(eps), lo, hi)
    return FillMap(lattice, eps_f, printable.cell_mm, (lo, hi), (float(h.eps_at(lo)), float(h.eps_at(hi))), r, eps,
                   fill, h.eps_at(fill), float(h.anisotropy))


def rod_width_mm(fmap: FillMap, r_mm) -> np.ndarray:
    """Cubic lattice: the rod width of the clipped fill at radius ``r_mm`` (interpolated)."""
    f = np.interp(r_mm, fmap.r_mm, fmap.fill)
    return parameter_for("cubic", f) * fmap.cell_mm


def fill_integral_mm3(fmap: FillMap, r_in_mm: float, shape: str, height_mm: float | None = None) -> float:
    """Solid volume of the lattice ∫ fill dV over the inner body of radius ``r_in_mm`` (sphere: 4π∫f r² dr;
    cylinder of ``height_mm``: 2πh∫f r dr), the analytic reference for the meshed lattice."""
    r = np.linspace(0.0, r_in_mm, 2001)
    if fmap.lattice == "cubic":
        f = fill_fraction("cubic", rod_width_mm(fmap, r) / fmap.cell_mm)
    else:
        f = np.interp(r, fmap.r_mm, fmap.fill)
    if shape == "sphere":
        return float(4 * np.pi * np.trapezoid(f * r * r, r))
    return float(2 * np.pi * height_mm * np.trapezoid(f * r, r))


def _pair(width_mm, step_mm: float, lo_mm: float, hi_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """(width clipped to the printable multiples of ``step_mm``, the lower of its two neighbouring multiples)."""
    lo_q = math.ceil(lo_mm / step_mm - 1e-9)
    hi_q = math.floor(hi_mm / step_mm + 1e-9)
    w = np.clip(np.asarray(width_mm, float), lo_q * step_mm, hi_q * step_mm)
    return w, np.minimum(np.floor(w / step_mm + 1e-9), hi_q - 1) * step_mm


def _upper_fraction(w, base, step_mm, average) -> np.ndarray:
    g0, g1 = average(base), average(base + step_mm)
    return np.clip((average(w) - g0) / np.where(g1 != g0, g1 - g0, 1.0), 0.0, 1.0)


def dithered_widths(width_mm, along, step_mm: float, lo_mm: float, hi_mm: float,
                    average=lambda w: w) -> tuple[np.ndarray, np.ndarray]:
    """Rod widths a slicer places (multiples of ``step_mm`` in [lo_mm, hi_mm]) alternated along a line
    of cells so that the mean of ``average(width)`` (the width itself, or the εr_eff it gives) along the
    line is that of ``width_mm``: the two neighbouring multiples, the upper one in a fraction t of the
    cells spread evenly by the cell's integer position ``along`` the line (error diffusion). A wave
    crossing the line sees the mean (the cells are far below the wavelength). Returns (widths, t)."""
    w, base = _pair(width_mm, step_mm, lo_mm, hi_mm)
    t = _upper_fraction(w, base, step_mm, average)
    i = np.asarray(along, np.int64)
    upper = np.floor((i + 1) * t + 1e-9) > np.floor(i * t + 1e-9)
    return base + upper * step_mm, t


def eps_of_width(lattice: str, eps_f: float, cell_mm: float):
    """εr_eff of a rod width (mm) of the cubic lattice, from the unit-cell table."""
    h = homogenized(lattice, eps_f)
    return lambda w: h.eps_at(fill_fraction("cubic", np.asarray(w, float) / cell_mm))


def dithered_fill(width_mm, step_mm: float, lo_mm: float, hi_mm: float, cell_mm: float, lattice: str,
                  eps_f: float) -> tuple[np.ndarray, np.ndarray]:
    """(mean fill, mean εr_eff) of a line of cells dithered on εr_eff as :func:`dithered_widths`."""
    eps = eps_of_width(lattice, eps_f, cell_mm)
    w, base = _pair(width_mm, step_mm, lo_mm, hi_mm)
    t = _upper_fraction(w, base, step_mm, eps)
    f0, f1 = fill_fraction("cubic", base / cell_mm), fill_fraction("cubic", (base + step_mm) / cell_mm)
    return (1 - t) * f0 + t * f1, (1 - t) * eps(base) + t * eps(base + step_mm)
