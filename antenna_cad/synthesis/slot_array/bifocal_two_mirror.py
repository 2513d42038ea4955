"""Bifocal two-mirror beam former (seed-003 §3.3): Kinber-type point-by-point construction, vector form."""

from __future__ import annotations

from functools import partial

import numpy as np

from antenna_cad.raytrace.snell import reflect
from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import (BeamFormer, _assemble_symmetric, _monotone, _remaining_to_point,
                                                         trace_two_mirror)
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS, _normal_from_slope, _slope_from_normal, _unit
from antenna_cad.synthesis.slot_array.curves import _rms


def bifocal_two_mirror(*, a0: float, a2: float, h1: float, b0: float, b2: float, h2: float,
                       rho1: float, rho2: float = np.inf, half_width: float = 0.5,
                       margin: float = 0.1, n_seg: int = 41, max_iter: int = 60,
                       scale_mm: float = 1.0, field_prefix: str = "beamformer") -> BeamFormer:
    """Bifocal two-mirror, three-layer beam former (seed-003 §3.3, eqs. 2.1–2.7).

    Normalised (D = 1) inputs: initial segments y1 = a0 + a2 x² (|x| ≤ h1, mirror 1, layers 1→2)
    and y2 = b0 + b2 x² (|x| ≤ h2, mirror 2, layers 2→3). Central ray F1 → A(−h1) → B(+h2) →
    F3 (or a plane front when ``rho2`` is inf); its direction is taken from the coordinates of
    A and B (erratum §7.3). F2, F4 are mirror images. Step A: F1 rays on the newest mirror-1
    segment build the next mirror-2 segment; step B: F4 rays on the newest mirror-2 segment build
    the next mirror-1 segment; the left halves follow by x → −x symmetry. Stops when both mirrors
    cover |x| ≤ half_width + margin. All outputs are multiplied by ``scale_mm``.
    """
    fp = field_prefix
    if h1 <= 0 or h2 <= 0 or rho1 <= 0 or rho2 <= 0:
        raise DesignError(fp, f"h1, h2, rho1, rho2 must be > 0 (got {h1}, {h2}, {rho1}, {rho2})")
    plane = not np.isfinite(rho2)
    xs1 = np.linspace(-h1, h1, n_seg)
    xs2 = np.linspace(-h2, h2, n_seg)
    seg1 = (xs1, a0 + a2 * xs1**2, 2 * a2 * xs1)
    seg2 = (xs2, b0 + b2 * xs2**2, 2 * b2 * xs2)
    A = np.array([-h1, a0 + a2 * h1**2])
    B = np.array([h2, b0 + b2 * h2**2])
    eAB = _unit(B - A)
    d_in = reflect(eAB, _normal_from_slope(np.array(-2 * a2 * h1)))
    F1 = A - rho1 * d_in
    e_out = reflect(eAB, _normal_from_slope(np.array(2 * b2 * h2)))
    AB = float(np.linalg.norm(B - A))
    F2 = F1 * np.array([-1.0, 1.0])
    if plane:
        u3 = e_out
        u4 = u3 * np.array([-1.0, 1.0])
        l0 = rho1 + AB - float(u3 @ B)
        F3 = F4 = None
    else:
        F3 = B + rho2 * e_out
        F4 = F3 * np.array([-1.0, 1.0])
        l0 = rho1 + AB + rho2

    def step_a(seg):               # F1 rays on mirror 1 -> new mirror-2 points
        x, y, s = seg
        P = np.stack([x, y], -1)
        r1 = np.linalg.norm(P - F1, axis=-1)
        e = reflect(_unit(P - F1), _normal_from_slope(s))
        if plane:
            t = (l0 - r1 + P @ u3) / (1.0 - e @ u3)
            Q = P + t[:, None] * e
            eo = np.broadcast_to(u3, Q.shape)
        else:
            t = _remaining_to_point(P, e, F3, l0 - r1)
            Q = P + t[:, None] * e
            eo = _unit(F3 - Q)
        return Q[:, 0], Q[:, 1], _slope_from_normal(e - eo)

    def step_b(seg):               # F4 rays (or the reversed plane wave u4) on mirror 2 -> mirror 1
        x, y, s = seg
        M = np.stack([x, y], -1)
        if plane:
            d = np.broadcast_to(-u4, M.shape)
            L = l0 + M @ u4
        else:
            d = _unit(M - F4)
            L = l0 - np.linalg.norm(M - F4, axis=-1)
        e = reflect(d, _normal_from_slope(s))
        t = _remaining_to_point(M, e, F2, L)
        N = M + t[:, None] * e
        return N[:, 0], N[:, 1], _slope_from_normal(e - _unit(F2 - N))

    m1, m2 = [seg1], [seg2]
    need = half_width + margin
    for _ in range(max_iter):
        if m1[-1][0][-1] >= need and m2[-1][0][-1] >= need:
            break
        n2, n1 = step_a(m1[-1]), step_b(m2[-1])
        _monotone(n1[0], "mirror 1", fp)
        _monotone(n2[0], "mirror 2", fp)
        m1.append(n1)
        m2.append(n2)
    else:
        raise DesignError(fp, f"mirrors did not reach |x| = {need:.3g} in {max_iter} iterations "
                          f"(reached {m1[-1][0][-1]:.4g}, {m2[-1][0][-1]:.4g})")

    # the initial segments hold both halves; later segments only x > 0 (mirror them)
    mir1 = _assemble_symmetric(m1, "mirror_1", "layer1-layer2", scale_mm)
    mir2 = _assemble_symmetric(m2, "mirror_2", "layer2-layer3", scale_mm)

    sc = scale_mm
    foci = np.array([F1, F2]) * sc
    if plane:
        dirs = np.array([u3, u4])
    else:
        dirs = np.array([_unit(F3 - np.array([0, b0])), _unit(F4 - np.array([0, b0]))])

    trace = partial(trace_two_mirror, mir1, mir2)

    def eikonal(x_mm, j):
        """Design path focus j → point Q on mirror 2: l0 + u_j·Q (plane output) or
        l0 − |Q F_out| (focal output, F_out = F3 for F1, F4 for F2)."""
        x = np.asarray(x_mm, float)
        Q = np.stack([x, mir2.y_at(x)], -1)
        if plane:
            return l0 * sc + Q @ dirs[j]
        return l0 * sc - np.linalg.norm(Q - (F3 if j == 0 else F4) * sc, axis=-1)

    sig = []
    xs = np.linspace(-half_width, half_width, N_SIGMA_RAYS) * sc
    for j in range(2):
        Q, L, ok, _ = trace(foci[j], xs)
        if plane:
            tot = L - Q @ dirs[j]
            ref = l0 * sc
        else:
            F_out = (F3 if j == 0 else F4) * sc
            tot = L + np.linalg.norm(F_out - Q, axis=-1)
            ref = l0 * sc
        if not ok.all():
            raise DesignError(fp, f"focus {j + 1}: {int((~ok).sum())} of {ok.size} rays miss "
                              "mirror 2; increase the construction margin")
        sig.append(_rms(tot - ref))
    sig = np.array(sig)
    R = float(np.linalg.norm(F1)) * sc
    phi0 = np.arctan2(F1[0], -F1[1])
    phi = np.linspace(-max(2 * abs(phi0), np.pi / 3), max(2 * abs(phi0), np.pi / 3), 121)
    locus = np.stack([R * np.sin(phi), -R * np.cos(phi)], -1)
    params = {"l0": float(l0), "F1": F1.copy(), "iterations": len(m1) - 1, "plane_output": plane,
              "beam_angle_rad": float(np.arctan2(dirs[0][0], dirs[0][1]))}
    if not plane:
        params["F3"] = F3.copy()
    return BeamFormer("bifocal_two_mirror", (mir1, mir2), (), foci, dirs, sig, sig / sc,
                      sc, mir2, locus, np.zeros(2), eikonal, trace, params)
