"""Bifocal mirror–lens beam former (seed-003 §3.4, errata §7.4)."""

from __future__ import annotations

from functools import partial

import numpy as np

from antenna_cad.raytrace.snell import refract
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import (BeamFormer, _assemble_symmetric, _monotone, _monotone_prefix,
                                                         trace_mirror_lens)
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS, _normal_from_slope, _slope_from_normal, _unit
from antenna_cad.synthesis.slot_array.curves import _rms


def _transfer_up(e_in: np.ndarray, slope: np.ndarray, ratio: float | np.ndarray) -> np.ndarray:
    """Wave crossing a mirror-edge coupling slot into the other layer, travelling back (+y).

    Tangential phase is conserved: e_out·τ = ratio·(e_in·τ) with ratio = n_in/n_out
    (seed-003 §3.4, (2.10)/(2.12)/(2.15)); the normal part is taken with +y sign.
    """
    nrm = _normal_from_slope(slope)                     # has +y component
    tau = np.stack([nrm[..., 1], -nrm[..., 0]], -1)
    et = ratio * np.sum(e_in * tau, -1)
    if np.any(np.abs(et) > 1.0):
        raise DesignError("beamformer", "no transmitted wave at the mirror (|n sin| > 1)")
    return et[..., None] * tau + np.sqrt(1.0 - et**2)[..., None] * nrm


def bifocal_mirror_lens(*, lens_a2: float, lens_vertex: float, x0: float, p1: float, p2: float,
                        f0: float, n: float, half_width: float = 0.5, margin: float = 0.05,
                        n_seg: int = 41, max_iter: int = 80, scale_mm: float = 1.0,
                        field_prefix: str = "beamformer") -> BeamFormer:
    """Bifocal mirror–lens, two-layer beam former (seed-003 §3.4, eqs. 2.8–2.18, errata §7.4).

    Normalised inputs: initial lens input surface y = lens_vertex + lens_a2·x² on |x| ≤ x0;
    on-axis focus F(0, f0); lens index n; p1 = distance F1 → lens point A(−x0); p2 = reference
    distance to the output front. Step 0 builds the initial mirror through O from F (plane wave
    along +y, L0 = 2f0 + d(n − 1)); F1 follows by back-refraction of the ray A → D (D = right end
    of the initial mirror) and the output direction δ from the tangential law at D. Then
    alternately: F1 rays through the newest lens segment give the next mirror segment (2.13–2.15);
    the reversed plane wave of F2 on the *previous* mirror segment gives the next lens segment
    (2.16–2.18, C sign corrected).
    """
    fp = field_prefix
    if n <= 1 or x0 <= 0 or f0 <= lens_vertex or p1 <= 0:
        raise DesignError(fp, f"need n > 1, x0 > 0, f0 > lens vertex, p1 > 0 "
                          f"(got n={n}, x0={x0}, f0={f0}, p1={p1})")
    F = np.array([0.0, f0])
    xl = np.linspace(-x0, x0, n_seg)
    lens0 = (xl, lens_vertex + lens_a2 * xl**2, 2 * lens_a2 * xl)
    L0 = 2 * f0 + lens_vertex * (n - 1)
    K = np.stack([lens0[0], lens0[1]], -1)
    e, ok = refract(_unit(K - F), _normal_from_slope(lens0[2]), 1.0, n)
    e = _unit(e)
    cosb = -e[:, 1]
    KH = (L0 + K[:, 1] - f0 - np.linalg.norm(K - F, axis=-1)) / (n + cosb)
    H = K + KH[:, None] * e
    mir0 = (H[:, 0], H[:, 1], _slope_from_normal(n * e - np.array([0.0, 1.0])))
    _monotone(mir0[0], "initial mirror", fp)
    A = K[0]
    D = H[-1]
    eAD = _unit(D - A)
    back, ok = refract(-eAD, _normal_from_slope(np.array(lens0[2][0])), n, 1.0)
    F1 = A + p1 * _unit(back)
    u1 = _transfer_up(eAD, np.array(mir0[2][-1]), n)
    delta = float(np.arctan2(u1[0], u1[1]))
    l0 = float(np.linalg.norm(D - A))
    R0 = p1 + n * l0 + p2 - float(u1 @ D)
    F2 = F1 * np.array([-1.0, 1.0])
    u2 = u1 * np.array([-1.0, 1.0])

    def step_mirror(seg):          # F1 rays through lens points -> new mirror points
        x, y, s = seg
        M = np.stack([x, y], -1)
        e, ok = refract(_unit(M - F1), _normal_from_slope(s), 1.0, n)
        if not ok.all():
            raise DesignError(fp, "total reflection at the lens surface")
        e = _unit(e)
        l = (R0 - np.linalg.norm(M - F1, axis=-1) - p2 + M @ u1) / (n - e @ u1)
        N = M + l[:, None] * e
        return N[:, 0], N[:, 1], _slope_from_normal(n * e - u1)

    def step_lens(seg):            # reversed plane wave of F2 on mirror points -> new lens points
        x, y, s = seg
        P = np.stack([x, y], -1)
        e = _transfer_up(np.broadcast_to(-u2, P.shape), s, 1.0 / n)
        DP = p2 - P @ u2
        S = R0 - DP
        w = F2 - P
        a = n * n - 1.0
        bq = np.sum(e * w, -1) - n * S
        cq = S**2 - np.sum(w * w, -1)
        disc = bq * bq - a * cq
        if np.any(disc < 0):
            raise DesignError(fp, "lens construction has no solution (negative discriminant)")
        roots = np.stack([(-bq - np.sqrt(disc)) / a, (-bq + np.sqrt(disc)) / a], -1)
        good = (roots > 0) & ((S[:, None] - n * roots) > 0)
        l = np.where(good[:, 0], roots[:, 0], roots[:, 1])
        if not good.any(axis=1).all():
            raise DesignError(fp, "lens construction: no positive path root")
        Q = P + l[:, None] * e
        air = _unit(Q - F2)
        return Q[:, 0], Q[:, 1], _slope_from_normal(air + n * e)

    lenses, mirrors = [lens0], [mir0]
    need = half_width + margin
    for _ in range(max_iter):
        if lenses[-1][0][-1] >= need and mirrors[-1][0][-1] >= need:
            break
        nm = _monotone_prefix(step_mirror(lenses[-1]))
        nl = _monotone_prefix(step_lens(mirrors[-1]))
        mirrors.append(nm)
        lenses.append(nl)
        if len(nm[0]) < n_seg or len(nl[0]) < n_seg:   # construction diverges (§3.4): stop
            if min(nm[0][-1], nl[0][-1]) < half_width:
                raise DesignError(fp, f"construction diverges at |x| = "
                                  f"{min(nm[0][-1], nl[0][-1]):.4g} before covering the "
                                  f"half-aperture {half_width:.4g}")
            break
    else:
        raise DesignError(fp, f"surfaces did not reach |x| = {need:.3g} in {max_iter} iterations")
    sc = scale_mm
    mir = _assemble_symmetric(mirrors, "mirror", "layer1-layer2", sc)
    lens = _assemble_symmetric(lenses, "lens", "layer1", sc)
    foci = np.array([F1, F2]) * sc
    dirs = np.array([u1, u2])
    Rsc, p2sc = R0 * sc, p2 * sc

    trace = partial(trace_mirror_lens, lens, mir, n)

    def eikonal(x_mm, j):
        x = np.asarray(x_mm, float)
        Q = np.stack([x, mir.y_at(x)], -1)
        return Rsc - p2sc + Q @ dirs[j]

    sig = []
    xs = np.linspace(-half_width, half_width, N_SIGMA_RAYS) * sc
    for j in range(2):
        Q, L, ok, _ = trace(foci[j], xs)
        if not ok.all():
            raise DesignError(fp, f"focus {j + 1}: {int((~ok).sum())} rays miss the mirror")
        sig.append(_rms(L + p2sc - Q @ dirs[j] - Rsc))
    sig = np.array(sig)
    # lens thickness over the aperture (lens above mirror)
    xa = np.linspace(-half_width, half_width, 201) * sc
    thick = lens.y_at(xa) - mir.y_at(xa)
    Rl = float(np.linalg.norm(F1)) * sc
    phi0 = np.arctan2(-F1[0], F1[1])
    lim = max(2 * abs(phi0), np.pi / 3)
    phi = np.linspace(-lim, lim, 121)
    locus = np.stack([Rl * np.sin(phi), Rl * np.cos(phi)], -1)
    params = {"delta_rad": delta, "F1": F1.copy(), "R0": float(R0), "L0": float(L0),
              "iterations": len(lenses) - 1, "beam_angle_rad": delta, "n": float(n),
              "min_lens_thickness_mm": float(thick.min()),
              "initial_mirror_half_width": float(mir0[0][-1])}
    return BeamFormer("bifocal_mirror_lens", (mir,), (lens,), foci, dirs, sig, sig / sc, sc,
                      mir, locus, np.zeros(2), eikonal, trace, params)
