"""Trifocal two-mirror beam former (seed-003 §3.6, §3.8): mirror 1, mirror 2 (the guide entries) and the
slot line t(x), built by the march of :mod:`antenna_cad.synthesis.slot_array.trifocal`.

Frame: the thesis's (x, z) is this package's (x, y) (the guides run +y from mirror 2, the wave
reversing at each coupling slot). Initial data (§3.6): foci F1 = (x1, z1) (x1 < 0), F = (0, z_F),
F2 = (−x1, z1); mirror 1 on C D is z = b0 + b2 x² through C = (x_C, z_C) and D = (−x_C, z_C) with the
slope at C that reflects the F1 ray into the direction β_C below +x (γ_C = (90° − α_C − β_C)/2); B is
where that ray meets the F ray reflected at D; mirror 2 on A B is z = a0 + a2 x² through B. The
beams point at ±α, α = arctg(x_F1/(z_F1 − z_O1)), O1 = (0, b0) the mirror-1 vertex.

Where the seed is silent or inconsistent: β_C is not given (erratum §7.6); the three eikonals
fix the mirror-2 slope at B (n₂(e_1 − e_F)·(1, z′) = s_1), so a2 (and the vertex O2 = (0, a0)) follows
from that C¹ condition instead of being given — with the thesis's z_O2 = −1.02 and x_C = −0.08 the
condition gives β_C = 69.97° and a2 = 14.1, where no F2 ray can meet mirror 2 (the march stops at
x = 0.04 D). The march stalls near x = 0.40 D of mirror 2 for every β_C, x_C tried, so the former
is built for a half-aperture ``half_width`` ≤ 0.35 D: D (``scale_mm``) is larger than the guide array.
"""

from __future__ import annotations

import math
import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array import trifocal as tr
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS


def initial_segments(f1, f_z: float, c, beta_c: float, field: str):
    """Initial data of §3.6 (normalised): (Foci, mirror-1 b0, b2, mirror-2 a0, a2, B)."""
    F1, F, C = (float(f1[0]), float(f1[1])), (0.0, float(f_z)), (float(c[0]), float(c[1]))
    if not (F1[0] < 0 and C[0] < 0 and C[1] > max(F1[1], F[1])):
        raise DesignError(field, f"need x_F1 < 0, x_C < 0 and C above the foci (got F1 {F1}, C {C})")
    e_out = (math.cos(beta_c), -math.sin(beta_c))
    b2 = tr._slope_between(*tr._unit2(C[0] - F1[0], C[1] - F1[1]), *e_out, 1.0) / (2 * C[0])
    b0 = C[1] - b2 * C[0] ** 2
    D = (-C[0], C[1])
    eD = tr._unit2(*tr._redirect(*tr._unit2(D[0] - F[0], D[1] - F[1]), 2 * b2 * D[0], 1.0))
    a, b = tr._meet(*C, *e_out, *D, *eD)
    if not (a > 0 and b > 0):
        raise DesignError(field + ".beta_c_deg", f"the F1 ray from C and the F ray from D do not meet below "
                          f"mirror 1 (β_C = {math.degrees(beta_c):.4g}°)")
    B = (C[0] + a * e_out[0], C[1] + a * e_out[1])
    if B[0] <= 0:
        raise DesignError(field + ".beta_c_deg", f"B lies at x = {B[0]:.4g} D ≤ 0: the rays cross before "
                          "mirror 2 (β_C too large)")
    s1 = math.sin(math.atan(F1[0] / (F1[1] - b0)))
    slope_b = (s1 - (e_out[0] - eD[0])) / (e_out[1] - eD[1])       # C¹ at B (module docstring)
    a2 = slope_b / (2 * B[0])
    a0 = B[1] - a2 * B[0] ** 2
    fo = tr.Foci(F1, F, s1, 1.0, math.dist(C, F1) + a - s1 * B[0], math.dist(D, F) + b)
    return fo, b0, b2, a0, a2, B


def trifocal_two_mirror(*, f1, f_z: float, c, beta_c: float, half_width: float = 0.35, margin: float = 0.03,
                        n_seg: int = 81, max_steps: int = 30, scale_mm: float = 1.0,
                        field_prefix: str = "beamformer") -> BeamFormer:
    """Trifocal two-mirror former, normalised inputs (module docstring), outputs scaled to mm.

    ``eikonal(x_mm, j)`` is the design path from focus j (0: F1, 1: F, 2: F2) to mirror 2 at x:
    c_j + s_j x − T(x); ``params['T_curve']`` holds T(x) = n_w t(x) (mm) for the slot line.
    """
    fp = field_prefix
    fo, b0, b2, a0, a2, B = initial_segments(f1, f_z, c, beta_c, fp)
    xc = float(c[0])
    S0 = tr.Segment(lambda x: [x, b0 + b2 * x * x, 2 * b2 * x], xc, -xc)
    surf, G = tr.construct(fo, S0, a0, a2, B[0], half_width=half_width, margin=margin, max_steps=max_steps,
                           field=fp + ".beta_c_deg")
    xs0 = np.linspace(xc, -xc, n_seg)
    params = {"beta_c_rad": float(beta_c), "b0": b0, "b2": b2, "a0": a0, "a2": a2, "B": np.array(B)}
    return tr.assemble_former("trifocal_two_mirror", fo, surf, G, (xs0, b0 + b2 * xs0**2, 2 * b2 * xs0), (a0, a2),
                              half_width=half_width, n_seg=n_seg, scale_mm=scale_mm, params=params)


def optimise_beta_c(*, f1, f_z: float, c, half_width: float, bounds_deg: tuple[float, float] = (55.0, 70.0),
                    field_prefix: str = "beamformer") -> tuple[float, float]:
    """β_C (rad) minimising σ over the field of view (seed-003 §3.8), the parameter the seed leaves out.

    Objective: the larger σ of a source half-way between F and F1 and one 45 % beyond F1 (each moved
    radially to its best distance; :func:`antenna_cad.synthesis.slot_array.fov.sigma_at`); β_C for
    which the march cannot cover ``half_width`` score 1. Bounded scalar search (scipy). Returns
    (β_C, objective).
    """
    from scipy.optimize import minimize_scalar

    from antenna_cad.synthesis.slot_array.fov import sigma_at

    x = np.linspace(-half_width, half_width, N_SIGMA_RAYS)

    def objective(beta_deg: float) -> float:
        try:
            bf = trifocal_two_mirror(f1=f1, f_z=f_z, c=c, beta_c=math.radians(beta_deg), half_width=half_width + 0.005,
                                     margin=0.02, n_seg=21, field_prefix=field_prefix)
        except DesignError:
            return 1.0
        cen, F = bf.focal_locus_centre_mm, bf.foci_mm[0]
        up = 1.0 if F[1] > cen[1] else -1.0
        R0, psi0 = float(np.linalg.norm(F - cen)), math.atan2(F[0] - cen[0], up * (F[1] - cen[1]))
        worst = 0.0
        for frac in (0.5, 1.45):
            pos = lambda R: cen + np.array([R * math.sin(frac * psi0), up * R * math.cos(frac * psi0)])
            res = minimize_scalar(lambda R: np.nan_to_num(sigma_at(bf, pos(R), x)[0], nan=1.0),
                                  bounds=(0.6 * R0, 1.4 * R0), method="bounded", options={"xatol": 1e-5 * R0})
            worst = max(worst, float(res.fun))
        return worst

    fail = DesignError(field_prefix + ".beta_c_deg", f"no β_C in {bounds_deg[0]:g}–{bounds_deg[1]:g}° lets the "
                       f"march cover |x| ≤ {half_width:.3g} D: change c or the foci")
    best = tr.grid_then_bounded(objective, np.linspace(*bounds_deg, 31), 1e-3, fail)
    return math.radians(best[0]), best[1]
