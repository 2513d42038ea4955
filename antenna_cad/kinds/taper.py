"""A taper-cut stack as geometrical optics sees it: the front face is the polyline through the lens
profile at every sheet face (the cones of ``edge: taper`` in the meridional section), the back face
the lens's own. The fast model and full-wave take the cones from the fine sub-slab section
(:func:`antenna_cad.fabrication.section.stepped_section`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from antenna_cad.fabrication.layup import LayupPlan
from antenna_cad.raytrace.trace2d import Interface


@dataclass(frozen=True)
class Taper:
    """The cones of ``layup`` (every sheet taper-cut) in front of ``lens`` (kinds.asbuilt.Lens)."""
    lens: object
    layup: LayupPlan

    def nodes(self, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """(r, z) of the cone polyline from the vertex to the first node at the lens radius, z
        stretched by ``scale`` about the first face (every sheet thicker)."""
        sheets = self.layup.sheets
        r = [s.front_radius_mm for s in sheets] + [sheets[-1].radius_mm]
        z = [s.z_min_mm for s in sheets] + [sheets[-1].z_max_mm]
        end = next((i for i, x in enumerate(r) if x >= self.lens.radius_mm - 1e-9), len(r) - 1)
        r, z = np.array(r[:end + 1]), np.array(z[:end + 1])
        keep = np.concatenate([[True], np.diff(r) > 1e-9])        # a vertical run has no z(r)
        return r[keep], z[0] + scale * (z[keep] - z[0])

    def faces(self, n: float, scale: float = 1.0) -> tuple[Interface, ...]:
        """(front polyline, back face) with lens index n."""
        r, z = self.nodes(scale)
        slope = np.diff(z) / np.diff(r)

        def z_of_y(y):
            return np.interp(np.abs(np.asarray(y, float)), r, z)

        def dz_dy(y):
            y = np.asarray(y, float)
            k = np.clip(np.searchsorted(r, np.abs(y)) - 1, 0, len(slope) - 1)
            return np.sign(y) * slope[k]

        back = self.lens.faces(n)[-1]
        z0 = float(z[0])
        if scale != 1.0:
            zb = z0 + scale * (float(back.z_of_y(0.0)) - z0)
            back = Interface.plane(zb, back.n_after)
        return Interface(z_of_y, dz_dy, float(n), float(np.median(z))), back

    def outline(self) -> np.ndarray:
        """Closed (z, y) outline of the section, for the ray-fan plot."""
        front, back = self.faces(self.lens.n)
        r, _ = self.nodes()
        y = np.unique(np.concatenate([-r, r, np.linspace(-self.lens.radius_mm, self.lens.radius_mm, 201)]))
        zb = float(back.z_of_y(0.0))
        ring = np.concatenate([np.stack([front.z_of_y(y), y], -1), [[zb, y[-1]], [zb, y[0]]]])
        return np.concatenate([ring, ring[:1], [[np.nan, np.nan]]])

    def largest_gap_mm(self) -> list[float]:
        """Per sheet: the largest distance from the lens profile to its cone, in the meridional plane."""
        r = np.linspace(0.0, self.lens.radius_mm, 4001)
        zf = self.lens.front_z(r)
        out = []
        for s in self.layup.sheets:
            z = np.linspace(s.z_min_mm, s.z_max_mm, 257)
            p = np.stack([np.interp(z, zf, r), z], -1)                 # the profile within the sheet
            a = np.array([s.front_radius_mm, s.z_min_mm])
            d = np.array([s.radius_mm, s.z_max_mm]) - a
            u = np.clip((p - a) @ d / (d @ d), 0.0, 1.0)
            out.append(float(np.max(np.linalg.norm(p - a - u[:, None] * d, axis=1))))
        return out
