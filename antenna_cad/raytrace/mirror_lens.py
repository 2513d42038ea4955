"""3-D geometrical-optics trace of the aplanatic mirror-lens (seed-004 §1, §3.1): feed → front face
(refraction) → mirror (reflection) → front face (refraction) → air, for any feed position.

Surfaces are axisymmetric profiles z = g(ρ) given as callables with their slopes (the exact
synthesis or the body as built). Frame and units of :mod:`antenna_cad.synthesis.aplanatic`: feed
at the origin, z into the body, the beam leaves toward −z; lengths in units of D (the tracer is
scale free). Pure numpy.

σ (seed-004 eq. (18)) is the RMS of the eikonal over the rays through the aperture, referred to a
plane wave along the rays' mean direction (tilt removed), with the feed moved along the focal
curve: for a lateral displacement δ_R the axial δ_Z that minimises σ.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
from scipy.optimize import minimize_scalar, root

from antenna_cad.raytrace.snell import reflect, refract, transmission
from antenna_cad.synthesis.aplanatic import Profiles

Profile = Callable[[np.ndarray], np.ndarray]
GRID = 41                       # launch grid per side (direction cosines), ≈ 1300 rays in the cone
MIN_RAYS = 50                   # fewer rays through the aperture: no usable wavefront
CONE_MARGIN = 1.25              # launch cone beyond the on-axis cone, so a displaced feed fills the aperture


@dataclass(frozen=True)
class Surface:
    z: Profile
    slope: Profile
    rho_max: float              # the face exists for ρ ≤ rho_max

    def normal(self, p: np.ndarray) -> np.ndarray:
        rho = np.hypot(p[:, 0], p[:, 1])
        safe = np.where(rho > 0, rho, 1.0)
        g = self.slope(rho) / safe
        return np.stack([-g * p[:, 0], -g * p[:, 1], np.ones(len(p))], -1)


@dataclass(frozen=True)
class Body:
    """The mirror-lens as a tracer sees it: front face, mirror, index, aperture radius, and whether
    the feed sits inside the dielectric (f0 = 0, seed-004 §2.4)."""
    front: Surface
    mirror: Surface
    n: float
    aperture: float
    gamma: float
    feed_inside: bool = False
    tan_delta: float = 0.0


def body_from_profiles(p: Profiles, tan_delta: float = 0.0, n: float | None = None) -> Body:
    """The exact synthesized body (Hermite profiles through the marched points and slopes)."""
    front, mirror = p.front_spline(), p.mirror_spline()
    return Body(Surface(front, front.derivative(), float(p.s[-1])),
                Surface(mirror, mirror.derivative(), float(p.R_b[-1])),
                p.n if n is None else n, float(p.s[-1]), p.gamma, p.feed_on_surface, tan_delta)


@dataclass(frozen=True)
class Rays:
    launch: np.ndarray          # (N, 3) unit launch directions
    exit_point: np.ndarray      # (N, 3) C
    exit_dir: np.ndarray        # (N, 3)
    opl: np.ndarray             # optical path feed → C
    inside: np.ndarray          # geometric path inside the dielectric
    fresnel: np.ndarray         # amplitude transmission, mean of both polarisations, both faces
    ok: np.ndarray


def _hit(p: np.ndarray, w: np.ndarray, surf: Surface, t: np.ndarray,
         alive: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Ray parameter where p + t·w meets z = g(ρ), Newton from ``t``; returns (t, converged). A ray
    leaves the iteration once its step is below 1e-14 (or not finite): the rays that miss the face
    would otherwise keep every ray in all 60 iterations. Rays not ``alive`` (already lost at an
    earlier face) are not iterated: they could only fail to converge, e.g. a ray reflected beyond
    the mirror's rim looking for the front face (a fifth of the launch grid for a feed on the
    surface, which kept the loop in all 60 iterations); each ray's iteration is its own, so the
    others get the same bits."""
    t, step = np.array(t, float), np.full(len(t), np.inf)
    act = np.arange(len(t)) if alive is None else np.flatnonzero(alive)
    for _ in range(60):
        pa, wa = p[act], w[act]
        q = pa + t[act, None] * wa
        rho = np.hypot(q[:, 0], q[:, 1])
        safe = np.where(rho > 0, rho, 1.0)
        h = q[:, 2] - surf.z(rho)
        dh = wa[:, 2] - surf.slope(rho) * (q[:, 0] * wa[:, 0] + q[:, 1] * wa[:, 1]) / safe
        step[act] = h / dh
        t[act] -= step[act]
        act = act[np.isfinite(step[act]) & (np.abs(step[act]) >= 1e-14)]
        if not act.size:
            break
    return t, np.isfinite(t) & (t > 0) & (np.abs(step) < 1e-10)


def _fresnel(w_in, w_out, normal, n1, n2):
    nrm = normal / np.linalg.norm(normal, axis=-1, keepdims=True)
    ci, ct = np.abs(np.sum(w_in * nrm, -1)), np.abs(np.sum(w_out * nrm, -1))
    return 0.5 * (transmission(ci, ct, n1, n2, "perp") + transmission(ci, ct, n1, n2, "par"))


def trace(body: Body, feed, launch: np.ndarray) -> Rays:
    """Trace unit ``launch`` directions from ``feed`` through ``body``."""
    N = len(launch)
    p0 = np.tile(np.asarray(feed, float), (N, 1))
    n, z_mirror = body.n, float(body.mirror.z(np.array([0.0]))[0])
    ok = np.ones(N, bool)
    if body.feed_inside:
        a, w, opl, inside, fres = p0, launch, np.zeros(N), np.zeros(N), np.ones(N)
    else:
        t, good = _hit(p0, launch, body.front, (float(body.front.z(np.array([0.0]))[0]) - p0[:, 2]) / launch[:, 2])
        a = p0 + t[:, None] * launch
        ok &= good & (np.hypot(a[:, 0], a[:, 1]) <= body.front.rho_max)
        nrm = body.front.normal(a)
        w, good = refract(launch, nrm, 1.0, n)
        ok &= good
        fres = _fresnel(launch, w, nrm, 1.0, n)
        opl, inside = t, np.zeros(N)
    t, good = _hit(a, w, body.mirror, (z_mirror - a[:, 2]) / w[:, 2], ok)
    b = a + t[:, None] * w
    ok &= good & (np.hypot(b[:, 0], b[:, 1]) <= body.mirror.rho_max)
    opl, inside = opl + n * t, inside + t
    v = reflect(w, body.mirror.normal(b))
    z_front = body.front.z(np.minimum(np.hypot(b[:, 0], b[:, 1]), body.front.rho_max))
    t, good = _hit(b, v, body.front, (z_front - b[:, 2]) / v[:, 2], ok)
    c = b + t[:, None] * v
    ok &= good & (np.hypot(c[:, 0], c[:, 1]) <= body.aperture)
    opl, inside = opl + n * t, inside + t
    nrm = body.front.normal(c)
    out, good = refract(v, nrm, n, 1.0)
    ok &= good & np.all(np.isfinite(out), -1)
    fres = fres * _fresnel(v, out, nrm, n, 1.0)
    return Rays(launch, c, out, opl, inside, fres, ok)


def launch_grid(body: Body, grid: int = GRID, margin: float = CONE_MARGIN) -> np.ndarray:
    """Directions uniform in (sin α cos φ, sin α sin φ): for an aplanat r_C = γ sin α, so the
    on-axis rays cover the exit aperture uniformly."""
    s = min(0.999, margin * body.aperture / body.gamma)
    u, v = np.meshgrid(np.linspace(-s, s, grid), np.linspace(-s, s, grid))
    u, v = u.ravel(), v.ravel()
    keep = u**2 + v**2 <= s**2
    u, v = u[keep], v[keep]
    return np.stack([u, v, np.sqrt(1 - u**2 - v**2)], -1)


@dataclass(frozen=True)
class Wavefront:
    x: np.ndarray               # exit points (units of D)
    y: np.ndarray
    error: np.ndarray           # eikonal minus the best plane wave (tilt and piston removed)
    beam: np.ndarray            # unit beam direction (mean exit direction)

    @property
    def sigma(self) -> float:
        return float(np.sqrt(np.mean(self.error**2)))

    @property
    def field_angle_deg(self) -> float:
        return float(np.degrees(np.arccos(np.clip(-self.beam[2], -1.0, 1.0))))


def wavefront(r: Rays) -> Wavefront:
    """Eikonal of the good rays on a plane normal to their mean direction, tilt and piston removed
    (seed-004 (18): L0 the mean)."""
    c, w, opl = r.exit_point[r.ok], r.exit_dir[r.ok], r.opl[r.ok]
    if len(opl) < MIN_RAYS:
        raise ValueError(f"only {len(opl)} rays reach the aperture")
    b = w.mean(axis=0)
    b /= np.linalg.norm(b)
    proj = c @ b
    L = opl + (proj.max() - proj) / (w @ b)
    A = np.stack([np.ones(len(L)), c[:, 0], c[:, 1]], -1)
    resid = L - A @ np.linalg.lstsq(A, L, rcond=None)[0]
    return Wavefront(c[:, 0], c[:, 1], resid, b)


def sigma_at(body: Body, feed, launch: np.ndarray | None = None) -> Wavefront:
    return wavefront(trace(body, feed, launch_grid(body) if launch is None else launch))


def _sigma_or_inf(body: Body, feed, launch) -> float:
    try:
        return sigma_at(body, feed, launch).sigma
    except ValueError:
        return np.inf


@dataclass(frozen=True)
class FieldScan:
    """σ against the field angle with the feed on the focal curve (arrays, units of D)."""
    delta_r: np.ndarray
    delta_z: np.ndarray
    field_angle_deg: np.ndarray
    sigma: np.ndarray
    sigma_on_axis_focus: np.ndarray     # σ with δ_Z = 0 (feed on the focal plane)


def field_scan(body: Body, angles_deg: np.ndarray, dz_range: float = 0.05) -> FieldScan:
    """For each field angle θ: lateral feed offset δ_R = γ sin θ (the aplanat's beam tilt, the
    linear term of (19); γ sin θ / n for a feed inside the dielectric, (20)), then the axial δ_Z
    minimising σ (focal curve); the feed moves to −x."""
    launch = launch_grid(body)
    dr, dz, ang, sig, sig0 = [], [], [], [], []
    scale = body.n if body.feed_inside else 1.0        # (20): the linear term is n sin α δ_R inside
    for th in np.radians(np.asarray(angles_deg, float)):
        d = body.gamma * np.sin(th) / scale
        try:
            at_focus = sigma_at(body, (-d, 0.0, 0.0), launch)
        except ValueError as exc:
            raise ValueError(f"field angle {np.degrees(th):.1f}° (feed offset {d:.3f} D): {exc}") from None
        res = minimize_scalar(lambda z: _sigma_or_inf(body, (-d, 0.0, z), launch), bounds=(-dz_range, dz_range),
                              method="bounded", options={"xatol": 1e-7})
        best, z = (at_focus, 0.0) if at_focus.sigma <= res.fun else (sigma_at(body, (-d, 0.0, res.x), launch), res.x)
        dr.append(d), dz.append(z), ang.append(best.field_angle_deg), sig.append(best.sigma)
        sig0.append(at_focus.sigma)
    return FieldScan(*(np.array(a) for a in (dr, dz, ang, sig, sig0)))


@dataclass(frozen=True)
class ApertureField:
    """GO aperture field on the exit face along the scan-plane cut (plain arrays for the
    radiation / full-wave modules): ``x`` exit coordinate (units of D), ``amplitude`` relative to
    its maximum for an isotropic feed (ray-tube divergence × Fresnel × dielectric loss; multiply
    by the feed's pattern at ``launch_angle``), ``phase_deg`` = −360·eikonal/λ, tilt removed."""
    x: np.ndarray
    amplitude: np.ndarray
    phase_deg: np.ndarray
    launch_angle: np.ndarray
    beam_angle_deg: float


def aperture_field(body: Body, feed, wavelength: float, rays: int = 401, h: float = 1e-6) -> ApertureField:
    """Meridional cut (y = 0) of the aperture field for a feed at ``feed``; the ray-tube amplitude
    is √(dΩ / dA) from the Jacobian of launch direction → exit point (finite differences ``h``)."""
    s = min(0.999, CONE_MARGIN * body.aperture / body.gamma)
    u = np.linspace(-s, s, rays)
    base = np.stack([u, np.zeros_like(u)], -1)
    dirs = [base, base + [h, 0.0], base + [0.0, h]]
    traces = [trace(body, feed, np.column_stack([q, np.sqrt(1 - np.sum(q**2, -1))])) for q in dirs]
    ok = traces[0].ok & traces[1].ok & traces[2].ok
    c = [t.exit_point[ok, :2] for t in traces]
    jac = np.abs((c[1][:, 0] - c[0][:, 0]) * (c[2][:, 1] - c[0][:, 1])
                 - (c[1][:, 1] - c[0][:, 1]) * (c[2][:, 0] - c[0][:, 0])) / h**2
    r0 = traces[0]
    wz = r0.launch[ok, 2]
    k = 2 * np.pi / wavelength
    amp = np.sqrt(1.0 / (wz * jac)) * r0.fresnel[ok] * np.exp(-0.5 * k * body.n * body.tan_delta * r0.inside[ok])
    wf = wavefront(replace(r0, ok=ok))
    order = np.argsort(wf.x)
    return ApertureField(wf.x[order], (amp / amp.max())[order], (-360.0 * wf.error / wavelength)[order],
                         np.arccos(wz)[order], wf.field_angle_deg)


def _surface_point(surf: Surface, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Point on z = g(ρ) above (x, y) and its derivatives along x and y."""
    rho = float(np.hypot(*xy))
    g, gp = float(surf.z(np.array([rho]))[0]), float(surf.slope(np.array([rho]))[0])
    k = gp / rho if rho > 0 else 0.0
    return np.array([xy[0], xy[1], g]), np.array([1.0, 0.0, k * xy[0]]), np.array([0.0, 1.0, k * xy[1]])


def _unit(v):
    return v / np.linalg.norm(v)


def stationary_path(body: Body, source, exit_point, guess: np.ndarray) -> float:
    """Optical path source → A′ (front) → B′ (mirror) → fixed exit point C made stationary over A′
    and B′ (Fermat; seed-004 §3.2 'the exit point is fixed'); A′ is absent for a feed inside."""
    o, c, n = np.asarray(source, float), np.asarray(exit_point, float), body.n

    def parts(x):
        if body.feed_inside:
            return None, _surface_point(body.mirror, x)
        return _surface_point(body.front, x[:2]), _surface_point(body.mirror, x[2:])

    def grad(x):
        a, (b, bx, by) = parts(x)
        e_bc = _unit(c - b)
        if a is None:
            e_ob = _unit(b - o)
            return [n * (e_ob - e_bc) @ bx, n * (e_ob - e_bc) @ by]
        (pa, ax, ay) = a
        e_oa, e_ab = _unit(pa - o), _unit(b - pa)
        ga, gb = e_oa - n * e_ab, n * (e_ab - e_bc)
        return [ga @ ax, ga @ ay, gb @ bx, gb @ by]

    sol = root(grad, guess, method="hybr", options={"xtol": 1e-15})
    a, (b, _, _) = parts(sol.x)
    if a is None:
        return float(n * (np.linalg.norm(b - o) + np.linalg.norm(c - b)))
    return float(np.linalg.norm(a[0] - o) + n * np.linalg.norm(b - a[0]) + n * np.linalg.norm(c - b))


def astigmatism_3d(body: Body, r_exit: float, delta: float = 1e-3) -> tuple[float, float]:
    """L_X, L_Y (the δ_R² coefficients of (19)/(20), per unit n for a feed inside) at exit radius
    ``r_exit`` by exact 3-D stationary paths with the source at (−δ cos φ, −δ sin φ, 0), φ = 0 and
    90°, central second differences in δ."""
    sa = r_exit / body.gamma
    ray = trace(body, (0.0, 0.0, 0.0), np.array([[sa, 0.0, np.sqrt(1 - sa * sa)]]))
    c = ray.exit_point[0]
    w = ray.launch[0]
    if body.feed_inside:
        guess = (_hit(np.zeros((1, 3)), w[None], body.mirror, np.array([1.0]))[0][0] * w)[:2]
    else:
        t_a = _hit(np.zeros((1, 3)), w[None], body.front, np.array([body.front.z(np.array([0.0]))[0] / w[2]]))[0]
        a = t_a[0] * w
        u, _ = refract(w[None], body.front.normal(a[None]), 1.0, body.n)
        t = _hit(a[None], u, body.mirror, np.array([(body.mirror.z(np.array([0.0]))[0] - a[2]) / u[0, 2]]))[0]
        b = a + t[0] * u[0]
        guess = np.concatenate([a[:2], b[:2]])
    L0 = stationary_path(body, (0.0, 0.0, 0.0), c, guess)
    out = []
    for phi in (0.0, np.pi / 2):
        e = np.array([-np.cos(phi), -np.sin(phi), 0.0])
        Lp = stationary_path(body, delta * e, c, guess)
        Lm = stationary_path(body, -delta * e, c, guess)
        out.append((Lp + Lm - 2 * L0) / (2 * delta**2) / (body.n if body.feed_inside else 1.0))
    return out[0], out[1]
