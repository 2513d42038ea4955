"""The quiet zone as a volume: per-plane statistics against closed forms, the propagated field of a
uniform circular aperture against its exact on-axis field over the depth, a plane wave's zero figures,
the zone's defaults, and the figures in a collimator's verification."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from antenna_cad.quietzone.stats import largest_diameter_mm, plane_figures
from antenna_cad.quietzone.verdict import ModelPlanes, quiet_zone_study
from antenna_cad.quietzone.volume import Rays, caustic_period_mm, propagated, radii_mm, zone_from
from antenna_cad.spec.common import TestZoneSpec

LAM = 30.0
K = 2 * math.pi / LAM


def test_quadratic_phase_and_taper_closed_forms():
    """φ = c·r², level b·r² dB over a disc of radius ρ: p-p cρ², area-weighted RMS cρ²/√12,
    taper bρ², ripple 0 (to the quadrature of 4001 samples)."""
    rho, c, b = 200.0, 1e-3, -2e-5                      # deg/mm², dB/mm²
    r = np.linspace(0.0, rho, 4001)
    e = 10 ** (b * r**2 / 20) * np.exp(1j * np.radians(c * r**2))
    p = plane_figures(r, e, 2 * rho, 0.0, 1.0, 11.25)
    assert p.phase_p2p_deg == pytest.approx(c * rho**2, rel=1e-9)
    assert p.phase_rms_deg == pytest.approx(c * rho**2 / math.sqrt(12), rel=1e-5)
    assert p.amplitude_taper_db == pytest.approx(b * rho**2, rel=1e-9)
    assert p.amplitude_ripple_db < 1e-9
    # within ±11.25°: c r² ≤ 22.5 → r ≤ 150 mm (to a sample); within ±0.5 dB: |b| r² ≤ 1 → r ≤ 223 mm
    assert largest_diameter_mm(r, e, 1.0, 11.25) == pytest.approx(300.0, abs=0.2)
    assert largest_diameter_mm(r, e, 0.5, 180.0) == pytest.approx(2 * math.sqrt(1 / 2e-5) if
                                                                  2 * math.sqrt(1 / 2e-5) < 400 else 400.0, abs=0.2)


def _exact_on_axis(a: float, z: np.ndarray) -> np.ndarray:
    """Rayleigh–Sommerfeld field on the axis of a uniform disc of radius a (exact; the angular spectrum
    is the same propagator), over the incident plane wave: 1 − z/R·e^{jk(R − z)}, R = √(z² + a²)."""
    R = np.hypot(z, a)
    return 1 - z / R * np.exp(1j * K * (R - z))


def test_uniform_disc_on_axis_over_the_depth():
    """A uniform disc Ø10 λ propagated to 15 planes from 2 λ to 30 λ (Fresnel number 12.5 to 0.8):
    |E| and the phase on the axis against the exact form (0.015: the κ quadrature's ≈ 1 % of
    radiation.testzone with one κ axis for every plane; 1° where |E| > 0.2); beyond 15 λ (z > 3a) it is
    the Fresnel form 2|sin(k a²/(4z))|."""
    a = 5 * LAM
    r = radii_mm(a, LAM)
    z = np.linspace(2 * LAM, 30 * LAM, 15)
    e = propagated(r, np.ones_like(r), LAM, z, np.array([0.0]))[:, 0] * np.exp(-1j * K * z)
    exact = _exact_on_axis(a, z)
    np.testing.assert_allclose(np.abs(e), np.abs(exact), atol=0.015)
    ok = np.abs(exact) > 0.2
    np.testing.assert_allclose(np.degrees(np.angle(e[ok] / exact[ok])), 0.0, atol=1.0)
    far = z > 15 * LAM
    np.testing.assert_allclose(np.abs(exact[far]), 2 * np.abs(np.sin(K * a**2 / (4 * z[far]))), atol=0.06)


def test_quiet_zone_figures_of_a_uniform_disc_follow_its_axial_caustic():
    """The zone's amplitude p-p on each plane is at least the axis-to-rim swing the exact on-axis form
    gives, and the figures take the worst plane."""
    a = 5 * LAM
    zone = zone_from(TestZoneSpec(diameter_mm=2 * LAM, distance_mm=4 * LAM, depth_mm=8 * LAM, planes=9),
                     2 * a, 0.0, a, LAM)
    r = radii_mm(a, LAM)
    fields = propagated(r, np.ones_like(r), LAM, zone.planes_mm, r)
    model = ModelPlanes("angular spectrum", "", {"ideal": [(r, e) for e in fields]})
    v = quiet_zone_study(zone, [model], "on_axis", {"ideal": -90.0}, True)
    rows = [row for row in v.tables[0].rows]
    assert len(rows) == 9 and [row[2] for row in rows] == pytest.approx(zone.planes_mm.tolist(), abs=0.05)
    worst = max(row[4] for row in rows)
    assert v.figures["quiet_zone_ideal_on_axis_phase_p2p_deg"] == pytest.approx(worst, abs=1e-3)
    assert v.checks[0].name == "quiet_zone"


def test_plane_wave_has_zero_figures_on_every_plane():
    """GO of a collimated uniform beam: zero phase p-p and RMS, zero ripple and taper, full diameter."""
    y = np.linspace(0.0, 250.0, 501)
    rays = Rays(y, np.ones_like(y), np.zeros_like(y), np.ones_like(y), np.full_like(y, 1234.5), 0.0)
    zone = zone_from(TestZoneSpec(), 400.0, 100.0, 250.0, LAM)
    planes = [rays.field_at(z, LAM) for z in zone.planes_mm]
    v = quiet_zone_study(zone, [ModelPlanes("GO", "go_", {"ideal": planes})], "on_axis", {"ideal": -99.0}, True)
    f = v.figures
    for k in ("phase_p2p_deg", "phase_rms_deg", "amplitude_ripple_db", "amplitude_taper_db"):
        assert abs(f[f"quiet_zone_go_ideal_on_axis_{k}"]) < 1e-9
    assert f["quiet_zone_go_ideal_on_axis_diameter_mm"] == pytest.approx(500.0)
    assert v.checks[0].status == "pass"


def test_zone_defaults():
    """Depth one AUT diameter (at least 2 λ), near face at the AUT's distance, ≥ 5 planes spaced by at
    most half the caustic period at the near face; an old spec (limits only) stays valid."""
    z = zone_from(TestZoneSpec(), 500.0, 100.0, 250.0, LAM)
    assert (z.diameter_mm, z.distance_mm, z.depth_mm, z.planes_mm[0], z.planes_mm[-1]) == (500.0, 100.0, 500.0, 100.0, 600.0)
    assert np.diff(z.planes_mm).max() <= caustic_period_mm(250.0, 100.0, LAM) / 2 + 1e-9
    small = zone_from(TestZoneSpec(), 20.0, 3000.0, 250.0, LAM)
    assert small.depth_mm == 2 * LAM and len(small.planes_mm) == 5
    assert len(zone_from(TestZoneSpec(depth_mm=100000), 500.0, 100.0, 250.0, LAM).planes_mm) == 200   # capped
    assert caustic_period_mm(250.0, 100.0, LAM) == pytest.approx(LAM / (1 - 100 / math.hypot(100, 250)))
    TestZoneSpec.model_validate({"amplitude_db": 0.5, "phase_deg": 5})


def test_collimator_verification_carries_the_quiet_zone():
    """A machined PTFE collimator (ideal lens only): both models' figures, the tables, the plots; GO of
    the ideal lens is flat on every plane; the check names the fast model and the worst plane."""
    from antenna_cad.kinds import collimator as Kc
    from antenna_cad.spec import parse_spec
    spec = parse_spec({"name": "t", "kind": "collimator", "frequency_ghz": 15.0, "material": "ptfe",
                       "design": {"diameter_mm": 120, "focal_length_mm": 300, "aut": {"diameter_mm": 80},
                                  "test_zone": {"depth_mm": 60, "planes": 6}},
                       "fabrication": {"method": "solid"}})
    design = Kc.synthesize(spec)
    v = Kc.verify(spec, design, None, Kc.fabricate(spec, design, None, ()))
    f = v.figures
    assert f["quiet_zone_planes"] == 6 and f["quiet_zone_depth_mm"] == 60
    assert f["quiet_zone_go_ideal_on_axis_phase_p2p_deg"] < 0.01
    assert f["quiet_zone_ideal_on_axis_phase_p2p_deg"] > f["quiet_zone_go_ideal_on_axis_phase_p2p_deg"]
    assert 0 < f["quiet_zone_ideal_on_axis_diameter_mm"] <= 120
    check = next(c for c in v.checks if c.name == "quiet_zone")
    assert "fast model" in check.message and "worst at" in check.message
    assert {"quiet-zone-phase", "quiet-zone-amplitude", "quiet-zone-map"} <= {p.name for p in v.plots}
    assert {"quiet-zone", "quiet-zone-planes"} <= {t.name for t in v.tables}


def test_stack_own_figures_divide_out_the_rim():
    """A stepped variant equal to the ideal lens times a known phase c·r² (the same radii): the stack's
    own figures are that phase's closed forms on every plane, whatever the common field does."""
    a, c = 5 * LAM, 2e-3
    zone = zone_from(TestZoneSpec(diameter_mm=6 * LAM, distance_mm=2 * LAM, depth_mm=4 * LAM, planes=5),
                     2 * a, 0.0, a, LAM)
    r = radii_mm(a, LAM)
    ideal = propagated(r, np.ones_like(r), LAM, zone.planes_mm, r)
    stepped = ideal * np.exp(1j * np.radians(c * r**2))
    model = ModelPlanes("fast", "", {"ideal": [(r, e) for e in ideal], "stepped": [(r, e) for e in stepped]})
    f = quiet_zone_study(zone, [model], "on_axis", {"ideal": -90.0, "stepped": -90.0}, True).figures
    rho = r[r <= 3 * LAM * (1 + 1e-12)][-1]
    assert f["quiet_zone_stepped_added_on_axis_phase_p2p_deg"] == pytest.approx(c * rho**2, rel=1e-9)
    assert f["quiet_zone_stepped_added_on_axis_phase_rms_deg"] == pytest.approx(c * rho**2 / math.sqrt(12), rel=2e-3)


def _plate(thickness_mm: float, radius_mm: float):
    """foam_mm of a plate of foam 0 ≤ z ≤ thickness, r ≤ radius."""
    def foam(z0, z1, r):
        return np.where(np.asarray(r) <= radius_mm, max(0.0, min(z1, thickness_mm) - max(z0, 0.0)), 0.0)
    return foam


def test_multislice_without_foam_is_the_feeds_own_wave():
    """No foam: 40 slices over 5 λ reproduce the feed's own spherical wave (E_r of the dipole,
    cos²θ·e^{ikR}/R, the feed 100 λ away) out to the rim within 1 % and 0.6° (further on, the rolled-off
    edge of the spill-over, 1–5 λ beyond the rim, sends its own weak edge wave in)."""
    from antenna_cad.fullwave.fastmodel import multislice_field
    a, feed, end = 8 * LAM, -100 * LAM, 5 * LAM
    r, e = multislice_field(_plate(0.0, a), 0.0, end, end, feed, a, 1.1, LAM)
    R = np.hypot(r, end - feed)
    exact = ((end - feed) / R) ** 2 * np.exp(1j * K * R) / R
    inside = r <= a
    np.testing.assert_allclose(np.abs(e[inside] / exact[inside]), 1.0, atol=0.01)
    np.testing.assert_allclose(np.degrees(np.angle(e[inside] / exact[inside])), 0.0, atol=0.6)


def test_multislice_disc_of_foam_against_its_closed_form():
    """A disc of foam (radius a, 20 mm, εr 1.047) before a far feed (a plane wave), carried through its
    slices and on by the angular spectrum as the quiet zone's fast model does: what it adds to the field
    on the axis at L behind it, over the incident wave there, is (τe^{iφ0} − 1)·(1 − L/ρ·e^{jk(ρ − L)}),
    ρ = √(L² + a²) (L from the plate's middle: a plate this thin diffracts as a screen there),
    φ0 = k0(n−1)·20 mm, τ = 4n/(1+n)² (the exact Rayleigh–Sommerfeld field of a disc); within 10 % of
    the departure |τe^{iφ0} − 1| at 2 λ (where the plate's thickness still shows) and 3 % from 10 λ on."""
    from antenna_cad.fullwave.fastmodel import multislice_field, thin_screen_deg
    n, a, d0, feed = 1.047 ** 0.5, 250.0, 20.0, -1e6
    departure = 4 * n / (1 + n) ** 2 * np.exp(1j * math.radians(thin_screen_deg(d0, n, LAM))) - 1
    L = np.linspace(2 * LAM, 20 * LAM, 7)
    r, plate = multislice_field(_plate(d0, a), 0.0, d0, d0, feed, a, n, LAM)
    free = multislice_field(_plate(0.0, a), 0.0, d0, d0, feed, a, n, LAM)[1]
    grid = radii_mm(float(r[-1]), LAM)
    added = np.interp(grid, r, (plate - free).real) + 1j * np.interp(grid, r, (plate - free).imag)
    got = propagated(grid, added, LAM, L, np.array([0.0]))[:, 0] * (d0 + L - feed) / np.exp(1j * K * (d0 + L - feed))
    mid = L + d0 / 2
    rho = np.hypot(mid, a)
    exact = departure * (1 - mid / rho * np.exp(1j * K * (rho - mid)))
    assert np.max(np.abs(got - exact)) < 0.1 * abs(departure)
    assert np.max(np.abs(got - exact)[L >= 10 * LAM]) < 0.03 * abs(departure)


def test_rays_that_cross_the_axis_arrive_at_their_radius():
    """GO of a converging fan: a ray aimed 10 mm off axis at 0.1 rad inward is at r = 10 mm again
    200 mm further on (having crossed the axis), with its straight-line path."""
    rays = Rays(np.array([0.0, 10.0]), np.array([1.0, math.cos(0.1)]), np.array([0.0, -math.sin(0.1)]),
                np.ones(2), np.zeros(2), 0.0)
    z = 2 * 10.0 / math.tan(0.1)
    r, e = rays.field_at(z, LAM)
    assert r == pytest.approx([0.0, 10.0])
    assert np.angle(e[1]) == pytest.approx(np.angle(np.exp(1j * K * z / math.cos(0.1))), abs=1e-9)


def test_a_zone_touching_the_stack_is_the_aperture_field():
    """A zone starting at the back of the stack (distance 0; the spectrum of λ/4, ≈ 9 k): the plane there
    reproduces the aperture field (a uniform disc: 1 within 2 %) away from the rim and from the axis, where
    a body of revolution focuses the ringing of the truncated spectrum."""
    a = 5 * LAM
    r = radii_mm(a, LAM)
    e = propagated(r, np.ones_like(r), LAM, np.array([0.0, LAM]), r)
    inside = (r > LAM) & (r < a - 2 * LAM)
    np.testing.assert_allclose(np.abs(e[0][inside]), 1.0, atol=0.02)
