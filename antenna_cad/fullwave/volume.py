"""The full-wave field over the quiet zone: the DFT Er of one on-axis run recorded over the (r, z)
half-plane that spans the zone's depth (:mod:`antenna_cad.fullwave.runner`, ``volume_z_mm``), so that
one run gives every plane of the zone (compact ranges scan several planes across the depth).

A plane between two grid rows is read by linear interpolation of the field with the plane wave's
carrier e^{ik0z} taken out (what remains varies slowly along z), then put back."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class VolumeField:
    """Er on radii ``r_mm`` (from the axis) × planes ``z_mm`` (increasing, the lens's frame): ``field`` [r, z]."""
    r_mm: np.ndarray
    z_mm: np.ndarray
    field: np.ndarray
    wavelength_mm: float

    @classmethod
    def from_run(cls, out: dict) -> "VolumeField":
        """From a runner result that recorded the volume."""
        return cls(out["volume_r_mm"], out["volume_z_mm"], out["volume_er"], float(out["lambda_mm"]))

    def covers(self, z_mm: np.ndarray, radius_mm: float) -> bool:
        """Whether every plane ``z_mm`` and the radius lie within the recorded half-plane."""
        z = np.asarray(z_mm, float)
        return bool(z.min() >= self.z_mm[0] and z.max() <= self.z_mm[-1] and radius_mm <= self.r_mm[-1])

    def planes(self, z_mm: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """(r, E) on each plane z (module docstring)."""
        k = 2 * math.pi / self.wavelength_mm
        envelope = self.field * np.exp(-1j * k * self.z_mm)[None, :]
        out = []
        for z in np.asarray(z_mm, float):
            i = int(np.clip(np.searchsorted(self.z_mm, z) - 1, 0, len(self.z_mm) - 2))
            t = (z - self.z_mm[i]) / (self.z_mm[i + 1] - self.z_mm[i])
            out.append((self.r_mm, ((1 - t) * envelope[:, i] + t * envelope[:, i + 1]) * np.exp(1j * k * z)))
        return out
