"""A lens of revolution as the full-wave and fast models see it: the synthesized faces, the
stepped sections, the feed on the axis; and the two phase models of stepped − ideal built on it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from antenna_cad.fullwave.deck import ideal_parts, make_deck, slab_parts
from antenna_cad.fullwave.fastmodel import fast_phase
from antenna_cad.raytrace.trace2d import Slabs

C_MM_GHZ = 299.792458


@dataclass(frozen=True)
class RevolvedLens:
    """Faces z = front_z(r), back_z(r) (mm, r ≤ radius), εr, frequency and the on-axis feed's z;
    ``sections``: variant name → stepped section (``stepped``, ``fabricated``)."""
    front_z: Callable[[np.ndarray], np.ndarray]
    back_z: Callable[[np.ndarray], np.ndarray]
    radius_mm: float
    eps_r: float
    frequency_ghz: float
    feed_z_mm: float
    sections: dict[str, Slabs]

    @property
    def wavelength_mm(self) -> float:
        return C_MM_GHZ / self.frequency_ghz

    @property
    def n(self) -> float:
        return self.eps_r ** 0.5

    def parts(self, variant: str) -> list[dict]:
        if variant == "ideal":
            return ideal_parts(self.front_z, self.back_z, self.radius_mm, self.eps_r)
        return slab_parts(self.sections[variant], self.eps_r)

    def deck(self, variant: str, settings, field_map: bool = True,
             volume_z_mm: tuple[float, float] | None = None) -> dict:
        """The runner's deck of ``variant`` with the spec's ``verification`` settings; ``volume_z_mm``:
        the quiet zone's depth, recorded over (r, z)."""
        return make_deck(self.parts(variant), frequency_ghz=self.frequency_ghz,
                         resolution=settings.resolution_px_per_lambda, feed_z_mm=self.feed_z_mm,
                         feed_pattern=settings.feed_pattern, feed_q=settings.feed_q, radius_mm=self.radius_mm,
                         plane_offset_lambda=settings.plane_offset_lambda, field_map=field_map,
                         volume_z_mm=volume_z_mm)

    def excess_mm(self, variant: str, r: np.ndarray) -> np.ndarray:
        """Foam along z at radius r in the section (its y ≥ 0 half) minus the ideal lens's: Δd(r)."""
        s = self.sections[variant]
        cell = np.searchsorted(s.y_breaks, r)
        foam = (np.diff(s.z_edges)[:, None] * s.material[:, cell]).sum(axis=0)
        ideal = np.where(r <= self.radius_mm, self.back_z(r) - self.front_z(r), 0.0)
        return foam - ideal

    def plane_z_mm(self, plane_offset_lambda: float) -> float:
        z = max(float(np.max(s.z_edges)) for s in self.sections.values()) if self.sections else \
            float(np.max(self.back_z(np.linspace(0.0, self.radius_mm, 101))))
        return z + plane_offset_lambda * self.wavelength_mm

    def screen_z_mm(self) -> float:
        """Where the fast model puts its thin screen: the area-weighted mean front face."""
        r = np.linspace(0.0, self.radius_mm, 201)
        return float(np.average(self.front_z(r), weights=r + 1e-9))

    def fast_difference_deg(self, variant: str, plane_offset_lambda: float, r_obs: np.ndarray) -> np.ndarray:
        """Fast model of the phase ``variant`` − ideal on the aperture plane (deg) at radii r_obs;
        the screen sits at the mean front face."""
        distance = self.plane_z_mm(plane_offset_lambda) - self.screen_z_mm()
        return fast_phase(lambda x: self.excess_mm(variant, x), self.n, self.wavelength_mm, self.radius_mm,
                          distance, r_obs)
