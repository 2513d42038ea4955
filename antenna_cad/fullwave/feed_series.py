"""Far field of a feed over a multilayer sphere as the series of seed-002 §2.4.5–§2.4.6: the Huygens
element of eq. (2), the weights I_n of an extended feed (a radiating cap), and the gain of the lens
with its real feed from the radiated power itself.

Seed-002's convention (time e^{iωt}, far field e^{−ikr}, outgoing ξ_n^{(2)} = j_n − i y_n, spherical
Bessel functions): the sphere's E- and M-type coefficients are a_n^e = −conj(a_n), a_n^m = −conj(b_n)
of the Bohren–Huffman coefficients (e^{−iωt}, ``scattnlay``) of the same sphere. The seed's feed lies
on the axis at ϑ = 0, radius b, and radiates toward the sphere, so the lens's beam leaves at ϑ = π;
the functions here take the angle from the beam, θ = π − ϑ, and the feed's electric moment lies in
the plane φ = 0 (the E-plane). With a Huygens element I_m = W0·I_e the bracket of (2) over W0·I_e is

    E_θ/cos φ = (1/x)·A − i·B,   x = kb,
    A = Σ C_n^ee·2τ_n + 2x·i·Σ C_n^me·π_n,    B = Σ C_n^mm·2τ_n − (2i/x)·Σ C_n^em·π_n,

τ_n = dP_n^1/dϑ and π_n = P_n^1/sin ϑ (the digest's {P_n^2 − n(n+1)P_n^0} = 2τ_n), c_n =
(2n+1)/(n(n+1))·i^n, C_n^ee = c_n χ'^(e)_n, C_n^me = c_n ζ'^(e)_n, C_n^em = c_n χ'^(m)_n, C_n^mm =
c_n ζ'^(m)_n, with the superscripts as the digest reconstructs them. E_φ/(−sin φ) is the same with
τ_n ↔ π_n. The electric half alone is a short dipole. An extended feed multiplies every χ' and ζ' by
its I_n (§2.4.6). Printed as it is, the series is the exact field: the tests check it against the
free-space Huygens element ((1 + cos θ)/2, directivity 3) and against the sphere's near field in
plane waves by reciprocity (``scattnlay``), 1e-4.
"""

from __future__ import annotations

import numpy as np
from scipy.special import spherical_jn, spherical_yn

SEED_W0 = 120 * np.pi          # W0 of seed-002 (Ω): I_m = W0·I_e for a Huygens element


def n_max(x: float) -> int:
    """Terms of the series for the largest size parameter x = kb (digest §2.4.4)."""
    return int(np.ceil(x + 4 * x ** (1 / 3) + 2))


def angular(n: int, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """π_n = P_n^1/sin θ and τ_n = dP_n^1/dθ, rows n = 1 … n (the Bohren–Huffman recursions)."""
    mu = np.cos(theta)
    pi = np.zeros((n + 1, len(mu)))
    tau = np.zeros_like(pi)
    pi[1] = 1.0
    for k in range(1, n + 1):
        if k > 1:
            pi[k] = ((2 * k - 1) * mu * pi[k - 1] - k * pi[k - 2]) / (k - 1)
        tau[k] = k * mu * pi[k] - (k + 1) * pi[k - 1]
    return pi[1:], tau[1:]


def seed_coefficients(x_layers, m_layers, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(a_n^e, a_n^m), n = 1 … n, of the multilayer sphere in the seed's convention from the
    Bohren–Huffman a_n, b_n (``scattnlay``): size parameters k·r_i and relative indices (e^{−iωt})."""
    from antenna_cad.fullwave.mie import quiet_stdout
    from scattnlay import scattcoeffs
    with quiet_stdout():
        _, an, bn = scattcoeffs(np.asarray(x_layers, float), np.asarray(m_layers, complex), nmax=n)
    return -np.conj(np.asarray(an)[:n]), -np.conj(np.asarray(bn)[:n])


def radial_terms(x: float, a_e: np.ndarray, a_m: np.ndarray, weights=None):
    """(χ'^(e), ζ'^(e), χ'^(m), ζ'^(m)) of (2) at the feed radius, x = kb, each times the extended
    feed's I_n when given: χ' = [x j_n]' + [x ξ_n]'·a, ζ' = j_n + ξ_n·a (d/db (b f(kb)) = [x f(x)]')."""
    n = np.arange(1, len(a_e) + 1)
    j, dj = spherical_jn(n, x), spherical_jn(n, x, derivative=True)
    y, dy = spherical_yn(n, x), spherical_yn(n, x, derivative=True)
    xi, dxi = j - 1j * y, dj - 1j * dy
    dxj, dxxi = j + x * dj, xi + x * dxi
    w = np.ones(len(n)) if weights is None else np.asarray(weights)
    return (w * (dxj + dxxi * a_e), w * (j + xi * a_m), w * (dxj + dxxi * a_m), w * (j + xi * a_e))


def far_field(x: float, a_e, a_m, theta: np.ndarray, electric: float = 1.0, magnetic: float = 1.0,
              weights=None) -> tuple[np.ndarray, np.ndarray]:
    """E-plane E_θ(θ, φ = 0) and H-plane E_φ(θ, φ = 90°)·(−1) of (2) against the angle θ from the beam,
    in units of the bracket over W0·I_e; ``electric``/``magnetic`` scale the two halves (1, 1: the
    Huygens element; 1, 0: the short dipole); ``weights``: an extended feed's I_n."""
    n = np.arange(1, len(a_e) + 1)
    c = (2 * n + 1) / (n * (n + 1)) * 1j ** n
    chi_e, zeta_e, chi_m, zeta_m = (c * t for t in radial_terms(x, a_e, a_m, weights))
    pi, tau = angular(len(n), np.pi - np.asarray(theta, float))          # the seed's ϑ = π − θ
    planes = []
    for t_e, p_e in ((tau, pi), (pi, tau)):         # E-plane, then τ ↔ π: the H-plane
        a = 2 * (chi_e @ t_e) + 2j * x * (zeta_e @ p_e)
        b = 2 * (zeta_m @ t_e) - 2j / x * (chi_m @ p_e)
        planes.append(electric * a / x - 1j * magnetic * b)
    return planes[0], planes[1]


def directivity(x: float, a_e, a_m, magnetic: float = 1.0, weights=None) -> float:
    """4π|E(beam)|² over the radiated power of the feed (Huygens, or the dipole for ``magnetic`` = 0)
    over the sphere: E_θ = A(θ) cos φ, E_φ = −B(θ) sin φ radiate π∫(|A|² + |B|²) d(cos θ), a
    polynomial of degree 2n in cos θ, integrated exactly by Gauss–Legendre."""
    u, w = np.polynomial.legendre.leggauss(len(a_e) + 2)
    e, h = far_field(x, a_e, a_m, np.concatenate([[0.0], np.arccos(u)]), 1.0, magnetic, weights)
    return float(4 * abs(e[0]) ** 2 / (w @ (np.abs(e[1:]) ** 2 + np.abs(h[1:]) ** 2)))


def cap_weights(n: int, theta0: float, f_afr=None, samples: int = 2001) -> np.ndarray:
    """I_n of a radiating cap of half-angle ϑ0 (seed-002 §2.4.6), n = 1 … n, with amplitude–phase
    distribution f_AFR(ϑ) (default uniform):
    I_n = −2π/(n(n+1))·∫_0^ϑ0 ((1 − cos ϑ)P_n^1(cos ϑ) − n(n+1) sin ϑ P_n^0(cos ϑ)) f(ϑ) dϑ,
    P_n^1 = sin ϑ·π_n (the phase of :func:`angular`); a point (ϑ0 → 0) gives I_n → the same for
    every n, the point feed."""
    t = np.linspace(0.0, theta0, samples)
    f = np.ones_like(t) if f_afr is None else np.asarray(f_afr(t), complex)
    pi, _ = angular(n, t)
    k = np.arange(1, n + 1)[:, None]
    legendre0 = np.array([np.polynomial.legendre.legval(np.cos(t), np.eye(n + 1)[i]) for i in range(1, n + 1)])
    integrand = ((1 - np.cos(t)) * np.sin(t) * pi - k * (k + 1) * np.sin(t) * legendre0) * f
    return -2 * np.pi / (k[:, 0] * (k[:, 0] + 1)) * np.trapezoid(integrand, t, axis=1)


def real_feed_weights(n: int, x: float, pattern, samples: int = 4001) -> np.ndarray:
    """I_n of a real feed with far-field amplitude ``pattern``(θ) (θ from its axis, toward the lens)
    at x = kb (seed-002 §2.4.6, up to the constant C/j_0), in the seed's ϑ = π − θ:
    I_n = ∫_0^π e^{ix cos ϑ} F/(1 − cos ϑ)·sin²ϑ·sqrt(1 + (x(1 − cos ϑ)/2)²)·P_n^1 dϑ
          / (n(n+1)·(i/(4π ω ε b)·d(b j_n)/db + (120π/4π)·j_n)·i^n),
    with 1/(ω ε0) = 120π/k: the denominator is 30·n(n+1)·(i[x j_n]'/x + j_n)·i^n. F must vanish
    at ϑ = 0 (behind the feed), where the integrand has 1/(1 − cos ϑ)."""
    t = np.linspace(0.0, np.pi, samples)[1:]
    f = np.asarray(pattern(np.pi - t), complex)
    pi, _ = angular(n, t)
    k = np.arange(1, n + 1)
    c = np.cos(t)
    kernel = np.exp(1j * x * c) * f / (1 - c) * np.sin(t) ** 3 * np.sqrt(1 + (x / 2 * (1 - c)) ** 2)
    j, dj = spherical_jn(k, x), spherical_jn(k, x, derivative=True)
    return np.trapezoid(kernel * pi, t, axis=1) / (30 * k * (k + 1) * (1j * (j + x * dj) / x + j) * 1j ** k)


def feed_gains_dbi(radii_mm, eps, wavelength_mm: float, feed_mm: float) -> dict[str, float]:
    """Directivity (dBi) of the layered sphere fed at radius ``feed_mm`` by the Huygens element and by
    the short dipole, from the series (2) and the power it radiates (for a lossless lens the gain;
    the dipole figure by reciprocity, 1.5·|E(focus)|², leaves the lens's reaction on the feed out)."""
    k = 2 * np.pi / wavelength_mm
    x = k * feed_mm
    a_e, a_m = seed_coefficients(k * np.asarray(radii_mm, float), np.sqrt(np.asarray(eps, complex)), n_max(x))
    return {name: float(10 * np.log10(directivity(x, a_e, a_m, magnetic))) for name, magnetic in (("huygens", 1.0),
                                                                                                 ("dipole", 0.0))}
