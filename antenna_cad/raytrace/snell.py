"""Vector Snell refraction and mirror reflection, vectorized over rays (2-D or 3-D).

Vector form of Snell's law used throughout the seeds' constructions (seed-000 §2.7:
``n_a·d_a − n_b·d_b ∥ N``), written for arrays of unit directions.
"""

from __future__ import annotations

import numpy as np


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def refract(direction: np.ndarray, normal: np.ndarray, n_from: float | np.ndarray,
            n_to: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Refract unit ``direction`` at a surface with ``normal`` (either orientation).

    Returns ``(transmitted, ok)``: unit transmitted directions and a boolean mask that is
    False where the ray is totally internally reflected (transmitted is NaN there).
    """
    d = _unit(np.asarray(direction, dtype=float))
    nrm = _unit(np.asarray(normal, dtype=float))
    cos_i = -np.sum(d * nrm, axis=-1, keepdims=True)
    nrm = np.where(cos_i < 0.0, -nrm, nrm)          # make the normal face the incoming ray
    cos_i = np.abs(cos_i)
    eta = np.asarray(n_from, dtype=float) / np.asarray(n_to, dtype=float)
    eta = np.reshape(eta, eta.shape + (1,)) if np.ndim(eta) else eta
    k = 1.0 - eta**2 * (1.0 - cos_i**2)
    ok = (k >= 0.0)[..., 0]
    t = eta * d + (eta * cos_i - np.sqrt(np.where(k >= 0.0, k, np.nan))) * nrm
    return t, ok


def reflect(direction: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Mirror-reflect unit ``direction`` at a surface with ``normal`` (either orientation)."""
    d = _unit(np.asarray(direction, dtype=float))
    nrm = _unit(np.asarray(normal, dtype=float))
    return d - 2.0 * np.sum(d * nrm, axis=-1, keepdims=True) * nrm


def incidence_angle(direction: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Angle (rad) between a ray and the surface normal, in [0, π/2]."""
    d = _unit(np.asarray(direction, dtype=float))
    nrm = _unit(np.asarray(normal, dtype=float))
    return np.arccos(np.clip(np.abs(np.sum(d * nrm, axis=-1)), 0.0, 1.0))


def transmission(cos_i: np.ndarray, cos_t: np.ndarray, n_from: float | np.ndarray,
                 n_to: float | np.ndarray, polarisation: str) -> np.ndarray:
    """Fresnel amplitude transmission coefficient, seed-000 §4.4 (2.20)–(2.22) with Z = Z0/n
    (the printed τ∥ (2.20) repeats cos φ; (2.22) is the right form):
    ``perp``: 2n₁cosφ/(n₁cosφ + n₂cosθ), ``par``: 2n₁cosφ/(n₁cosθ + n₂cosφ)."""
    if polarisation == "perp":
        return 2 * n_from * cos_i / (n_from * cos_i + n_to * cos_t)
    return 2 * n_from * cos_i / (n_from * cos_t + n_to * cos_i)
