"""The synthesis inner loops on floats (validate in ≤ 1 s) reproduce the vectorized numpy
steps they replace: the Nikulina chain's one-point steps, the graded tracer's scalar spline and n²,
and the layer ray's math path against its numpy path."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicHermiteSpline

from antenna_cad.synthesis.bifocal_steps import _back, _back_plane1, _fwd, _fwd_plane1, _Optics
from antenna_cad.synthesis.graded import _LAWS_NP, Medium, Ray
from antenna_cad.synthesis.graded_lens import scalar_spline


def _optics() -> _Optics:
    tilt = math.radians(5.0)
    return _Optics(np.array([-300.0, -20.0]), 1.6, 900.0, k=np.array([math.cos(tilt), math.sin(tilt)]))


def test_one_point_steps_match_the_vectorized_steps():
    o = _optics()
    y = np.linspace(-80.0, 80.0, 41)
    P = np.stack([240.0 - 0.002 * y**2, y], -1)
    NP = np.stack([-np.ones_like(y), -0.004 * y], -1)
    NP /= np.linalg.norm(NP, axis=-1, keepdims=True)
    Q, NQ = _fwd(P, NP, o)
    B, NB = _back(Q, NQ, o)
    assert np.all(np.isfinite(Q)) and np.all(np.isfinite(B))
    for i in range(len(y)):
        q, nq = _fwd_plane1(tuple(P[i]), tuple(NP[i]), o)
        b, nb = _back_plane1(tuple(Q[i]), tuple(NQ[i]), o)
        np.testing.assert_allclose([*q, *nq], [*Q[i], *NQ[i]], rtol=1e-14, atol=1e-12)
        np.testing.assert_allclose([*b, *nb], [*B[i], *NB[i]], rtol=1e-14, atol=1e-12)


def test_one_point_steps_report_no_solution_as_nan():
    o = _optics()
    short = _Optics(o.F, o.n, 0.0, k=o.k)                  # eikonal too short: t < 0 and no root s > 0
    P, NP = np.array([[240.0, 10.0]]), np.array([[-1.0, 0.0]])
    Q, NQ = _fwd(P, NP, short)
    B, _ = _back(np.array([[250.0, 10.0]]), NP, short)
    assert np.isnan(Q).all() and np.isnan(B).all()
    assert np.isnan(_fwd_plane1((240.0, 10.0), (-1.0, 0.0), short)[0]).all()
    assert np.isnan(_back_plane1((250.0, 10.0), (-1.0, 0.0), short)[0]).all()


def test_scalar_spline_is_scipys_ppoly_bit_for_bit():
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(-1.0, 1.0, 30))
    spline = CubicHermiteSpline(x, rng.normal(size=30), rng.normal(size=30))
    at = scalar_spline(spline)
    pts = np.concatenate([rng.uniform(-1.3, 1.3, 2000), x])     # inside, outside, on the breakpoints
    assert np.array_equal(spline(pts), [at(float(v)) for v in pts])


@pytest.fixture
def medium() -> Medium:
    med = Medium(1.6, 2.0)
    for top, m_i in ((0.3, -1.0), (0.45, 3.0), (0.6, -2.0)):
        med.close_top(top)
        med.add_layer(m_i)
    return med


def test_n2_at_is_n_squared_everywhere(medium):
    ys = np.concatenate([np.linspace(-0.7, 0.7, 301), [0.3, -0.45, 0.6]])     # the boundaries included
    assert [medium.n2_at(y) for y in ys] == [float(v) ** 2 for v in medium.n(ys)]


@pytest.mark.parametrize("a, kinds", [(1.45, {"sin", "cosh"}), (1.3, {"sin", "sinh"})])
def test_layer_ray_math_path_matches_numpy_path(medium, a, kinds):
    ray = Ray(medium, 0.0, 0.05, a, 1.0, 10.0)
    assert len(ray.segments) > 10 and {seg.kind for seg in ray.segments} == kinds    # crosses the layers
    for seg in ray.segments:
        for x in np.linspace(seg.x0, seg.x1, 7):
            with np.errstate(all="ignore"):
                ref = seg._at(float(x), _LAWS_NP[seg.kind], np.sqrt)
            np.testing.assert_allclose(seg.at(float(x)), ref, rtol=1e-13, atol=1e-13)
    xs = np.linspace(0.0, ray.x_end, 200)
    np.testing.assert_allclose(ray.ys(xs), [ray.y_at(float(x)) for x in xs], rtol=1e-13, atol=1e-13)
