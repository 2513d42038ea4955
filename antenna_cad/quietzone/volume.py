"""The quiet-zone cylinder, its planes, and the field on them from GO and from the fast model.

Zone (``design.test_zone``): diameter (default the AUT's: the spec's, or the caller's default AUT),
near face ``distance_mm`` behind the back of the stack (default the AUT's distance), depth away from
the lens (default one zone diameter, at least 2 λ), and the planes scanned across it: at least
``MIN_PLANES``, spaced by at most half the period of the axial caustic (at most ``MAX_PLANES``). That
caustic is the rim's (and the ring edges') diffraction arriving on the axis of a body of revolution:
the edge wave from radius a and the direct wave differ in path by √(z² + a²) − z, so along z the
pattern repeats every λ / (1 − z/√(z² + a²)) — shortest near the lens and for the outermost edge
(a = the lens radius).

Fields on a plane z behind the stack:
* GO: each ray straight on from its exit point (amplitude unchanged, as the seed's model, §4.4;
  no diffraction, so no caustic and no rim wave);
* the fast model: each variant (the ideal lens, a stepped section) carried from its feed through its
  own foam slice by slice (:func:`antenna_cad.fullwave.fastmodel.multislice_field`: the feed's
  spill-over beside the rim, the rim's and every ring edge's diffraction where they are) to the plane
  at the back of the stack, then on by the exact angular spectrum of a body of revolution
  (:func:`antenna_cad.radiation.testzone.propagate_bor_planes`) to each plane (:func:`fast_fields`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from antenna_cad.radiation.testzone import propagate_bor_planes

MIN_PLANES = 5
MAX_PLANES = 200            # the spec's own bound on ``planes``: a deep zone is scanned no finer than this
MIN_DEPTH_WAVELENGTHS = 2.0
SAMPLES_PER_WAVELENGTH = 20      # radial samples of the propagated field


@dataclass(frozen=True)
class Zone:
    """The cylinder; planes as distances behind the back of the stack."""
    diameter_mm: float
    distance_mm: float
    depth_mm: float
    planes_mm: np.ndarray
    amplitude_db: float
    phase_deg: float
    cross_pol_db: float | None

    def limits_text(self) -> str:
        xp = f", cross-pol ≤ {self.cross_pol_db:g} dB" if self.cross_pol_db is not None else ""
        return f"±{self.amplitude_db:g} dB, ±{self.phase_deg:g}°{xp}"


def caustic_period_mm(edge_radius_mm: float, z_mm: float, wavelength_mm: float) -> float:
    """Period along the axis of the interference of an edge wave from radius a with the direct wave
    at distance z (module docstring)."""
    return wavelength_mm / (1.0 - z_mm / math.hypot(z_mm, edge_radius_mm))


def zone_from(spec, aut_diameter_mm: float, aut_distance_mm: float, lens_radius_mm: float,
              wavelength_mm: float) -> Zone:
    """The zone of ``spec`` (``design.test_zone``) with its defaults (module docstring); the AUT is the
    spec's, or the caller's default one."""
    diameter = spec.diameter_mm if spec.diameter_mm is not None else aut_diameter_mm
    distance = spec.distance_mm if spec.distance_mm is not None else aut_distance_mm
    depth = spec.depth_mm if spec.depth_mm is not None else max(diameter, MIN_DEPTH_WAVELENGTHS * wavelength_mm)
    if spec.planes is not None:
        n = spec.planes
    else:
        spacing = caustic_period_mm(lens_radius_mm, max(distance, wavelength_mm), wavelength_mm) / 2
        n = min(MAX_PLANES, max(MIN_PLANES, math.ceil(depth / spacing) + 1))
    return Zone(diameter, distance, depth, distance + np.linspace(0.0, depth, n), spec.amplitude_db, spec.phase_deg,
                spec.cross_pol_db)


def radii_mm(radius_mm: float, wavelength_mm: float) -> np.ndarray:
    """Uniform radii 0 … radius at ``SAMPLES_PER_WAVELENGTH`` per λ."""
    return np.linspace(0.0, radius_mm, int(SAMPLES_PER_WAVELENGTH * radius_mm / wavelength_mm) + 2)


@dataclass(frozen=True)
class Rays:
    """Exit rays of a body of revolution (the y ≥ 0 half of a meridional trace) on the plane z_mm:
    position y, direction (z, y) components, amplitude and optical path (mm)."""
    y_mm: np.ndarray
    dz: np.ndarray
    dy: np.ndarray
    amplitude: np.ndarray
    path_mm: np.ndarray
    z_mm: float

    def field_at(self, z_mm: float, wavelength_mm: float) -> tuple[np.ndarray, np.ndarray]:
        """GO field on the plane ``z_mm``: (r increasing, complex field), each ray carried straight on (one
        that has crossed the axis arrives at radius |y|)."""
        t = (z_mm - self.z_mm) / self.dz
        y, path = np.abs(self.y_mm + t * self.dy), self.path_mm + t
        o = np.argsort(y)
        return y[o], self.amplitude[o] * np.exp(1j * 2 * np.pi / wavelength_mm * path[o])


def propagated(r_mm: np.ndarray, field: np.ndarray, wavelength_mm: float, distances_mm: np.ndarray,
               rho_mm: np.ndarray) -> np.ndarray:
    """[plane, ρ] the body-of-revolution field E(r) after each distance (angular spectrum)."""
    return propagate_bor_planes(r_mm, field, wavelength_mm, distances_mm, rho_mm)


def fast_fields(lens, z_ref_mm: float, distances_mm: np.ndarray, rho_mm: np.ndarray,
                variants: list[str]) -> dict[str, np.ndarray]:
    """[plane, ρ] the fast model's field of each variant (``ideal`` or a stepped section) of ``lens``
    (:class:`antenna_cad.fullwave.lens.RevolvedLens`) on the planes ``distances_mm`` behind ``z_ref_mm``
    (the back of the stack): the multi-slice field on that plane (``lens.fast_field``) propagated on by
    the exact angular spectrum of a body of revolution."""
    lam = lens.wavelength_mm
    out = {}
    for name in variants:
        r, e = lens.fast_field(name, z_ref_mm)
        grid = radii_mm(float(r[-1]), lam)
        out[name] = propagated(grid, np.interp(grid, r, e.real) + 1j * np.interp(grid, r, e.imag), lam,
                               distances_mm, rho_mm)
    return out


def stack_ratios(lens, z_ref_mm: float, distances_mm: np.ndarray, rho_mm: np.ndarray) -> dict[str, np.ndarray]:
    """[plane, ρ] each stepped section's fast-model field over the ideal lens's: the stack's own factor
    (what sanding removes; the rim's own diffraction divides out)."""
    fields = fast_fields(lens, z_ref_mm, distances_mm, rho_mm, ["ideal", *lens.sections])
    return {name: fields[name] / fields["ideal"] for name in lens.sections}
