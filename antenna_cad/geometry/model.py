"""The Model value: labelled solids with their materials, and the checks of solid vs design."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
import shapely

from antenna_cad.geometry import kernel
from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check

Role = Literal["fabricated", "reference"]


@dataclass(frozen=True)
class ModelPart:
    label: str            # "lens", "sheet-07", "box-floor", ...
    material: Material
    role: Role            # fabricated: a part to make; reference: ideal body, allowance, envelope
    shape: kernel.Shape
    prism: SlottedPrism | RingPrism | None = None   # the shape's exact description, when it is one

    @property
    def volume_mm3(self) -> float:
        """The solid's volume; a prism's exactly from its profile (OCCT's integration over the
        Ka lids' 3,200 slot faces took longer than meshing them)."""
        return self.prism.volume_mm3() if self.prism is not None else kernel.volume(self.shape)

    def is_valid(self) -> bool:
        """BRepCheck of the solid; for a prism the exact test of its profile instead
        (:meth:`SlottedPrism.is_valid`: linear in the slots, where BRepCheck took 2 ms a slot)."""
        return self.prism.is_valid() if self.prism is not None else kernel.is_valid(self.shape)


@dataclass(frozen=True)
class RingPrism:
    """A flat ring (or disc, ``r_inner_mm`` 0) about z from ``z0_mm`` to ``z1_mm`` — what
    :func:`geometry.luneburg.annulus_solid` revolves — turned −90° about x when ``axis_y`` (the
    cylinder lenses' frame); meshed without OCCT by :func:`export.mesh.mesh_prism`."""
    r_inner_mm: float
    r_outer_mm: float
    z0_mm: float
    z1_mm: float
    axis_y: bool = False

    def is_valid(self) -> bool:
        return 0.0 <= self.r_inner_mm < self.r_outer_mm and self.z0_mm < self.z1_mm

    def volume_mm3(self) -> float:
        return math.pi * (self.r_outer_mm**2 - self.r_inner_mm**2) * (self.z1_mm - self.z0_mm)


@dataclass(frozen=True, eq=False)
class SlottedPrism:
    """A plate with rounded-end slots through it: the polygon ``outer_mm`` (counter-clockwise, straight
    edges) less the slots, extruded from ``z0_mm`` to ``z1_mm`` — what :func:`geometry.slot_array.
    slotted_plate` builds with one face and one prism. Slots are rows (x, y, length, width, angle) with
    the angle from +y, as :func:`geometry.slot_array.slot_wire` draws them: a straight core of half-length
    max(length/2 − width/2, 1e-4) along u = (sin a, cos a) and semicircular ends of radius width/2.
    It lets the part be meshed without OCCT (:func:`export.mesh.mesh_prism`). With
    ``axis_x`` the profile is drawn in (y, z) and extruded along x from ``z0_mm`` to ``z1_mm`` (the
    cyclic turn (u, v, w) → (w, u, v): the parallel plates of :func:`geometry.bifocal.plate_parts`)."""
    outer_mm: np.ndarray
    slots: np.ndarray
    z0_mm: float
    z1_mm: float
    axis_x: bool = False

    def cores(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(centres (m, 2), unit axes u (m, 2), straight half-lengths, radii) of the slots."""
        x, y, length, width, angle = self.slots.T
        u = np.column_stack([np.sin(angle), np.cos(angle)])
        return np.column_stack([x, y]), u, np.maximum(length / 2 - width / 2, 1e-4), width / 2

    def volume_mm3(self) -> float:
        """Plate area (shoelace) less each slot's (2·s × width + π r²), times the thickness."""
        x, y = np.asarray(self.outer_mm, float).T
        area = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
        if len(self.slots):
            _, _, s, r = self.cores()
            area -= float(np.sum(4 * s * r + np.pi * r**2))
        return area * (self.z1_mm - self.z0_mm)

    def is_valid(self) -> bool:
        """True when the plate is a valid solid: a simple outer polygon, every slot strictly inside
        it and no two slots touching — exact (segment distances against the radii), as BRepCheck
        would find the face's wires (no self-intersection, inner wires inside and disjoint)."""
        plate = shapely.Polygon(self.outer_mm)
        if not plate.is_valid or self.z1_mm <= self.z0_mm:
            return False
        if not len(self.slots):
            return True
        c, u, s, r = self.cores()
        cores = shapely.linestrings(np.stack([c - u * s[:, None], c + u * s[:, None]], axis=1))
        inside = shapely.contains(plate, cores) & (shapely.distance(plate.exterior, cores) > r)
        tree = shapely.STRtree(cores)
        i, j = tree.query(cores, predicate="dwithin", distance=2 * float(r.max()))
        pair = i < j
        i, j = i[pair], j[pair]
        apart = shapely.distance(cores[i], cores[j]) > r[i] + r[j]
        return bool(inside.all() and apart.all())


@dataclass(frozen=True)
class Model:
    parts: tuple[ModelPart, ...]
    checks: tuple[Check, ...]
    step_pcurves: bool = True   # False: STEP without p-curves (optional data; ~2x faster, 3x smaller
                                # for thousands of slot faces)
    cutaway: tuple[str, ...] = ()   # labels left out of the report's pictures so nested parts show

    def part(self, label: str) -> ModelPart:
        return next(p for p in self.parts if p.label == label)


def relative_volume_check(name: str, solid_mm3: float, analytic_mm3: float, what: str,
                          rel_limit: float = 1e-6) -> Check:
    """Solid volume against its analytic integral (DESIGN.md "Tests": geometry vs invariants)."""
    rel = abs(solid_mm3 / analytic_mm3 - 1.0)
    return Check.upper(name, rel, rel_limit, "", f"{what}: relative volume error")
