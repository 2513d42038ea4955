"""A taper-cut stack as geometrical optics sees it: the faces are the polylines through the lens
profile at every sheet face (the cones of ``edge: taper`` in the meridional section). The radius
rises from the vertex to its largest node — the front polyline — and, for a lens whose radius falls
again behind its rim (the bifocal lens, seed-000 §3.2), falls from there to the back — the back
polyline; a lens whose radius stays at its largest (the collimator's back slab) keeps its own back
face. The fast model and full-wave take the cones from the fine sub-slab section
(:func:`antenna_cad.fabrication.section.stepped_section`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.raytrace.trace2d import Interface
from antenna_cad.verification import Table

PROFILE_SAMPLES = 20001     # radii on which the lens faces are sampled for the section radius
GAP_SAMPLES = 1025          # depths across a sheet at which the profile is held to its cone


def gap_mm(profile: np.ndarray, cone: tuple[float, float], z: tuple[float, float]) -> float:
    """Largest distance, in the meridional plane, from the (r, z) points ``profile`` to the cone
    line from (cone[0], z[0]) to (cone[1], z[1])."""
    a = np.array([cone[0], z[0]])
    d = np.array([cone[1], z[1]]) - a
    u = np.clip((profile - a) @ d / (d @ d), 0.0, 1.0)
    return float(np.max(np.linalg.norm(profile - a - u[:, None] * d, axis=1)))


def cone_gap_mm(cone: tuple[float, float], z: tuple[float, float], radius_at) -> float:
    """:func:`gap_mm` of the profile r = ``radius_at(z)`` (a scalar function) across the sheet."""
    zz = np.linspace(z[0], z[1], GAP_SAMPLES)
    return gap_mm(np.stack([[radius_at(x) for x in zz], zz], -1), cone, z)


def cone_table(layup: LayupPlan, radius_at) -> Table:
    """The layer table of a taper-cut layup whose lens radius at depth z is ``radius_at(z)``."""
    rows = tuple((s.label, round(s.z_min_mm, 3), round(s.z_max_mm, 3), *(round(r, 3) for r in s.cone_mm),
                  round(cone_gap_mm(s.cone_mm, (s.z_min_mm, s.z_max_mm), radius_at), 3)) for s in layup.sheets)
    return Table("layers", "Sheets (taper-cut)", ("sheet", "z min mm", "z max mm", "cone radius front mm",
                                                  "cone radius back mm", "largest gap to the profile mm"), rows,
                 caption="each rim is the cone through the lens profile at the sheet's two faces; gap: the "
                 "largest distance from the profile to the cone in the meridional section (no sanding)")


def _polyline(r: np.ndarray, z: np.ndarray, n_after: float) -> Interface:
    """z(|y|) through the nodes (r increasing; a vertical run dropped: it has no z(r))."""
    keep = np.concatenate([[True], np.diff(r) > 1e-9])
    r, z = r[keep], z[keep]
    slope = np.diff(z) / np.diff(r) if len(r) > 1 else np.zeros(1)

    def z_of_y(y):
        return np.interp(np.abs(np.asarray(y, float)), r, z)

    def dz_dy(y):
        y = np.asarray(y, float)
        k = np.clip(np.searchsorted(r, np.abs(y)) - 1, 0, len(slope) - 1)
        return np.sign(y) * slope[k]
    return Interface(z_of_y, dz_dy, float(n_after), float(np.median(z)))


@dataclass(frozen=True)
class Taper:
    """The cones of ``layup`` (every sheet taper-cut) of ``lens`` (:class:`antenna_cad.asbuilt.lens.Lens`)."""
    lens: object
    layup: LayupPlan

    def nodes(self, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """(r, z) of the cone polyline at every sheet face, vertex to back, z stretched by ``scale``
        about the first face (every sheet thicker)."""
        sheets = self.layup.sheets
        r = np.array([s.cone_mm[0] for s in sheets] + [sheets[-1].cone_mm[1]])
        z = np.array([s.z_min_mm for s in sheets] + [sheets[-1].z_max_mm])
        return r, z[0] + scale * (z - z[0])

    def _split(self, scale: float) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray] | None]:
        """(front nodes, back nodes or None): rising to the first largest node, falling from the last."""
        r, z = self.nodes(scale)
        top = r.max() - 1e-9
        first, last = int(np.argmax(r >= top)), len(r) - 1 - int(np.argmax(r[::-1] >= top))
        front = (r[:first + 1], z[:first + 1])
        return front, ((r[last:][::-1], z[last:][::-1]) if last < len(r) - 1 else None)

    def faces(self, n: float, scale: float = 1.0) -> tuple[Interface, ...]:
        """(front polyline, back face) with lens index n: the back polyline of a lens whose radius
        falls behind its rim, else the lens's own back face."""
        (rf, zf), back_nodes = self._split(scale)
        back = self.lens.faces(n)[-1]
        if back_nodes is not None:
            back = _polyline(*back_nodes, back.n_after)
        elif scale != 1.0:
            z0 = float(zf[0])
            back = Interface.plane(z0 + scale * (float(back.z_of_y(0.0)) - z0), back.n_after)
        return _polyline(rf, zf, n), back

    def outline(self) -> np.ndarray:
        """Closed (z, y) outline of the section, for the ray-fan plot."""
        front, back = self.faces(self.lens.n)
        r, _ = self.nodes()
        y = np.unique(np.concatenate([-r, r, np.linspace(-self.lens.radius_mm, self.lens.radius_mm, 201)]))
        y = y[np.abs(y) <= r.max() + 1e-9]
        ring = np.concatenate([np.stack([front.z_of_y(y), y], -1), np.stack([back.z_of_y(y[::-1]), y[::-1]], -1)])
        return np.concatenate([ring, ring[:1], [[np.nan, np.nan]]])

    def section_radius(self, z) -> np.ndarray:
        """The ideal lens's half-width at depth z: the largest r with front(r) ≤ z ≤ back(r)."""
        r = np.linspace(0.0, self.lens.radius_mm, PROFILE_SAMPLES)
        zf, zb = self.lens.front_z(r), self.lens.back_z(r)
        z = np.asarray(z, float)
        rise = np.interp(z, zf, r, left=0.0, right=self.lens.radius_mm)
        if np.ptp(zb) < 1e-9:                                   # a flat back face
            fall = np.where(z <= zb[0] + 1e-9, self.lens.radius_mm, 0.0)
        else:
            fall = np.interp(z, zb[::-1], r[::-1], left=self.lens.radius_mm, right=0.0)
        return np.minimum(rise, fall)

    def largest_gap_mm(self) -> list[float]:
        """Per sheet: the largest distance from the lens profile to its cone, in the meridional plane."""
        rim = [float(self.lens.front_z(self.lens.radius_mm)), float(self.lens.back_z(self.lens.radius_mm))]
        out = []
        for s in self.layup.sheets:
            z = np.concatenate([np.linspace(s.z_min_mm, s.z_max_mm, GAP_SAMPLES),
                                [x for x in rim if s.z_min_mm < x < s.z_max_mm]])
            out.append(gap_mm(np.stack([self.section_radius(z), z], -1), s.cone_mm, (s.z_min_mm, s.z_max_mm)))
        return out
