"""Trifocal mirror–lens beam former (seed-003 §2.5, §3.7, §3.8): the dielectric lens's input surface, the
mirror (the guide entries) and the slot line t(x), built by the march of
:mod:`antenna_cad.synthesis.slot_array.trifocal` with refraction into the lens (n₂ = n).

Thesis frame (x, z) (§3.7): foci F1 = (x1, z1) (x1 < 0), F = (0, z_F), F2 = (−x1, z1) at z < 0; the lens
input surface z = a2 x² (vertex at the origin) through A = (x_A, z_A) and C = (−x_A, z_A), with
a2 = tg γ_A/(2 x_A); B is where the F1 ray refracted at A meets the F ray refracted at C; the mirror
z = b0 + b2 x² runs through B with its vertex O1 = (0, b0). The rays cross the lens (index n) from the
input surface to the mirror; there the wave passes the coupling slot into the guides, which run back
(−z). This package's frame has the guides along +y, so the results are mapped y = −z (foci above the
lens, the mirror below, as for the bifocal mirror–lens of §3.4).

Where the seed is silent or inconsistent (measured, see the tests): O1 and n are not given (erratum
§7.7). The three eikonals fix the mirror slope at B (n (e_1 − e_F)·(1, z′) = sin α), so O1 and the beam
angle α are one parameter: this former takes O1 and derives α. The thesis's α = arctg(x_F1/z_F1) = 29.1°
(with its x_A, γ_A and n = √2.2) would need a steep mirror (b2 = −15.4), on which no F2 ray satisfies its
eikonal: the march stops at x = 0.05 D. With its F1, F, x_A, γ_A the march covers |x| ≥ 0.525 D with
smooth segments only for z_O1 ≈ 1.03–1.07 about z_B = 1.040 (a nearly flat initial mirror; α ≈ 13.9–15.0°;
steps of 0.01 D: at 1.01–1.02 and 1.08–1.10 it still covers the aperture, through near-folds).
"""

from __future__ import annotations

import math

import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array import trifocal as tr
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer

# recipes/ka-slot-array-trifocal-mirror-lens.yaml (normalised): the thesis's §3.8 foci, x_A and γ_A, n = √2.2
# (the lens of the guide filling, as in §2.3), z_O1 from :func:`optimise_o1`
KA_RECIPE = dict(f1=(-0.25, -0.45), f_z=-0.5, x_a=-0.09, gamma_a=-0.09, n=math.sqrt(2.2), o1_z=1.0355)
SMOOTH_TOL = 1e-8       # D: largest mid-node error of a frozen march segment the O1 search accepts


def _refracted(P, F, slope: float, n: float) -> tuple[float, float]:
    return tr._unit2(*tr._redirect(*tr._unit2(P[0] - F[0], P[1] - F[1]), slope, n))


def initial_point_b(f1, f_z: float, x_a: float, gamma_a: float, n: float, field: str):
    """A, C, the refracted F1 ray at A and F ray at C, their meeting point B and the lens a2 (§3.7)."""
    F1, F = (float(f1[0]), float(f1[1])), (0.0, float(f_z))
    if not (F1[0] < 0 and F1[1] < 0 and F[1] < 0 and x_a < 0 and n > 1):
        raise DesignError(field, f"need x_F1 < 0, z_F1 < 0, z_F < 0, x_A < 0 and n > 1 (got F1 {F1}, "
                          f"z_F {F[1]}, x_A {x_a}, n {n})")
    a2 = math.tan(gamma_a) / (2 * x_a)
    A, C = (x_a, a2 * x_a * x_a), (-x_a, a2 * x_a * x_a)
    e1, eF = _refracted(A, F1, 2 * a2 * x_a, n), _refracted(C, F, -2 * a2 * x_a, n)
    a, b = tr._meet(*A, *e1, *C, *eF)
    B = (A[0] + a * e1[0], A[1] + a * e1[1])
    if not (a > 0 and b > 0 and B[0] > 0):
        raise DesignError(field + ".gamma_a_rad", "the F1 ray refracted at A and the F ray refracted at C do "
                          f"not meet inside the lens at x > 0 (x_A = {x_a:g}, γ_A = {gamma_a:g} rad)")
    return F1, F, a2, A, C, e1, eF, a, b, B


def initial_segments(f1, f_z: float, x_a: float, gamma_a: float, n: float, o1_z: float, field: str):
    """Initial data of §3.7 (normalised, thesis frame): (Foci, lens a2, mirror b0, b2, B); sin α from
    the C¹ condition at B on the mirror parabola through B with vertex z = ``o1_z``."""
    F1, F, a2, A, C, e1, eF, a, b, B = initial_point_b(f1, f_z, x_a, gamma_a, n, field)
    b0 = float(o1_z)
    b2 = (B[1] - b0) / B[0] ** 2
    s1 = n * ((e1[0] - eF[0]) + (e1[1] - eF[1]) * 2 * b2 * B[0])
    if not 0 < s1 < 1:
        raise DesignError(field + ".o1", f"the mirror vertex z_O1 = {b0:.4g} D gives sin α = {s1:.4g} at B "
                          f"(C¹ condition): no beam pair; move O1 toward z_B = {B[1]:.4g} D")
    fo = tr.Foci(F1, F, s1, n, math.dist(A, F1) + n * a - s1 * B[0], math.dist(C, F) + n * b)
    return fo, a2, b0, b2, B


def trifocal_mirror_lens(*, f1, f_z: float, x_a: float, gamma_a: float, n: float, o1_z: float,
                         half_width: float = 0.5, margin: float = 0.03, n_seg: int = 81, max_steps: int = 30,
                         scale_mm: float = 1.0, field_prefix: str = "beamformer") -> BeamFormer:
    """Trifocal mirror–lens former, normalised inputs (module docstring; γ_A in radians), outputs in mm in
    this package's frame (y = −z). ``params``: a2, b0 (= z_O1), b2, B (thesis frame), α, n, the minimum
    lens thickness over the aperture, the march record."""
    fp = field_prefix
    fo, a2, b0, b2, B = initial_segments(f1, f_z, x_a, gamma_a, n, o1_z, fp)
    S0 = tr.Segment(lambda x: [x, a2 * x * x, 2 * a2 * x], x_a, -x_a)
    surf, G = tr.construct(fo, S0, b0, b2, B[0], half_width=half_width, margin=margin, max_steps=max_steps,
                           field=fp + ".o1")
    xs0 = np.linspace(x_a, -x_a, n_seg)
    bf = tr.assemble_former("trifocal_mirror_lens", fo, surf, G, (xs0, a2 * xs0**2, 2 * a2 * xs0), (b0, b2),
                            half_width=half_width, n_seg=n_seg, scale_mm=scale_mm, flip=True,
                            params={"a2": a2, "b0": b0, "b2": b2, "B": np.array(B), "n": float(n)})
    lens, mirror = bf.lenses[0], bf.mirrors[0]
    xa = np.linspace(-half_width, half_width, 201) * scale_mm
    bf.params["min_lens_thickness_mm"] = float(np.min(lens.y_at(xa) - mirror.y_at(xa)))
    return bf


def optimise_o1(*, f1, f_z: float, x_a: float, gamma_a: float, n: float, half_width: float,
                window: tuple[float, float] = (-0.08, 0.08), field_prefix: str = "beamformer") -> tuple[float, float]:
    """z_O1 (normalised) minimising σ over the 80° field of view (seed-003 §3.8), the parameter the seed
    leaves out: a 17-point scan of z_B + ``window`` (the march covers the aperture only near a flat
    initial mirror), then a bounded scalar search about the best. Objective: σ(80°) of
    :func:`antenna_cad.synthesis.slot_array.fov.field_curve` on 5 field angles (1 where the march does not
    cover ``half_width``, a frozen segment misses its map by more than ``SMOOTH_TOL`` — a near-fold, where
    the eikonals would no longer hold to 1e-9 D — or the rays miss before 40°). Returns (z_O1, objective)."""

    from antenna_cad.synthesis.slot_array.fov import field_curve

    z_b = initial_point_b(f1, f_z, x_a, gamma_a, n, field_prefix)[-1][1]

    def objective(z: float) -> float:
        try:
            bf = trifocal_mirror_lens(f1=f1, f_z=f_z, x_a=x_a, gamma_a=gamma_a, n=n, o1_z=z,
                                      half_width=half_width + 0.005, margin=0.02, n_seg=21, field_prefix=field_prefix)
        except DesignError:
            return 1.0
        if bf.params["interp_error"] > SMOOTH_TOL:               # a map of the march not smooth: not exact
            return 1.0
        value = field_curve(bf, half_width, n_angles=5).sigma_fov()
        return value if np.isfinite(value) else 1.0

    fail = DesignError(field_prefix + ".o1", f"no mirror vertex within z_B {window[0]:+g}…{window[1]:+g} D lets "
                       f"the march cover |x| ≤ {half_width:.3g} D: change x_a, gamma_a_rad or the foci")
    return tr.grid_then_bounded(objective, z_b + np.linspace(*window, 17), 1e-4, fail)

