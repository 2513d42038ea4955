"""Constants and small vector/check helpers of the slot-array synthesis (seed-003)."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError


C_MM_GHZ = 299.792458  # speed of light, mm·GHz (λ0[mm] = C_MM_GHZ / f[GHz])
N_SIGMA_RAYS = 50       # rays for the RMS path error σ, seed-003 §3.3 eq. (2.7)
FEED_RMS_WARN = 1 / 16  # λ; RMS slot-phase aberration of a feed above this is reported (warn)

LAYOUTS = ("longitudinal_4", "longitudinal_pair", "transverse_3")
TAPER_LAWS = ("sin", "exp", "cos_pedestal", "uniform")
BEAMFORMERS = ("single_mirror", "bifocal_two_mirror", "bifocal_mirror_lens", "trifocal_two_mirror",
               "trifocal_mirror_lens")


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _normal_from_slope(slope: np.ndarray) -> np.ndarray:
    s = np.asarray(slope, dtype=float)
    return _unit(np.stack([-s, np.ones_like(s)], axis=-1))


def _slope_from_normal(nv: np.ndarray) -> np.ndarray:
    return -nv[..., 0] / nv[..., 1]


def _lower(name: str, value: float, limit: float, unit: str, what: str,
           warn_margin: float = 0.0) -> Check:
    """Pass when ``value >= limit + warn_margin``, warn inside the margin, fail below ``limit``."""
    if value < limit:
        status = "fail"
    elif value < limit + warn_margin:
        status = "warn"
    else:
        status = "pass"
    return Check(name, status, float(value), float(limit), unit,
                 f"{what}: {value:.4g} {unit} (minimum {limit:.4g} {unit})")


def raise_on_fail(checks: Sequence[Check], fields: dict[str, str] | None = None) -> None:
    """Raise :class:`DesignError` for the first failed check (field from ``fields[name]``)."""
    fields = fields or {}
    for c in checks:
        if c.status == "fail":
            raise DesignError(fields.get(c.name, c.name), c.message)
