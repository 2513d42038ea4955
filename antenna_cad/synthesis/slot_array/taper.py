"""Leaky-wave amplitude taper, eq. (1.1) corrected (seed-003 §3.2, erratum §7.1)."""

from __future__ import annotations

import numpy as np

from antenna_cad.synthesis.checks import DesignError
from antenna_cad.synthesis.slot_array.common import TAPER_LAWS


def taper_alpha_np_per_m(y_mm, length_mm: float, law: str = "sin", eta: float = 0.9,
                         pedestal: float = 0.3):
    """Leaky-wave attenuation α(y) (Np/m) that radiates a prescribed |A(y)|² (seed-003 §3.2).

    α = ½|A|² / [η⁻¹ ∫₀ᴸ|A|² − ∫₀ʸ|A|²], η = radiated fraction (P_L = load power; erratum §7.1).
    Laws: ``sin`` |A|² = sin(πy/L) (Table 1.1, closed form as in the digest); ``cos_pedestal``
    |A| = pedestal + (1 − pedestal)·sin(πy/L) (Table 3.1 shape; pedestal not given in the seed);
    ``exp``/``uniform``: constant α = −ln(1 − η)/(2L), exponential field decay.
    """
    y = np.asarray(y_mm, dtype=float)
    L = float(length_mm)
    if not 0.0 < eta < 1.0:
        raise DesignError("slots.taper.eta", f"must be in (0, 1) (got {eta})")
    if law == "sin":
        num = np.sin(np.pi * y / L)
        den = (2 * L / np.pi) / eta - (L / np.pi) * (1.0 - np.cos(np.pi * y / L))
    elif law == "cos_pedestal":
        q = pedestal
        g = lambda u: (q * q * u + 2 * q * (1 - q) * (L / np.pi) * (1 - np.cos(np.pi * u / L))
                       + (1 - q) ** 2 * (u / 2 - L / (4 * np.pi) * np.sin(2 * np.pi * u / L)))
        num = (q + (1 - q) * np.sin(np.pi * y / L)) ** 2
        den = g(L) / eta - g(y)
    elif law in ("exp", "uniform"):
        return np.full_like(y, -np.log(1.0 - eta) / (2 * L) * 1e3)
    else:
        raise DesignError("slots.taper.law", f"unknown law {law!r} (use one of {TAPER_LAWS})")
    return 0.5e3 * num / den


def slot_length_from_alpha_mm(alpha_np_per_m, a0: float = 0.0078, b0: float = 2.01):
    """Invert the cell fit α(L1) = a0·exp(b0·L1) (28 GHz, set 1; seed-003 §3.2)."""
    return np.log(np.asarray(alpha_np_per_m, dtype=float) / a0) / b0


def taper_slot_lengths_mm(n_cells: int, period_mm: float, length_mm: float, law: str = "sin",
                          eta: float = 0.9, a0: float = 0.0078, b0: float = 2.01,
                          pedestal: float = 0.3) -> np.ndarray:
    """L1 of every cell, evaluated at the cell centres y = (m + ½)p (seed-003 §3.2, R3)."""
    y = (np.arange(n_cells) + 0.5) * period_mm
    return slot_length_from_alpha_mm(taper_alpha_np_per_m(y, length_mm, law, eta, pedestal), a0, b0)
