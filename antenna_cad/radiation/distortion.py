"""The seed's pattern-distortion criterion: the antenna under test (AUT) in the collimator's field,
its sum and difference patterns and their integral errors (seed-000 §4.5, (1.19)–(1.24)).

    F(θ) = ∫ Ȧ(y) e^{jβ y sin θ} dy                                   (1.19)
    Δ_Σ = ∫ (F_A − F_0)² dθ / ∫ F_0² dθ,   θ ∈ [−90°, 90°]             (1.20)
    Δ_main over the reference main lobe, Δ_side the rest; Δ_Σ = Δ_main + Δ_side   (1.21)–(1.23)
    AUT taper A(y) = cos^k(π y / L)                                     (1.24)

The seed leaves the conventions open; we use the digest's (seed-000 §5.3 [OURS]): |F| normalised
to its own maximum (a shape error, not a gain error), θ over ±90°, the main lobe bounded by the
first nulls of F_0 (for the difference pattern: the nulls outside its two peaks), and odd
excitation sign(y) for the difference pattern. A 2-D AUT (circle or rectangle) is reduced to the
principal cut along y by integrating the excitation over x. The threshold is the same error for a
22.5° quadratic phase error across the AUT (Tables 1.6/1.7 recipe, computed, not copied: the
printed tables are about 1.4× ours and not regression targets, §7.4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from antenna_cad.radiation.aperture import Cut, matvec, trapezoid_weights

THETA_SAMPLES_PER_BEAMWIDTH = 32      # θ samples per λ/L: the main-lobe bound to ≈ 1 %
QUADRATIC_THRESHOLD_DEG = 22.5          # seed-000 §4.1: ΔΦ_m = π/8
FLANK_DB = 10.0                         # main-lobe bound of a difference flank without a null


@dataclass(frozen=True)
class Aut:
    """Antenna under test: a circle (``height_mm`` = its diameter, ``width_mm`` equal) or a
    ``width_mm`` × ``height_mm`` rectangle (x × y); the cut is in the y (vertical) plane."""
    width_mm: float
    height_mm: float
    circular: bool
    taper_k: int = 0

    def grid(self, wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
        """x and y sample points over the AUT, ≤ λ/8 apart."""
        def axis(size):
            n = 2 * int(4 * size / wavelength_mm) + 33
            return np.linspace(-size / 2, size / 2, n)
        return axis(self.width_mm), axis(self.height_mm)

    def excitation(self, x_mm: np.ndarray, y_mm: np.ndarray) -> np.ndarray:
        """Taper (1.24) on the grid [iy, ix], zero outside a circular AUT."""
        X, Y = np.meshgrid(x_mm, y_mm)
        if self.circular:
            rho = np.hypot(X, Y) / self.height_mm
            return np.where(rho <= 0.5 + 1e-12, np.cos(np.pi * np.minimum(rho, 0.5)) ** self.taper_k, 0.0)
        return (np.cos(np.pi * X / self.width_mm) * np.cos(np.pi * Y / self.height_mm)) ** self.taper_k


def aut_cuts(aut: Aut, x_mm: np.ndarray, y_mm: np.ndarray, field2d: np.ndarray,
             wavelength_mm: float) -> tuple[Cut, Cut]:
    """Sum and difference cuts (y plane) of the AUT receiving ``field2d[iy, ix]`` on its grid."""
    line = matvec(aut.excitation(x_mm, y_mm) * np.asarray(field2d, complex), trapezoid_weights(x_mm))
    c = line * trapezoid_weights(y_mm)
    return Cut(y_mm, c, wavelength_mm), Cut(y_mm, c * np.sign(y_mm), wavelength_mm)


@dataclass(frozen=True)
class IntegralErrors:
    total: float
    main: float
    side: float


def _main_lobe(o: np.ndarray, difference: bool) -> tuple[int, int]:
    """Indices bounding the reference main lobe: the first minima outside the peak(s). An odd
    excitation with a taper (k ≥ 2) steps at the centre and its flank decays without a null;
    there the bound is where it falls ``FLANK_DB`` below the peak."""
    n = len(o)
    c = n // 2
    if difference:
        left, right = int(np.argmax(o[:c])), c + int(np.argmax(o[c:]))
    else:
        left = right = int(np.argmax(o))
    return _walk(o, left, -1), _walk(o, right, 1)


def _walk(o: np.ndarray, i: int, step: int) -> int:
    """From ``i`` down the flank to the first minimum; without one, to the −FLANK_DB point."""
    j = i
    while 0 <= j + step < len(o) and o[j + step] <= o[j]:
        j += step
    if 0 < j < len(o) - 1:
        return j
    j = i
    while 0 <= j + step < len(o) and o[j + step] > 10 ** (-FLANK_DB / 20) * o[i]:
        j += step
    return j


class ErrorMeter:
    """Integral errors against one reference cut: the θ grid, its kernel and the reference's main
    lobe are computed once, so many actual cuts on the same samples are cheap."""

    def __init__(self, ideal: Cut, difference: bool = False):
        n = int(THETA_SAMPLES_PER_BEAMWIDTH * ideal.extent_mm / ideal.wavelength_mm) + 2001
        theta = np.linspace(-math.pi / 2, math.pi / 2, 2 * (n // 2) + 1)
        self.s_mm = ideal.s_mm
        self.kernel = np.exp(-1j * (2 * math.pi / ideal.wavelength_mm) * np.outer(np.sin(theta), ideal.s_mm))
        o = np.abs(matvec(self.kernel, ideal.c))
        self.o = o / o.max()
        self.w = trapezoid_weights(theta)
        self.ref = float(np.sum(self.o**2 * self.w))
        self.lo, self.hi = _main_lobe(self.o, difference)

    def __call__(self, actual: Cut) -> IntegralErrors:
        if actual.s_mm.shape != self.s_mm.shape or not np.allclose(actual.s_mm, self.s_mm):
            raise ValueError("actual and reference cuts must share their samples")
        a = np.abs(matvec(self.kernel, actual.c))
        err = (a / a.max() - self.o) ** 2 * self.w
        main = float(np.sum(err[self.lo:self.hi + 1])) / self.ref
        total = float(np.sum(err)) / self.ref
        return IntegralErrors(total, main, total - main)


def integral_errors(actual: Cut, ideal: Cut, difference: bool = False) -> IntegralErrors:
    """Δ_Σ, Δ_main, Δ_side of (1.20)–(1.23) between two cuts on the same samples (module
    docstring conventions)."""
    return ErrorMeter(ideal, difference)(actual)


def quadratic_phase(aut: Aut, x_mm: np.ndarray, y_mm: np.ndarray, edge_deg: float) -> np.ndarray:
    """e^{jφ}, φ = edge·(2ρ/L)² (circle) or edge·(2y/L)² (rectangle, the seed's 1-D error)."""
    X, Y = np.meshgrid(x_mm, y_mm)
    s = 2 * (np.hypot(X, Y) if aut.circular else np.abs(Y)) / aut.height_mm
    return np.exp(1j * math.radians(edge_deg) * s**2)


class AutMeter:
    """One AUT on its grid: excitation, plane-wave reference cuts and their error meters, so the
    AUT can be put in many fields cheaply."""

    def __init__(self, aut: Aut, wavelength_mm: float):
        self.aut, self.wavelength_mm = aut, wavelength_mm
        self.x, self.y = aut.grid(wavelength_mm)
        self.excitation = aut.excitation(self.x, self.y)
        self.ideal = aut_cuts(aut, self.x, self.y, np.ones_like(self.excitation), wavelength_mm)
        self.meters = (ErrorMeter(self.ideal[0]), ErrorMeter(self.ideal[1], difference=True))

    def errors(self, field2d: np.ndarray) -> tuple[IntegralErrors, IntegralErrors, tuple[Cut, Cut]]:
        """Sum and difference integral errors in ``field2d[iy, ix]`` on the AUT grid, and its cuts."""
        cuts = aut_cuts(self.aut, self.x, self.y, field2d, self.wavelength_mm)
        return self.meters[0](cuts[0]), self.meters[1](cuts[1]), cuts

    def thresholds(self, edge_deg: float = QUADRATIC_THRESHOLD_DEG) -> tuple[IntegralErrors, IntegralErrors]:
        """Errors of a ``edge_deg`` quadratic phase error over the AUT: the thresholds of Tables
        1.6/1.7 recomputed for this AUT."""
        return self.errors(quadratic_phase(self.aut, self.x, self.y, edge_deg))[:2]


def thresholds(aut: Aut, wavelength_mm: float,
               edge_deg: float = QUADRATIC_THRESHOLD_DEG) -> tuple[IntegralErrors, IntegralErrors]:
    """Sum and difference thresholds of :meth:`AutMeter.thresholds`."""
    return AutMeter(aut, wavelength_mm).thresholds(edge_deg)
