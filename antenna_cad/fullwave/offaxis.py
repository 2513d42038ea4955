"""A laterally displaced feed in the body-of-revolution solver: its Huygens sheet as a sum of
azimuthal orders e^{imφ}, one Meep run per order, and the aperture field rebuilt as their sum.

The feed is the on-axis feed's pattern moved to (x, y) = (0, y_f) in the plane of its focus, its axis
still along +z and its E along x (φ = 0 of the runner; a displacement along y scans in the H-plane, the
meridional plane the GO trace draws). Its tangential E and H on the sheet plane are sampled on rings and
split into orders by FFT over φ (:func:`sheet_harmonics`). The orders kept are |m| ≤ M with M the
smallest for which the truncated sum rebuilds the sheet's co-polar field over r ≤ R + 1 λ to a relative
error ≤ ``ORDER_TOLERANCE`` (0.3°, 0.04 dB, below the sheet's own 0.6° p-p; the power the dropped
orders carry is reported beside it).
A body of revolution maps the order-m solution to the order −m one under the mirror φ → −φ:
(Er, Eφ, Hr, Hφ) → (Er, −Eφ, −Hr, Hφ). When the sheet's order −m equals s_m times that mirror of its
order m (checked here to ``SYMMETRY_TOLERANCE``: it holds for a linearly polarized feed displaced in a
symmetry plane), only m ≥ 0 run and the order −m result is s_m·(Er, −Eφ) of the order m one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import trapezoid
from scipy.optimize import minimize

from antenna_cad.fullwave.runner import domain, feed_pattern

N_PHI = 256                  # ring samples (orders up to ±N_PHI/2; the kept ones are checked far below)
TABLE_PER_PX = 4             # sheet table samples per grid cell (linear interpolation in the runner)
ORDER_TOLERANCE = 5e-3       # relative error of the truncated co-polar sheet field (0.3°, 0.04 dB)
SYMMETRY_TOLERANCE = 1e-9
NEGLIGIBLE_POWER = 1e-12     # an order carrying less than this share of the sheet power is not run
MIRROR = np.array([1, -1, -1, 1])        # (Er, Eφ, Hr, Hφ) under φ → −φ
PHI = 2 * np.pi * np.arange(N_PHI) / N_PHI


def displaced_feed_xy(x, y, dz, feed_y: float, k: float, pattern: str, q: float):
    """Cartesian (Ex, Ey, Hx, Hy) of the x-polarized feed at (0, feed_y), axis +z, at points (x, y) an
    axial distance dz > 0 away (η0 = 1, time e^{−iωt}): E = g·(cos φ' F_E θ̂' − sin φ' F_H φ̂'),
    H = R̂ × E = g·(cos φ' F_E φ̂' + sin φ' F_H θ̂'), primes in the feed's frame (as runner.feed_fields)."""
    X, Y = np.asarray(x, float), np.asarray(y, float) - feed_y
    rho = np.hypot(X, Y)
    R = np.hypot(rho, dz)
    theta, phi = np.arctan2(rho, dz), np.arctan2(Y, X)
    fe, fh = feed_pattern(theta, pattern, q)
    g = np.exp(1j * k * R) / R
    ct, cp, sp = np.cos(theta), np.cos(phi), np.sin(phi)
    a_theta, a_phi = cp * fe * g, -sp * fh * g              # E = a_θ θ̂' + a_φ φ̂'
    b_theta, b_phi = sp * fh * g, cp * fe * g               # H = b_θ θ̂' + b_φ φ̂'
    return (a_theta * ct * cp - a_phi * sp, a_theta * ct * sp + a_phi * cp,
            b_theta * ct * cp - b_phi * sp, b_theta * ct * sp + b_phi * cp)


def to_cylindrical(ex, ey, hx, hy, phi):
    """(Er, Eφ, Hr, Hφ) about the lens axis at azimuth φ."""
    c, s = np.cos(phi), np.sin(phi)
    return np.array([ex * c + ey * s, -ex * s + ey * c, hx * c + hy * s, -hx * s + hy * c])


@dataclass(frozen=True)
class Harmonics:
    """The sheet's (Er, Eφ, Hr, Hφ) on rings ``r_mm`` by order: ``spectrum[:, :, m % N_PHI]`` is the
    coefficient c_m of f(φ) = Σ c_m e^{imφ}, shape (4, len(r_mm), N_PHI)."""
    r_mm: np.ndarray
    spectrum: np.ndarray

    def coeff(self, m: int) -> np.ndarray:
        return self.spectrum[:, :, m % N_PHI]

    def field(self, orders=None) -> np.ndarray:
        """(4, len(r), N_PHI) on φ_j = 2πj/N_PHI, rebuilt from ``orders`` (all by default)."""
        spec = self.spectrum
        if orders is not None:
            spec = np.zeros_like(spec)
            idx = [m % N_PHI for m in orders]
            spec[:, :, idx] = self.spectrum[:, :, idx]
        return np.fft.ifft(spec, axis=-1) * N_PHI


def sheet_harmonics(r_mm: np.ndarray, dz_mm: float, feed_y_mm: float, wavelength_mm: float, pattern: str,
                    q: float) -> Harmonics:
    """Orders −N_PHI/2 < m < N_PHI/2 of the displaced feed's sheet fields on rings of radius ``r_mm``."""
    rr, pp = np.meshgrid(r_mm, PHI, indexing="ij")
    xy = displaced_feed_xy(rr * np.cos(pp), rr * np.sin(pp), dz_mm, feed_y_mm, 2 * np.pi / wavelength_mm,
                           pattern, q)
    return Harmonics(np.asarray(r_mm, float), np.fft.fft(to_cylindrical(*xy, pp), axis=-1) / N_PHI)


def order_power(h: Harmonics, r_max_mm: float) -> np.ndarray:
    """Power each order carries through the sheet within r ≤ r_max, 2π ∫ Re(Er Hφ* − Eφ Hr*) r dr,
    indexed like the spectrum (order m at m % N_PHI)."""
    sel = h.r_mm <= r_max_mm
    c, r = h.spectrum[:, sel], h.r_mm[sel]
    flux = np.real(c[0] * np.conj(c[3]) - c[1] * np.conj(c[2]))
    return 2 * np.pi * trapezoid(flux * r[:, None], r, axis=0)


def copolar(f: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Ex = Er cos φ − Eφ sin φ of (Er, Eφ, ...) arrays shaped (.., r, φ)."""
    return f[0] * np.cos(phi) - f[1] * np.sin(phi)


@dataclass(frozen=True)
class OrderChoice:
    orders: tuple[int, ...]               # the orders the sum keeps, −M..M (negligible ones dropped)
    runs: tuple[int, ...]                 # the orders Meep runs
    mirror: dict[int, complex]            # order −m = s_m · mirror(order m), for m in runs
    sheet_error: float                    # max relative error of the truncated co-polar sheet field
    power_fraction: float                 # share of the sheet power the kept orders carry
    symmetry_residual: float              # worst relative mismatch of the mirror relation


def choose_orders(h: Harmonics, r_max_mm: float) -> OrderChoice:
    """The smallest M (≥ 1) whose orders |m| ≤ M rebuild the co-polar sheet field over r ≤ r_max to
    ``ORDER_TOLERANCE``; the mirror relation between m and −m, checked per order."""
    sel = h.r_mm <= r_max_mm
    sub = Harmonics(h.r_mm[sel], h.spectrum[:, sel])
    exact = copolar(sub.field(), PHI)
    power = order_power(h, r_max_mm)
    total = power.sum()
    for M in range(1, N_PHI // 4):
        kept = [m for m in range(-M, M + 1) if abs(power[m % N_PHI]) > NEGLIGIBLE_POWER * total]
        error = float(np.max(np.abs(copolar(sub.field(kept), PHI) - exact) / np.abs(exact)))
        if error <= ORDER_TOLERANCE:
            break
    else:
        raise ValueError(f"the displaced feed's sheet needs more than {N_PHI // 4} azimuthal orders")
    mirror, residual = {}, 0.0
    for m in (m for m in kept if m > 0 and -m in kept):
        image, target = MIRROR[:, None] * h.coeff(m), h.coeff(-m)
        s = complex(np.vdot(image, target) / np.vdot(image, image))
        residual = max(residual, float(np.linalg.norm(target - s * image) / np.linalg.norm(target)))
        mirror[m] = s
    runs = tuple(m for m in kept if m >= 0 or -m not in mirror) if residual <= SYMMETRY_TOLERANCE else tuple(kept)
    return OrderChoice(tuple(kept), runs, mirror if residual <= SYMMETRY_TOLERANCE else {}, error,
                       float(sum(power[m % N_PHI] for m in kept) / total), residual)


def order_decks(deck: dict, feed_y_mm: float) -> tuple[list[dict], OrderChoice]:
    """The runner's decks of the displaced feed, one per order Meep runs, from the on-axis ``deck``
    (same lens, domain and resolution): its sheet tabulated (``sheet``: r in λ, re/im of Er, Eφ, Hr,
    Hφ of order m), starting |m| + 1 cells off the axis for |m| > 1 (Meep zeroes those fields there,
    and a source on the axis of such an order can go unstable)."""
    d = domain(deck)
    lam, res = d["lam"], d["res"]
    r = np.arange(0.0, d["sr"] + 0.5 / res, 1.0 / (TABLE_PER_PX * res)) * lam
    feed = deck["feed"]
    h = sheet_harmonics(r, deck["sheet_z_mm"] - feed["z_mm"], feed_y_mm, lam, feed["pattern"], feed["q"])
    choice = choose_orders(h, deck["r_max_mm"])
    decks = []
    for m in choice.runs:
        keep = r >= ((abs(m) + 1) / res * lam if abs(m) > 1 else 0.0)
        c = h.coeff(m)[:, keep]
        table = {"r_lambda": np.round(r[keep] / lam, 9).tolist()}
        table |= {name: [np.round(c[i].real, 12).tolist(), np.round(c[i].imag, 12).tolist()]
                  for i, name in enumerate(("er", "ep", "hr", "hp"))}
        decks.append(deck | {"m": int(m), "feed": feed | {"y_mm": float(feed_y_mm)}, "sheet": table})
    return decks, choice


def order_fields(choice: OrderChoice, results: list[dict]) -> dict[int, np.ndarray]:
    """Order m → (Er, Eφ) on the aperture plane for every kept order, the mirrored ones derived."""
    out = {m: np.array([res["er"], res["ep"]]) for m, res in zip(choice.runs, results)}
    for m, s in choice.mirror.items():
        out[-m] = s * MIRROR[:2, None] * out[m]
    return out


def aperture_copolar(r_mm: np.ndarray, fields: dict[int, np.ndarray], x_mm, y_mm) -> np.ndarray:
    """Ex at points (x, y) of the aperture plane: Σ_m (Er_m cos φ − Eφ_m sin φ) e^{imφ}, the orders
    interpolated in r."""
    x, y = np.asarray(x_mm, float), np.asarray(y_mm, float)
    rho, phi = np.hypot(x, y), np.arctan2(y, x)
    total = np.zeros(rho.shape, complex)
    for m, (er, ep) in fields.items():
        e_r = np.interp(rho, r_mm, er.real) + 1j * np.interp(rho, r_mm, er.imag)
        e_p = np.interp(rho, r_mm, ep.real) + 1j * np.interp(rho, r_mm, ep.imag)
        total += (e_r * np.cos(phi) - e_p * np.sin(phi)) * np.exp(1j * m * phi)
    return total


@dataclass(frozen=True)
class TiltedStats:
    p2p_deg: float
    rms_deg: float
    beam_deg: float              # beam direction in the scan (y–z) plane, from the removed tilt
    phase_efficiency_db: float
    k_xy: tuple[float, float]    # the removed tilt (rad/mm)


def tilt_removed(field: np.ndarray, x, y, k_xy) -> np.ndarray:
    """Phase (deg) of ``field`` with the tilt e^{i(kx x + ky y)} and the mean phase removed."""
    z = field * np.exp(-1j * (k_xy[0] * np.asarray(x) + k_xy[1] * np.asarray(y)))
    return np.degrees(np.angle(z * np.conj(np.sum(z))))


def tilted_stats(field: np.ndarray, x, y, wavelength_mm: float, guess_sin: float) -> TiltedStats:
    """Statistics of an aperture field sampled uniformly on points (x, y) (area weights equal): the tilt
    is the one that maximizes |Σ E e^{−i(kx x + ky y)}| (the beam peak; for small residuals the
    |E|-weighted least-squares linear phase), from a start at ky = k0·guess_sin; then p-p, RMS about the
    mean, beam angle arcsin(ky/k0) and phase efficiency |Σ E e^{−ik·x}|² / (Σ|E|)²."""
    k0 = 2 * np.pi / wavelength_mm

    def peak(kv):
        return -np.abs(np.sum(field * np.exp(-1j * (kv[0] * x + kv[1] * y))))
    span = np.max(np.hypot(x, y))
    grid = k0 * guess_sin + np.linspace(-2, 2, 41) * np.pi / span
    start = grid[np.argmin([peak((0.0, g)) for g in grid])]
    best = minimize(peak, np.array([0.0, start]), method="Nelder-Mead",
                    options={"xatol": 1e-7 / span, "fatol": 1e-12 * np.sum(np.abs(field)), "maxiter": 400})
    kx, ky = (float(v) for v in best.x)
    ph = tilt_removed(field, x, y, (kx, ky))
    rms = float(np.sqrt(np.mean((ph - ph.mean()) ** 2)))
    eff = best.fun ** 2 / np.sum(np.abs(field)) ** 2
    return TiltedStats(float(np.ptp(ph)), rms, float(np.degrees(np.arcsin(np.clip(ky / k0, -1, 1)))),
                       float(10 * np.log10(eff)), (kx, ky))
