"""RMS path error σ (2.7) against field angle (seed-003 §3.8, Fig. 3.15) for any beam former.

A source at polar angle ψ about the former's focal-locus centre is moved radially to the distance that
minimises σ; its beam azimuth φ and σ are recorded. At broadside (β = 90°, where the thesis compares
the formers) the phase at the slot line of guide x is Ψ(x) = L(x) + n_w t(x) = L(x) − L̄(x) + const,
L the traced path from the source to the guide entry and L̄ the mean design eikonal that sets the slot
line (:func:`antenna_cad.synthesis.slot_array.slot_line_t_mm`). σ is (2.7) as the thesis defines it
(seed-003 §3.3, L486): σ = √(Σ (L_i − L_0)² / N), L_i the path of ray i to the output front, L_0 that
of the central ray, N = 50 rays. Here the central ray ends at x = 0 and the N rays on N guides spread
evenly across the aperture; the front of an off-design source is the plane through the central ray's
end whose tilt sin φ minimises σ (least squares through the origin: the thesis does not say how it
tilts it), so L_i − L_0 = Ψ(x_i) − Ψ(0) − x_i sin φ. σ is in units of the aperture width (D = 1 for
the thesis's formers; the geometry is normalised to D, L486/L1184). Referring to the central ray
rather than to the mean path makes σ larger where the error is even in x (up to 1.5× for pure
defocus; 1.3× on the ellipse at 40°). σ(FOV) is the largest σ for |φ| ≤ FOV/2: the thesis quotes it
at an 80° field of view, Fig. 3.15's abscissa being the field angle (L1188–1190).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.optimize import minimize_scalar

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS
from antenna_cad.synthesis.slot_array.slot_line import traced_eikonal_mm

FOV_DEG = 80.0                                      # seed-003 §3.8
THESIS_SIGMA_80 = {"trifocal_two_mirror": 0.8e-4, "trifocal_mirror_lens": 1.2e-4,
                   "bifocal_two_mirror": 3.4e-4, "single_mirror": 5.6e-4}     # Fig. 3.15, L1188


@dataclass(frozen=True)
class FieldCurve:
    """σ (units of the aperture width) against beam azimuth φ (deg), both signs, sorted by φ."""
    name: str
    angle_deg: np.ndarray
    sigma: np.ndarray
    aperture_mm: float

    def sigma_fov(self, fov_deg: float = FOV_DEG) -> float:
        """Largest σ over |φ| ≤ fov/2 (edge value interpolated; NaN if the curve does not reach it)."""
        h = fov_deg / 2
        if self.angle_deg.max() < h - 1e-9:
            return float("nan")
        inside = np.abs(self.angle_deg) <= h
        edge = np.interp([-h, h], self.angle_deg, self.sigma)
        return float(max(np.max(self.sigma[inside], initial=0.0), edge.max()))


def sigma_at(bf: BeamFormer, source_mm, x_mm: np.ndarray) -> tuple[float, float]:
    """(σ (2.7) in units of the aperture width 2·max|x|, sin φ) of one source, the central ray at
    x = 0 the reference (module docstring); NaN if rays miss."""
    x = np.concatenate([[0.0], x_mm])
    try:
        L = traced_eikonal_mm(bf, np.asarray(source_mm, float), x)
    except DesignError:
        return float("nan"), float("nan")
    psi = L - np.mean([bf.eikonal(x, j) for j in range(len(bf.foci_mm))], axis=0)
    d = psi[1:] - psi[0]
    tilt = float(np.dot(x_mm, d) / np.dot(x_mm, x_mm))
    return float(np.sqrt(np.mean((d - tilt * x_mm) ** 2)) / (2 * np.abs(x_mm).max())), tilt


def field_curve(bf: BeamFormer, half_width_mm: float, name: str | None = None, n_angles: int = 15,
                fov_deg: float = FOV_DEG, radius_bounds: tuple[float, float] = (0.6, 1.4)) -> FieldCurve:
    """σ(φ) over polar angles ψ from the axis past the design focus until φ passes fov/2 (or rays miss)."""
    x = np.linspace(-half_width_mm, half_width_mm, N_SIGMA_RAYS)
    c = np.asarray(bf.focal_locus_centre_mm, float)
    F = bf.foci_mm[0]
    up = 1.0 if F[1] > c[1] else -1.0
    R0 = float(np.linalg.norm(F - c))
    psi0 = float(np.arctan2(F[0] - c[0], up * (F[1] - c[1])))
    pos = lambda R, psi: c + np.array([R * np.sin(psi), up * R * np.cos(psi)])
    angles, sigmas = [], []
    step = abs(psi0) / (n_angles // 2) if psi0 else np.radians(2.0)
    sgn = np.sign(psi0) if psi0 else 1.0
    target = (fov_deg / 2) / (n_angles - 1)          # beam-angle step aimed at (deg)
    psi = 0.0
    for _ in range(4 * n_angles):
        f = lambda R: np.nan_to_num(sigma_at(bf, pos(R, psi), x)[0], nan=1.0)
        res = minimize_scalar(f, bounds=(radius_bounds[0] * R0, radius_bounds[1] * R0), method="bounded",
                              options={"xatol": 1e-6 * R0})
        s, sphi = sigma_at(bf, pos(float(res.x), psi), x)
        if not np.isfinite(s):
            break
        angles.append(np.degrees(np.arcsin(np.clip(sphi, -1, 1))))
        sigmas.append(s)
        if abs(angles[-1]) > fov_deg / 2 + 2:
            break
        if len(angles) > 1 and abs(angles[-1] - angles[-2]) > 1e-6:
            step = float(np.clip(step * target / abs(angles[-1] - angles[-2]), 0.25 * step, 4 * step))
        psi += sgn * step
    a, s = np.abs(np.array(angles)), np.array(sigmas)
    a, s = np.concatenate([-a[:0:-1], a]), np.concatenate([s[:0:-1], s])
    return FieldCurve(name or bf.type, a, s, 2 * half_width_mm)


def reference_formers() -> dict[str, tuple[BeamFormer, float]]:
    """The formers compared in the report, normalised (D = 1), with the half-aperture of their guides:
    the ellipse, the bifocal two-mirror and the trifocal two-mirror each optimised for the 80° field of
    view from the thesis's values (:data:`antenna_cad.synthesis.slot_array.optimise.OPTIMISED`, §3.8),
    and the R9 bifocal mirror–lens (§3.4, no free parameters searched)."""
    from antenna_cad.synthesis.slot_array.bifocal_mirror_lens import bifocal_mirror_lens
    from antenna_cad.synthesis.slot_array.optimise import OPTIMISED, THESIS_START, build
    from antenna_cad.synthesis.slot_array.trifocal_mirror_lens import KA_RECIPE, trifocal_mirror_lens
    out = {name: (build(name, params, THESIS_START[name][1]), THESIS_START[name][1]) for name, params in OPTIMISED.items()}
    out["trifocal_mirror_lens"] = (trifocal_mirror_lens(**KA_RECIPE, half_width=0.505, margin=0.02), 0.5)
    out["bifocal_mirror_lens"] = (bifocal_mirror_lens(lens_a2=-.15, lens_vertex=.42, x0=.06, p1=.8325, p2=3.0,
                                                      f0=1.4, n=np.sqrt(2.2)), 0.5)
    return out


@lru_cache(maxsize=1)
def reference_curves() -> tuple[FieldCurve, ...]:
    """σ(φ) of :func:`reference_formers` (computed once per process)."""
    return tuple(field_curve(bf, hw, name) for name, (bf, hw) in reference_formers().items())
