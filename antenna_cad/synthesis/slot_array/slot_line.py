"""Curved slot lines (seed-003 §3.5 generalised) and their phase coherence; rays traced to the guides."""

from __future__ import annotations

import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.curves import _rms


def slot_line_t_mm(bf: BeamFormer, x_mm, n_guide: float, cos_beta: float,
                   t0_mm: float) -> np.ndarray:
    """Distance t(x) along the guide from the guide entry (last mirror) to the slot-centre line.

    Coherence for both design foci j = 1, 2 (seed-003 §3.5, §3.6 convention-free form):
    Ψ_j = L_j(x) + n t − u_j·B = const, B = (x, y_Q(x) + t), u_j = (s_j, cos β), where L_j is
    the design eikonal from focus j to the guide entry Q(x) and n = γ/k (erratum §7.8). Adding
    the two equations (the x terms cancel for s_2 = −s_1) gives
    t = t0 + [L̄(0) − L̄(x) + cos β (y_Q(x) − y_Q(0))]/(n − cos β), L̄ = (L_1 + L_2)/2.
    For the ellipse L̄ = r0 and this is the corrected (3.7): t = t0 + y cos β/(n − cos β)
    (erratum §7.5); at broadside the line is the mirror shifted by t0 (R5).
    """
    x = np.asarray(x_mm, float)
    gc = bf.guide_curve
    lbar = lambda xx: np.mean([bf.eikonal(xx, j) for j in range(len(bf.foci_mm))], axis=0)
    num = (lbar(np.zeros(1))[0] - lbar(x)) + cos_beta * (gc.y_at(x) - float(gc.y_at(0.0)))
    return t0_mm + num / (n_guide - cos_beta)


def traced_rays(bf: BeamFormer, source, x_mm, iterations: int = 30) -> tuple[np.ndarray, tuple]:
    """Ray-traced path (mm) from a source to the guide entry point at x on the guide curve, and
    the ray vertices (hit points on each surface, the entry point last).

    ``source``: design-focus index (int) or a point (mm) in the feed layer. Independent of the
    construction: rays go through the interpolated curves with Snell / reflection; the launch
    point on the first surface is found by a vectorised secant search.
    """
    src = bf.foci_mm[source] if np.ndim(source) == 0 else np.asarray(source, float)
    x = np.asarray(x_mm, float)
    if bf.type == "single_mirror":
        _, L, _, vertices = bf.trace(src, x)
        return L, vertices
    tol = 1e-12 * bf.aperture_mm
    xh0 = x.copy()
    if bf.type.startswith("trifocal"):           # folded landing maps: start from a landing table
        first = (bf.lenses or bf.mirrors)[0]
        grid = np.linspace(*first.x_range_mm, 401)
        Qg, _, okg, _ = bf.trace(src, grid)
        k = np.argmin(np.where(okg[None, :], np.abs(Qg[None, :, 0] - x[:, None]), np.inf), axis=1)
        xh0 = grid[k]
    Q0 = bf.trace(src, xh0)[0]
    xh1 = xh0 - (Q0[:, 0] - x)
    for _ in range(iterations):
        Q1 = bf.trace(src, xh1)[0]
        f0, f1 = Q0[:, 0] - x, Q1[:, 0] - x
        if np.max(np.abs(f1)) < tol:
            break
        den = np.where(np.abs(f1 - f0) > 0, f1 - f0, 1.0)
        xh2 = np.where(np.abs(f1) < tol, xh1, xh1 - f1 * (xh1 - xh0) / den)
        xh0, Q0, xh1 = xh1, Q1, xh2
    Q, L, ok, vertices = bf.trace(src, xh1)
    if not ok.all() or np.max(np.abs(Q[:, 0] - x)) > 1e-9 * bf.aperture_mm:
        raise DesignError("beamformer", "could not trace rays from the source to every guide "
                          "entry (source outside the usable field of view?)")
    return L, vertices


def traced_eikonal_mm(bf: BeamFormer, source, x_mm) -> np.ndarray:
    """Ray-traced path (mm) from a source to the guide entry at x (:func:`traced_rays`)."""
    return traced_rays(bf, source, x_mm)[0]


def feed_phase_errors(bf: BeamFormer, sources_mm, x_mm, t_mm, n_guide: float, cos_beta: float,
                      wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Aberration of the slot-line phase for arbitrary feed positions (seed-003 §3.9, (3.41)).

    For each source: Ψ(x_i) = L(x_i) + (n − cos β) t_i − cos β y_Q(x_i) at the slot line of every
    guide; a linear fit a + s·x removes the constant and the beam tilt. Returns
    (RMS residual in wavelengths, beam azimuth sin φ = s) per source. At a design focus the
    residual is zero and s equals the design azimuth cosine.
    """
    x = np.asarray(x_mm, float)
    t = np.asarray(t_mm, float)
    yq = bf.guide_curve.y_at(x)
    A = np.column_stack([np.ones_like(x), x])
    rms, az = [], []
    for src in np.atleast_2d(np.asarray(sources_mm, float)):
        psi = traced_eikonal_mm(bf, src, x) + (n_guide - cos_beta) * t - cos_beta * yq
        coef, *_ = np.linalg.lstsq(A, psi, rcond=None)
        rms.append(_rms(psi - A @ coef) / wavelength_mm)
        az.append(coef[1])
    return np.array(rms), np.array(az)


def slot_phase_spread(bf: BeamFormer, x_mm, y_ref_mm, n_guide: float, cos_beta: float,
                      wavelength_mm: float) -> np.ndarray:
    """Peak-to-peak spread (in wavelengths) of the radiated −1st-harmonic phase per focus.

    ``x_mm``, ``y_ref_mm``: cell reference points (slot-line point + m·p) on each guide. The path
    is ray-traced to the guide entry, n·(y − y_Q) inside the guide, minus u_j·r toward the beam
    (seed-003 §8.3 "phase coherence at the slots"), wrapped modulo λ.
    """
    x = np.asarray(x_mm, float)
    y = np.asarray(y_ref_mm, float)
    ux, inv = np.unique(x, return_inverse=True)
    yq = bf.guide_curve.y_at(ux)[inv]
    out = []
    for j in range(len(bf.foci_mm)):
        L = traced_eikonal_mm(bf, j, ux)[inv]
        psi = L + n_guide * (y - yq) - bf.beam_dirs[j][0] * x - cos_beta * y
        ph = 2 * np.pi * psi / wavelength_mm
        mean = np.angle(np.mean(np.exp(1j * ph)))
        dev = np.angle(np.exp(1j * (ph - mean)))
        out.append((dev.max() - dev.min()) / (2 * np.pi))
    return np.array(out)
