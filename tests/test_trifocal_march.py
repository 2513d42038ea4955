"""Pieces of the (unfinished) trifocal march, seed-003 §3.6 (antenna_cad/synthesis/slot_array/trifocal.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from antenna_cad.synthesis.slot_array import trifocal as tr


def test_segment_interpolant_is_machine_precise_for_smooth_maps():
    seg = tr.Segment(lambda u: [math.sin(3 * u), math.exp(u)], -0.4, 0.7)
    u = np.linspace(-0.4, 0.7, 57)
    err = np.abs(seg(u) - np.column_stack([np.sin(3 * u), np.exp(u)])).max()
    assert err < 1e-13 and seg.interp_error < 1e-13


def _thesis_two_mirror(beta_c_deg: float):
    """§3.8 two-mirror set with β_C; initial segments of §3.6 (C/D on mirror 1, B where the F1 ray
    from C meets the F ray from D, mirror 2 through O2 and B)."""
    F1, F, C, z_o2 = (-0.25, -0.23), (0.0, -0.25), (-0.08, 0.25), -1.02
    bc = math.radians(beta_c_deg)
    e_out = (math.cos(bc), -math.sin(bc))
    b2 = tr._slope_between(*tr._unit2(C[0] - F1[0], C[1] - F1[1]), *e_out, 1.0) / (2 * C[0])
    b0 = C[1] - b2 * C[0] ** 2
    D = (-C[0], C[1])
    eD = tr._unit2(*tr._redirect(*tr._unit2(D[0] - F[0], D[1] - F[1]), 2 * b2 * D[0], 1.0))
    a, b = tr._meet(*C, *e_out, *D, *eD)
    B = (C[0] + a * e_out[0], C[1] + a * e_out[1])
    s1 = math.sin(math.atan(F1[0] / (F1[1] - b0)))
    fo = tr.Foci(F1, F, s1, 1.0, math.dist(C, F1) + a - s1 * B[0], math.dist(D, F) + b)
    return fo, e_out, eD, B, b0, b2, z_o2, (B[1] - z_o2) / B[0] ** 2


def test_thesis_two_mirror_set_is_inconsistent_at_B():
    """Where B reaches the mirror-2 vertex depth (β_C ≈ 72.3°), the three eikonals need a guide-curve
    slope n₂(e_1 − e_F)·(1, z′) = s_1 far from the slope of the parabola through O2 and B."""
    fo, e1, eF, B, *_, a2 = _thesis_two_mirror(72.3)
    required = (fo.s1 - (e1[0] - eF[0])) / (e1[1] - eF[1])
    assert -1.1 < B[1] < -0.95 and abs(required - 2 * a2 * B[0]) > 5


def test_march_on_the_thesis_set_fails_with_a_named_error():
    fo, *_, B, b0, b2, a0, a2 = _thesis_two_mirror(72.3)
    S0 = tr.Segment(lambda x: [x, b0 + b2 * x * x, 2 * b2 * x], -0.08, 0.08)
    with pytest.raises(tr.MarchError) as err:
        tr.construct(fo, S0, a0, a2, B[0], half_width=0.5, margin=0.1, max_steps=10,
                     field="beamformer.beta_c_deg")
    assert err.value.field == "beamformer.beta_c_deg"
