"""Patterns of the kinds whose aperture field comes as plain arrays: the aplanatic
mirror-lens (seed-004), the polyfocal constrained lens (seed-001 §1–§2) and the graded-index lens
(seed-001 §3.2), per lens variant at the nominal and the field-edge feed. The radiation model is
:mod:`antenna_cad.radiation.aperture` through :func:`antenna_cad.asbuilt.patterns.cut_aperture`.

Each kind gives the GO field on its exit face with phase −k·(optical path) (isotropic feed: no
spillover). The mirror-lens field is the scan-plane cut with the beam tilt removed: a body of
revolution E(r) on axis (Hankel transform), else E(x) taken constant across the disc. The 2-D
lenses (polyfocal between plates, graded between plates) are line apertures of the plate spacing's
height; a 3-D polyfocal lens is its grid of exit ports (one pitch² each), both principal cuts.
The polyfocal and graded lenses image feeds onto points at a finite distance; their pattern is
the one of the exit field referred to its image — the path to the image point (the kind's, or
the best-focus point minimising the path spread, σ of seed-001 (3.10)) added and the aperture
projected across the chief ray — which is the far field of the equivalent collimating lens and,
in u = offset / distance, the spread of the focal spot (Fresnel focusing). A plane-wave output is
referred to its direction. Efficiency: η_taper·η_phase relative to the lens's geometric aperture
(the mirror-lens amplitude already carries the dielectric loss, so η_taper does too).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from antenna_cad.asbuilt.patterns import PLOT_BEAMWIDTHS, cut_aperture, resampled
from antenna_cad.radiation.aperture import ApertureField, PatternFigures, pattern_figures, points_aperture
from antenna_cad.verification import Plot, Series, Table, Verification, cell, finite_figures


@dataclass(frozen=True)
class Case:
    """One (lens, feed) aperture: its radiation model and a label of how it was referred."""
    lens: str
    feed: str
    aperture: ApertureField
    note: str = ""
    cuts: tuple[str, ...] = ("y",)


def line_case(lens: str, feed: str, t_mm, amplitude, path_mm, wavelength_mm: float, half_mm: float,
              height_mm: float | None = None, on_axis: bool = False, note: str = "") -> Case:
    """A cut with field amplitude·e^{+jk·path} at ``t_mm`` (any order): a body of revolution
    (``on_axis``), a disc of radius ``half_mm`` or, with ``height_mm``, a strip 2·half × height."""
    o = np.argsort(t_mm)
    t = np.asarray(t_mm, float)[o]
    grid, e = resampled(t, np.asarray(amplitude, float)[o], 2 * np.pi / wavelength_mm * np.asarray(path_mm)[o],
                        max(half_mm, float(np.max(np.abs(t)))), wavelength_mm)
    return Case(lens, feed, cut_aperture(grid, e, wavelength_mm, half_mm, on_axis, height_mm), note)


def referred(points_mm: np.ndarray, path_mm: np.ndarray, target, is_point: bool):
    """Paths to ``target`` (an image point, or a plane wave along the direction ``target``) and the
    unit chief direction from the ports' centroid."""
    c = points_mm.mean(axis=0)
    if is_point:
        d = (target - c) / np.linalg.norm(target - c)
        return path_mm + np.linalg.norm(points_mm - target, axis=1), d
    d = np.asarray(target, float) / np.linalg.norm(target)
    return path_mm - (points_mm - c) @ d, d


def best_focus(points_mm: np.ndarray, path_mm: np.ndarray, guess) -> np.ndarray:
    """The image point minimising the spread of the total path (σ, seed-001 (3.10))."""
    spread = lambda p: float(np.std(path_mm + np.linalg.norm(points_mm - p, axis=1)))     # noqa: E731
    scale = float(np.ptp(points_mm[:, -1]) + np.ptp(points_mm[:, 0]))
    res = minimize(spread, np.asarray(guess, float), method="Nelder-Mead",
                   options={"xatol": 1e-9 * scale, "fatol": 1e-12 * scale, "maxiter": 4000})
    return res.x


def ports_case(lens: str, feed: str, points_mm: np.ndarray, amplitude, path_mm: np.ndarray, d: np.ndarray,
               cell_mm2: float, wavelength_mm: float, note: str = "") -> Case:
    """A 3-D port grid projected on the plane across the chief direction ``d`` (one cell each)."""
    a = np.cross([0.0, 1.0, 0.0], d)
    a /= np.linalg.norm(a)
    b = np.cross(d, a)
    e = np.asarray(amplitude) * np.exp(1j * 2 * np.pi / wavelength_mm * path_mm)
    return Case(lens, feed, points_aperture(points_mm @ a, points_mm @ b, e, cell_mm2, wavelength_mm), note,
                ("y", "x"))


def chief_note(d: np.ndarray, is_point: bool) -> str:
    """Where a lens's exit field is referred to: the chief direction's angle from the axis (last component)."""
    angle = float(np.degrees(np.arctan2(np.linalg.norm(d[:-1]), d[-1])))
    return f"{'image point' if is_point else 'plane wave'} {angle:.2f}° off axis"


def transverse(points: np.ndarray, d: np.ndarray) -> np.ndarray:
    """2-D points (axial, transverse) measured across the unit direction ``d`` from their centroid."""
    p = points - points.mean(axis=0)
    return p[:, 1] * d[0] - p[:, 0] * d[1]



def array_patterns(cases: list[Case], caption: str) -> Verification:
    """Figures ``pattern_<lens>_<feed>_*``, one plot per feed (lenses overlaid, the first drawn
    solid) and a table; a 3-D aperture adds its second principal cut (``_x`` figures)."""
    figures, rows, plots = {}, [], []
    feeds = list(dict.fromkeys(c.feed for c in cases))
    for feed in feeds:
        series = []
        for case in (c for c in cases if c.feed == feed):
            ap, key = case.aperture, f"pattern_{case.lens}_{case.feed}"
            for along in case.cuts:
                pf: PatternFigures = pattern_figures(ap, along)
                eff = pf.efficiency
                if along == "y":            # the scan plane: directivity and efficiency at its peak
                    figures |= {f"{key}_directivity_dbi": pf.directivity_dbi, f"{key}_hpbw_deg": pf.beam.hpbw_deg,
                                f"{key}_sll_db": pf.beam.sll_db, f"{key}_efficiency": eff.total,
                                f"{key}_efficiency_taper": eff.taper, f"{key}_efficiency_phase": eff.phase}
                    rows.append((case.lens, feed, cell(pf.directivity_dbi), cell(pf.beam.hpbw_deg, 4),
                                 cell(pf.beam.sll_db, 2), cell(eff.taper, 4), cell(eff.phase, 4), cell(eff.total, 4),
                                 case.note))
                else:
                    figures |= {f"{key}_hpbw_x_deg": pf.beam.hpbw_deg, f"{key}_sll_x_db": pf.beam.sll_db}
                    rows.append((case.lens, f"{feed} (x cut)", None, cell(pf.beam.hpbw_deg, 4), cell(pf.beam.sll_db, 2),
                                 None, None, None, case.note))
                cut = ap.cut(along)
                span = np.degrees(PLOT_BEAMWIDTHS * ap.wavelength_mm / cut.extent_mm)
                th = pf.beam.theta_deg + np.linspace(-span, span, 801)
                series.append(Series(f"{case.lens}{'' if along == 'y' else ', x cut'}", th, cut.db(th, pf.beam.peak),
                                     "line" if not series else "dashed"))
        plots.append(Plot(f"pattern-{feed.replace('_', '-')}", f"Far-field pattern, feed {feed.replace('_', ' ')}",
                          "θ from the beam (deg)", "relative power (dB)", tuple(series),
                          caption=caption + "; each lens to its own peak"))
    table = Table("patterns", "Far-field patterns per lens and feed",
                  ("lens", "feed", "directivity dBi", "HPBW deg", "first sidelobe dB", "η taper", "η phase",
                   "efficiency", "referred to"), tuple(rows),
                  caption=caption + "; D = (4πS/λ²)·η_taper·η_phase, efficiency = η_taper·η_phase (S: the lens's "
                                    "geometric aperture)")
    return Verification(finite_figures(figures), (), (table,), tuple(plots))


def path_mm(phase_rad, wavelength_mm: float) -> np.ndarray:
    """The optical path of a phase −k·path (the kinds' convention)."""
    return -np.asarray(phase_rad, float) * wavelength_mm / (2 * np.pi)


def imaged_case(lens: str, feed: str, points_mm: np.ndarray, amplitude, phase_rad, target, is_point: bool,
                wavelength_mm: float, half_mm: float, height_mm: float) -> Case:
    """A 2-D lens's exit field (points (axial, transverse) mm) referred to its image point or
    output direction ``target`` (module docstring), as a strip of ``height_mm``."""
    total, d = referred(points_mm, path_mm(phase_rad, wavelength_mm), np.asarray(target, float), is_point)
    return line_case(lens, feed, transverse(points_mm, d), amplitude, total, wavelength_mm, half_mm, height_mm,
                     note=chief_note(d[::-1], is_point))
