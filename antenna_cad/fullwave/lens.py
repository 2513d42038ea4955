"""A lens of revolution as the full-wave and fast models see it: the synthesized faces, the
stepped sections, the feed on the axis; and the two phase models of stepped − ideal built on it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from antenna_cad.fullwave.deck import ideal_parts, make_deck, slab_parts
from antenna_cad.fullwave.fastmodel import fast_phase, multislice_field
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

    def foam_mm(self, variant: str, z0: float, z1: float, r: np.ndarray) -> np.ndarray:
        """Foam along z between the planes z0 < z1 at radius r (mm): the ideal lens's between its faces
        (r ≤ radius), a stepped section's in the sheets whose cell at r is dielectric."""
        r = np.asarray(r, float)
        if variant == "ideal":
            rc = np.minimum(r, self.radius_mm)
            length = np.minimum(z1, self.back_z(rc)) - np.maximum(z0, self.front_z(rc))
            return np.where(r <= self.radius_mm, np.clip(length, 0.0, None), 0.0)
        s = self.sections[variant]
        overlap = np.clip(np.minimum(z1, s.z_edges[1:]) - np.maximum(z0, s.z_edges[:-1]), 0.0, None)
        return overlap @ s.material[:, np.searchsorted(s.y_breaks, r)]

    def z_span_mm(self, variant: str) -> tuple[float, float]:
        """The foremost and hindmost z of ``variant``'s foam."""
        if variant != "ideal":
            return float(self.sections[variant].z_edges[0]), float(self.sections[variant].z_edges[-1])
        r = np.linspace(0.0, self.radius_mm, 401)
        return float(np.min(self.front_z(r))), float(np.max(self.back_z(r)))

    def fast_field(self, variant: str, z_end_mm: float, pattern: str = "dipole", q: float = 1.0):
        """(r, E) of ``variant`` on the plane ``z_end_mm`` behind it by the multi-slice fast model
        (:func:`antenna_cad.fullwave.fastmodel.multislice_field`), the feed's ``pattern`` as the
        full-wave stage's."""
        z0, z1 = self.z_span_mm(variant)
        return multislice_field(lambda a, b, r: self.foam_mm(variant, a, b, r), z0, z1, z_end_mm, self.feed_z_mm,
                                self.radius_mm, self.n, self.wavelength_mm, pattern, q)

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
