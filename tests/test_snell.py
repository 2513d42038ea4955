import numpy as np

from antenna_cad.raytrace.snell import incidence_angle, reflect, refract


def test_refract_obeys_snell_and_flags_tir():
    theta = np.radians([0.0, 20.0, 40.0, 60.0])
    d = np.stack([np.sin(theta), np.cos(theta)], axis=-1)
    normal = np.tile([0.0, -1.0], (4, 1))  # facing the incoming ray's opposite side on purpose
    t, ok = refract(d, normal, 1.0, 1.5)
    assert ok.all()
    sin_t = t[:, 0]
    np.testing.assert_allclose(1.0 * np.sin(theta), 1.5 * sin_t, atol=1e-14)
    _, ok_back = refract(t, normal, 1.5, 1.0)
    assert ok_back.all()
    _, ok_tir = refract(d, normal, 1.5, 1.0)   # arcsin(1/1.5) = 41.8 deg
    assert list(ok_tir) == [True, True, True, False]


def test_reflect_and_incidence():
    d = np.array([[1.0, -1.0]]) / np.sqrt(2)
    r = reflect(d, np.array([[0.0, 1.0]]))
    np.testing.assert_allclose(r, [[1 / np.sqrt(2), 1 / np.sqrt(2)]], atol=1e-15)
    np.testing.assert_allclose(incidence_angle(d, np.array([[0.0, 1.0]])), np.pi / 4, atol=1e-15)
