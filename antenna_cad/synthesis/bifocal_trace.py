"""Verification of a synthesized bifocal lens (seed-000 §4.2, §5.9): exact 2-D trace through its
faces, the aperture phase, the design-focus eikonal and the defocus (scan-range) study against the
single-surface lens. Frame and units: :mod:`antenna_cad.synthesis.bifocal`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from antenna_cad.raytrace.collimator import single_surface_p2p_deg, usable_half_range_mm, usable_interval_mm
from antenna_cad.raytrace.trace2d import Trace2D, aim_at_face, trace
from antenna_cad.synthesis import collimator

if TYPE_CHECKING:
    from antenna_cad.synthesis.bifocal import BifocalDesign

C0_MM_PER_NS = 299.792458          # speed of light, mm/ns → λ0[mm] = C0_MM_PER_NS / f[GHz]



def _aim(design: BifocalDesign, feed: np.ndarray, n_rays: int, margin: float = 0.999) -> np.ndarray:
    return aim_at_face(design.interfaces()[0], feed, margin * design.edge_y_mm, n_rays)


def trace_bifocal(design: BifocalDesign, feed_y_mm: float, feed_z_mm: float = 0.0, n_rays: int = 201,
                  surfaces: Literal["spline", "polynomial"] = "spline",
                  z_plane_mm: float | None = None) -> Trace2D:
    """Exact 2-D trace from a feed at (feed_z_mm, feed_y_mm) through both faces to the AUT plane
    ``z = c`` (or ``z_plane_mm``). Rays are aimed at the illuminated face uniformly in y over the
    aperture; rays leaving the aperture (|y| > Y_B on either face) are flagged not ok."""
    feed = np.array([feed_z_mm, feed_y_mm], float)
    d = _aim(design, feed, n_rays)
    zt = design.antenna_x_mm if z_plane_mm is None else z_plane_mm
    tr = trace(np.tile(feed, (n_rays, 1)), d, design.interfaces(surfaces), 1.0, zt)
    ok = tr.ok & (np.abs(tr.points[1][:, 1]) <= design.edge_y_mm) & (np.abs(tr.points[2][:, 1]) <= design.edge_y_mm)
    return Trace2D(tr.points, tr.directions, tr.opl, ok)


def _design_focus_eikonal(design: BifocalDesign, k: int, n_rays: int = 401) -> np.ndarray:
    """Eikonal |O_k P| + n|PQ| − u_k·Q of rays from design focus k (c-free form of (3.16)); for a
    point-image lens |O_k P| + n|PQ| + |Q O_k'| (seed-001 §3.1)."""
    F = design.foci_mm[k]
    tr = trace(np.tile(F, (n_rays, 1)), _aim(design, F, n_rays, 0.995), design.interfaces("spline"), 1.0)
    yb = design.edge_y_mm
    ok = tr.ok & (np.abs(tr.points[1][:, 1]) <= yb) & (np.abs(tr.points[2][:, 1]) <= yb)   # inside the rim
    if ok.sum() < n_rays // 2:           # most rays lost: no spread to measure (NaN fails the check)
        return np.array([np.nan])
    Q = tr.points[-1][ok]
    if design.image_points_mm is not None:
        return tr.opl[ok] + np.linalg.norm(Q - design.image_points_mm[k], axis=-1)
    return tr.opl[ok] - Q @ design.exit_directions[k]


def aperture_phase(tr: Trace2D, wavelength_mm: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Phase on the target plane (seed-000 §4.2 with vector Snell): returns (y on the plane, phase
    error in degrees with the least-squares linear ramp removed, peak-to-peak in degrees)."""
    y = tr.points[-1][tr.ok, 1]
    ph = 360.0 * tr.opl[tr.ok] / wavelength_mm
    lin = np.polyval(np.polyfit(y, ph, 1), y)
    err = ph - lin
    return y, err, float(np.ptp(err))


@dataclass(frozen=True)
class DefocusStudy:
    """Aperture phase error (peak-to-peak, linear fit removed) vs feed displacement along the focal
    line, for the bifocal lens (feed plane z = 0) and a single-surface hyperbolic lens of the same
    aperture 2·Y_B and focal distance X_B (feed line z = −f), both at ``wavelength_mm``."""

    feed_y_mm: np.ndarray
    p2p_deg: np.ndarray
    single_p2p_deg: np.ndarray
    budget_deg: float
    usable_half_range_mm: float          # bifocal: outer end of the band around the focus a with p2p ≤ budget
    single_usable_half_range_mm: float
    usable_half_angle_deg: float         # atan(range / X_B)
    single_usable_half_angle_deg: float
    single_thickness_mm: float
    wavelength_mm: float
    usable_inner_mm: float = 0.0         # inner end of that band: 0 when it runs through the axis

def defocus_study(design: BifocalDesign, budget_deg: float = 22.5, frequency_ghz: float = 10.0,
                  feed_y_mm: np.ndarray | None = None, n_rays: int = 201,
                  surfaces: Literal["spline", "polynomial"] = "spline") -> DefocusStudy:
    """Seed-000 §5.9 study by exact trace: p2p phase vs feed y on the line z = 0, the usable scan band
    around the design focus at ``budget_deg`` (default ΔΦ_m = π/8 = 22.5°; it runs through the axis
    for the seed's lenses, not for fast ones such as seed-001's), and the same for the single-surface lens
    (seed-000 §2.1, §5.5) with f = X_B, D = 2Y_B and the same lens-to-AUT gap."""
    lam = C0_MM_PER_NS / frequency_ghz
    if feed_y_mm is None:
        feed_y_mm = np.linspace(0.0, 6.0 * design.focus_offset_mm, 49)
    feed_y_mm = np.asarray(feed_y_mm, float)
    bif = lambda y: aperture_phase(trace_bifocal(design, y, n_rays=n_rays, surfaces=surfaces), lam)[2]  # noqa: E731
    f, D = design.edge_x_mm, 2 * design.edge_y_mm
    gap = design.antenna_x_mm - design.rho2_mm
    sgl = lambda y: single_surface_p2p_deg(f, D, design.eps_r, y, gap, lam, n_rays)  # noqa: E731
    pb, inner, rb = usable_interval_mm(bif, feed_y_mm, budget_deg, design.focus_offset_mm)
    ps, rs = usable_half_range_mm(sgl, feed_y_mm, budget_deg)
    d = collimator.thickness_mm(D, f, float(np.sqrt(design.eps_r)))
    return DefocusStudy(feed_y_mm, pb, ps, float(budget_deg), rb, rs,
                        float(np.degrees(np.arctan2(rb, f))), float(np.degrees(np.arctan2(rs, f))), d, lam,
                        inner)
