"""Elliptic mirror of the bifocal single-mirror array (seed-003 §3.5)."""

from __future__ import annotations

from functools import partial

import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.beamformer import BeamFormer, trace_single_mirror
from antenna_cad.synthesis.slot_array.common import N_SIGMA_RAYS
from antenna_cad.synthesis.slot_array.curves import _make_curve, _rms


def ellipse_mirror(minor_semi_axis_mm: float, focal_separation_mm: float,
                   half_width_mm: float, n_points: int = 201) -> BeamFormer:
    """Elliptic mirror of the bifocal single-mirror array (seed-003 §3.5, eqs. 3.5–3.6).

    b = r0 cos α (vertex O to the line of foci), c = 2 r0 sin α. The mirror
    x² cos²α + y² − 2 r0 y cos α = 0 passes through O and is concave toward the foci
    F, F′ = (∓r0 sin α, r0 cos α). Focus F (left) launches a wave with azimuth cosine +sin α.
    Eikonal from F to the mirror point A: FA = r0 + x sin α (r + r′ = 2r0, r − r′ = 2x sin α).
    """
    b, c = float(minor_semi_axis_mm), float(focal_separation_mm)
    if b <= 0 or c < 0:
        raise DesignError("beamformer.minor_semi_axis_mm", f"need b > 0, c >= 0 (got {b}, {c})")
    r0 = np.hypot(b, c / 2)
    alpha = np.arctan2(c / 2, b)
    if half_width_mm >= r0:
        raise DesignError("beamformer.minor_semi_axis_mm",
                          f"mirror half-width {half_width_mm:.4g} mm >= r0 {r0:.4g} mm")
    x = np.linspace(-half_width_mm, half_width_mm, n_points)
    root = np.sqrt(1.0 - (x / r0) ** 2)
    y = b * (1.0 - root)
    slope = b * x / (r0**2 * root)
    mirror = _make_curve("mirror", "layer1-layer2", x, y, slope)
    sa, ca = np.sin(alpha), np.cos(alpha)
    foci = np.array([[-r0 * sa, r0 * ca], [r0 * sa, r0 * ca]])
    dirs = np.array([[sa, 0.0], [-sa, 0.0]])   # azimuth cosines ±sin α (y part set by β)

    def eikonal(x_mm, j):
        return r0 + (1 if j == 0 else -1) * np.asarray(x_mm, float) * sa

    trace = partial(trace_single_mirror, mirror)
    sig = []
    xs = np.linspace(-half_width_mm, half_width_mm, N_SIGMA_RAYS)
    for j in range(2):
        sig.append(_rms(trace(foci[j], xs)[1] - eikonal(xs, j)))
    sig = np.array(sig)
    phi = np.linspace(-np.pi / 3, np.pi / 3, 121)
    locus = np.stack([r0 * np.sin(phi), r0 * np.cos(phi)], axis=-1)
    return BeamFormer("single_mirror", (mirror,), (), foci, dirs, sig, sig / (2 * half_width_mm),
                      2 * half_width_mm, mirror, locus, np.zeros(2), eikonal, trace,
                      {"r0_mm": float(r0), "alpha_rad": float(alpha)})
