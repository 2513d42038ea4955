"""Spec of the polyfocal constrained lens (seed-001 §1, §2; kind ``polyfocal``).

Optics are given in the seed's normalised units (λ = 1 in its Ch.1, D = 1 in Ch.2) and scaled by
``design.unit_mm``; the realization (``lines``) is in millimetres. ``material`` is the dielectric
that fills the lines (air, {eps_r: 1, …}, for hollow waveguides). Supported cases (seed-001):

* ``2d`` / ``two_planes`` / ``foci`` — §1.2–§1.3: one focus pair (bifocal, with ``line_law``), or two
  pairs (first angle 0: trifocal; otherwise four-focal); ``thickness`` = 2·z0.
* ``2d`` / ``one_plane`` / ``foci`` — §1.4: four finite foci, two pairs [F1/F2 (f1, ±α) imaged at
  f1', F3/F4 (f3, ±β) imaged at f3'] (``f_image``: the image's distance from the exit-surface centre);
  the entry surface through the origin, ``thickness`` moves the output half along z (§1.1).
* ``2d`` / ``one_plane`` / ``plane_waves`` — §1.5: equal-line trifocal lens, foci [F on the axis,
  F1/F2 pair]; ``thickness`` = d.
* ``3d`` / ``three_planes`` / ``foci`` — §2.2: two pairs as §1.3 (f from the surface centres,
  angles), imaged point-symmetrically, ``thickness`` = 2·z0; both in the yz plane (variant 1), or the
  second in the xz plane (``azimuth_deg: 90``, variant 2, the rhombus).
* ``3d`` / ``one_plane`` / ``plane_waves`` — §2.4: five foci, [F1/F2 (f1, α, φ), F3/F4 (f3, β, ξ),
  F5 (f5, ψ) in the xz plane].

Each focus is given by the seed's parameters or by its position (:class:`FocusSpec`).
"""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG, MIN_MM, MIN_RATIO
from antenna_cad.spec.common import SpecBase, StrictModel


COORD = Annotated[float, Field(ge=-1e4, le=1e4)]
COORD_MM = Annotated[float, Field(ge=-1e7, le=1e7)]
MIN_F = 0.01              # shortest focal distance (normalised units)


class FocusSpec(StrictModel):
    """One focus, or a mirror pair of foci: the seed's parameters (f, angles in degrees) or the
    position of the focus (of the pair's upper member) in the lens frame — origin O at the lens
    centre, z the axis toward the output, y transverse (2-D: (y, z); 3-D: (x, y, z)), normalised
    units (``position``) or millimetres (``position_mm``)."""
    f: float | None = Field(None, gt=MIN_F, le=1e4, description="focal distance (normalised units): from the "
                            "surface centre in 2-D (seed-001 (1.2)/(1.5)), from the lens centre O in 3-D (2.1)")
    angle_deg: float | None = Field(None, ge=0, lt=80, description="angle to the lens axis (α, β, ψ); default 0")
    azimuth_deg: float | None = Field(None, ge=-90, le=90, description="3-D only: azimuth from Oy (φ, ξ); default 0")
    f_image: float | None = Field(None, gt=MIN_F, le=1e4, description="2-D one-plane lens with finite foci only "
                                  "(§1.4): distance f' of the pair's images from the exit-surface centre")
    position: tuple[COORD, ...] | None = Field(None, min_length=2, max_length=3, description="the focus "
                                               "position, normalised units (instead of f and the angles)")
    position_mm: tuple[COORD_MM, ...] | None = Field(None, min_length=2, max_length=3, description="the focus "
                                                     "position in mm (divided by design.unit_mm)")

    @model_validator(mode="after")
    def _one_form(self):
        given = [k for k in ("position", "position_mm") if getattr(self, k) is not None]
        if len(given) > 1:
            raise ValueError("give position or position_mm, not both")
        if given and any(getattr(self, k) is not None for k in ("f", "angle_deg", "azimuth_deg")):
            raise ValueError(f"{given[0]} replaces f, angle_deg and azimuth_deg; leave them out")
        if not given and self.f is None:
            raise ValueError("give f (with angle_deg, azimuth_deg) or the position (position or position_mm)")
        return self

    def resolved(self, where: str, case: str, thickness: float, unit_mm: float, single: bool) -> dict[str, float]:
        """{f, angle_deg, azimuth_deg} in the seed's parameters. ``single``: the focus is no mirror
        pair (§1.5's F, §2.4's F5), so it must lie on the axis (2-D) or in the xz plane (3-D).
        Raises ValueError "<where>.position: rule" for a position the case cannot take."""
        if self.f is not None:
            return {"f": self.f, "angle_deg": self.angle_deg or 0.0, "azimuth_deg": self.azimuth_deg or 0.0,
                    "f_image": self.f_image}
        key = "position" if self.position is not None else "position_mm"
        pos = np.array(self.position if self.position is not None else self.position_mm, float)
        pos = pos / (1.0 if self.position is not None else unit_mm)
        field = f"{where}.{key}"
        dims = 2 if case.startswith("2d") else 3
        if len(pos) != dims:
            raise ValueError(f"{field}: {'2-D foci take (y, z)' if dims == 2 else '3-D foci take (x, y, z)'}; "
                             f"got {len(pos)} numbers")
        rhombus = 0.0
        if case == "3d/three_planes/foci":         # the foci lie in the yz (or xz) plane, given as in 2-D
            if pos[0] != 0 and pos[1] != 0:
                raise ValueError(f"{field}: the foci of the three-plane lens lie in the yz plane (x = 0) or, for "
                                 "the rhombus, the second pair in the xz plane (y = 0)")
            rhombus = 90.0 if pos[0] != 0 else 0.0
            pos, dims = np.array([abs(pos[0]) or pos[1], pos[2]]), 2
        if dims == 2:
            y, z = pos
            z_ref = 0.0 if case == "2d/one_plane/foci" else -thickness / 2   # the entry-surface centre
            if z >= z_ref:
                raise ValueError(f"{field}: the focus must lie in front of the entry surface (z < "
                                 f"{z_ref:.6g} normalised: the entry-surface centre)")
            if y < 0:
                raise ValueError(f"{field}: give the upper focus of the ±pair (y ≥ 0)")
            if single and y != 0:
                raise ValueError(f"{field}: this focus lies on the axis (y = 0)")
            f, angle, azimuth = float(np.hypot(y, z - z_ref)), float(np.degrees(np.arctan2(y, z_ref - z))), rhombus
        else:
            x, y, z = pos
            f = float(np.linalg.norm(pos))
            if z >= 0:
                raise ValueError(f"{field}: the focus must lie in front of the lens (z < 0)")
            if single and (y != 0 or x < 0):
                raise ValueError(f"{field}: the fifth focus lies in the xz plane at x ≥ 0 (y = 0)")
            if not single and y < 0:
                raise ValueError(f"{field}: give the focus of the pair with y ≥ 0 (its mirror is in y)")
            angle = float(np.degrees(np.arccos(-z / f)))
            azimuth = 0.0 if single else float(np.degrees(np.arctan2(x, y)))
        if not f > MIN_F:
            raise ValueError(f"{field}: focal distance {f:.6g} below {MIN_F} normalised units")
        if not angle < 80:
            raise ValueError(f"{field}: angle to the axis {angle:.4g}° (rule: < 80°)")
        return {"f": f, "angle_deg": angle, "azimuth_deg": azimuth, "f_image": self.f_image}


class LinesSpec(StrictModel):
    """Realization of the lines (seed-001 §6, §8.1): straight channels from the entry to the exit
    point, each with the phase index that gives it the synthesized electrical length."""
    type: Literal["parallel_plate", "waveguide_array"] = Field(
        description="parallel_plate: TEM channels between two plates, the delay set by each channel's "
        "dielectric fill (εr = n²); waveguide_array: TE10 rectangular guides filled with `material`, "
        "the delay set by each guide's width")
    pitch_mm: float = Field(gt=0.1, le=1000, description="element spacing on the entry surface "
                            "(exit surface for plane-wave lenses)")
    phase_index: float = Field(gt=0.05, le=10, description="phase index λ/λ_line of the central line; "
                               "fixes the common constant of the line lengths")
    wall_mm: float = Field(0.5, ge=MIN_MM, le=50, description="minimum metal septum between channels")
    plate_spacing_mm: float = Field(gt=0.05, le=1000, description="channel height (2-D: the plate spacing)")
    plate_thickness_mm: float = Field(2.0, ge=MIN_MM, le=100, description="top and bottom plates (2-D)")
    margin_mm: float = Field(5.0, ge=0, le=1000, description="plates beyond the lens outline (2-D)")


class LensMirrorSpec(StrictModel):
    """§1.5 realised as the two-storey lens–mirror antenna (seed-001 §1.5 Realisation, §8.1 item 2):
    TE10 guides of one width (``lines.plate_spacing_mm`` high, ``lines.pitch_mm`` apart on the exit
    surface, walls ≥ ``lines.wall_mm``) folded by 180° E-plane U-bends placed for equal lengths."""
    guide_width_mm: float = Field(gt=0.1, le=500, description="broad wall a of every guide (in the plate plane)")
    septum_mm: float = Field(1.0, ge=MIN_MM, le=50, description="metal between the layers; the U-bend turns "
                             "about its rounded edge (centre-line radius (plate spacing + septum)/2)")
    bend_run_mm: float | None = Field(None, ge=0, le=1000, description="axial run of each layer-1 guide before "
                                      "its bend (None: the guide width)")
    mirror_clearance_mm: float = Field(10.0, ge=0.1, le=10000, description="least axial distance from an entry "
                                       "point to its guide's kink (fixes the common line length)")
    setback_mm: float | None = Field(None, ge=-1000, le=10000, description="layer-2 exit-surface vertex behind "
                                     "the entry vertex (toward the feeds); None: the flare's mouth flush with the "
                                     "back of the feed horns. The bends move out until every layer-2 run "
                                     "is at least a guide width")
    horn_aperture_mm: float = Field(10.0, gt=0.1, le=1000, description="H-plane sectoral feed horn aperture "
                                    "(centred on each focus F, F1, F2, aimed at the entry-surface centre)")
    horn_length_mm: float = Field(15.0, gt=0.1, le=1000, description="feed horn length, throat to aperture")
    horn_stub_mm: float | None = Field(None, ge=MIN_MM, le=1000, description="feed guide behind each horn throat "
                                       "(None: twice the guide width)")
    flare_length_mm: float = Field(30.0, gt=0.1, le=10000, description="E-plane flare of the output plates")
    mouth_height_mm: float = Field(gt=0.05, le=1000, description="plate spacing at the radiating mouth")
    band_ghz: tuple[Annotated[float, Field(gt=0.1, le=1e4)], Annotated[float, Field(gt=0.1, le=1e4)]] = Field(
        description="operating band (lowest, highest): single-mode guides and plates are checked over it")

    @model_validator(mode="after")
    def _band(self):
        if not self.band_ghz[0] < self.band_ghz[1]:
            raise ValueError("design.lens_mirror.band_ghz: give (lowest, highest) with lowest < highest")
        return self


class PolyfocalDesignSpec(StrictModel):
    dimensions: Literal["2d", "3d"]
    symmetry: Literal["three_planes", "two_planes", "one_plane"]
    output: Literal["foci", "plane_waves"]
    foci: tuple[FocusSpec, ...] = Field(min_length=1, max_length=3,
                                        description="focus pairs ±angle (and single foci) in the seed's order")
    unit_mm: float = Field(gt=1e-3, le=1e5, description="one normalised unit in millimetres")
    aperture: float = Field(ge=MIN_RATIO, le=1e4, description="aperture D (normalised units)")
    thickness: float = Field(ge=MIN_RATIO, le=1e4, description="axial thickness (normalised): 2z0 (§1.2), d (§1.5); "
                             "3-D: the output half moved by it along z (§2.1)")
    line_law: Literal["equal_length", "straight", "flat"] = Field(
        "equal_length", description="bifocal only (§1.2): (a) equal lines, (b) straight lines, (c) flat")
    straight_index: float = Field(0.5, gt=0.05, lt=1.0, description="§1.2 (b): phase index n_w of the "
                                  "identical straight lines")
    view_angle_deg: float = Field(60.0, ge=MIN_DEG, le=150, description="full view angle of the σ study")
    focal_axis_z: float | None = Field(None, ge=-1e4, le=1e4, description="2-D bifocal only (§1.2): z_F, where the "
                                       "focal circle through F1, F2 crosses the axis (normalised, from the lens "
                                       "centre); None: optimised for the least peak σ over the view")
    lines: LinesSpec
    lens_mirror: LensMirrorSpec | None = Field(None, description="§1.5 only: build the two-storey lens–mirror "
                                               "antenna (U-bend mirror, E-plane flare) instead of straight channels")

    @property
    def case(self) -> str:
        return f"{self.dimensions}/{self.symmetry}/{self.output}"

    @property
    def foci_count(self) -> int:
        if self.case == "3d/one_plane/plane_waves":
            return 5
        return sum(1 if f["angle_deg"] == 0 else 2 for f in self.resolved_foci())

    def resolved_foci(self) -> list[dict[str, float]]:
        """The foci as the seed's {f, angle_deg, azimuth_deg}, positions converted (FocusSpec.resolved)."""
        singles = {"2d/one_plane/plane_waves": {0}, "3d/one_plane/plane_waves": {2}}.get(self.case, set())
        return [f.resolved(f"design.foci[{i}]", self.case, self.thickness, self.unit_mm, i in singles)
                for i, f in enumerate(self.foci)]

    @model_validator(mode="after")
    def _supported(self):
        counts = {"2d/two_planes/foci": (1, 2), "2d/one_plane/foci": (2,), "2d/one_plane/plane_waves": (2,),
                  "3d/three_planes/foci": (2,), "3d/one_plane/plane_waves": (3,)}
        if self.case == "3d/two_planes/foci":
            raise ValueError("design.symmetry: the two-plane 3-D lens with finite foci (seed-001 §2.3 (d), the "
                             "trapezoid) maps x2 = −x1: every line crosses the plane x = 0, so straight channels "
                             "would cut through each other; it needs flexible (bootlace) lines, which are not built")
        if self.case not in counts:
            raise ValueError(f"design.symmetry: the case {self.case} is not implemented; use one of "
                             f"{', '.join(sorted(counts))} (seed-001 §1.2–§1.5, §2.4)")
        if len(self.foci) not in counts[self.case]:
            raise ValueError(f"design.foci: the case {self.case} takes {' or '.join(map(str, counts[self.case]))} "
                             f"focus entries (got {len(self.foci)})")
        if self.dimensions == "2d" and any(f.azimuth_deg for f in self.foci):
            raise ValueError("design.foci: azimuth_deg is for the 3-D lenses only (the 2-D foci lie in the yz plane)")
        foci = self.resolved_foci()
        if self.case == "3d/three_planes/foci" and (foci[0]["azimuth_deg"] != 0 or foci[1]["azimuth_deg"] not in (0, 90)):
            raise ValueError("design.foci: the three-plane lens takes its first pair in the yz plane (azimuth_deg 0) "
                             "and its second in the yz (0) or the xz plane (90: the rhombus)")
        finite = self.case == "2d/one_plane/foci"
        if any((f.f_image is not None) != finite for f in self.foci):
            raise ValueError("design.foci: f_image is for the 2-D one-plane lens with finite foci (§1.4), and that "
                             "lens needs it on both pairs")
        if finite and (min(f["angle_deg"] for f in foci) == 0 or foci[0]["angle_deg"] == foci[1]["angle_deg"]):
            raise ValueError("design.foci: §1.4 takes two pairs off the axis at different angles (angle > 0)")
        if self.case in ("2d/two_planes/foci", "3d/three_planes/foci") and len(foci) == 2:
            a, b = foci
            if b["angle_deg"] == 0 or a["angle_deg"] == b["angle_deg"]:
                raise ValueError("design.foci: the second pair needs an angle > 0 and ≠ the first")
        bifocal = self.case == "2d/two_planes/foci" and len(foci) == 1
        if bifocal and foci[0]["angle_deg"] == 0:
            raise ValueError("design.foci: a bifocal lens needs its pair off the axis (angle > 0); one focus on the "
                             "axis is a single-focus lens")
        if self.focal_axis_z is not None and not bifocal:
            raise ValueError("design.focal_axis_z: only for a 2-D bifocal lens (other lenses' focal curves pass "
                             "through their foci or are fitted)")
        if self.focal_axis_z is not None:
            z_focus = -self.thickness / 2 - foci[0]["f"] * np.cos(np.radians(foci[0]["angle_deg"]))
            if abs(self.focal_axis_z - z_focus) < 1e-6 * self.aperture:
                raise ValueError(f"design.focal_axis_z: equals the foci's z {z_focus:.6g}; no circle centred on the "
                                 "axis passes through them and this point")
        if self.case == "2d/one_plane/plane_waves" and (foci[0]["angle_deg"] != 0 or foci[1]["angle_deg"] == 0):
            raise ValueError("design.foci: §1.5 takes [F on the axis (angle 0), the F1/F2 pair (angle > 0)]")
        if self.case == "3d/one_plane/plane_waves":
            if abs(foci[0]["f"] - foci[1]["f"]) < 1e-9:
                raise ValueError("design.foci: §2.4 needs f1 ≠ f3 ((2.47) divides by f1² − f3²)")
            if self.foci[2].azimuth_deg:
                raise ValueError("design.foci: the fifth focus lies in the xz plane (leave azimuth_deg out)")
        if self.lens_mirror is not None:
            self._check_lens_mirror()
        if self.lines.wall_mm >= self.lines.pitch_mm:
            raise ValueError("design.lines.wall_mm: must be < lines.pitch_mm")
        if self.aperture * self.unit_mm < 2 * self.lines.pitch_mm:
            raise ValueError("design.lines.pitch_mm: fewer than 3 elements across the aperture")
        return self

    def _check_lens_mirror(self) -> None:
        m = self.lens_mirror
        if self.case != "2d/one_plane/plane_waves":
            raise ValueError("design.lens_mirror: the two-storey lens–mirror antenna realises the §1.5 lens "
                             "(2d / one_plane / plane_waves) only")
        if m.guide_width_mm + self.lines.wall_mm > self.lines.pitch_mm:
            raise ValueError("design.lens_mirror.guide_width_mm: guide width + lines.wall_mm must not exceed "
                             "lines.pitch_mm")
        if m.horn_aperture_mm < m.guide_width_mm:
            raise ValueError("design.lens_mirror.horn_aperture_mm: the H-plane horn flares from the guide: give at "
                             "least guide_width_mm")
        if m.mouth_height_mm <= self.lines.plate_spacing_mm:
            raise ValueError("design.lens_mirror.mouth_height_mm: the E-plane flare opens: give more than "
                             "lines.plate_spacing_mm")


class MetalFabSpec(StrictModel):
    """Milled or sheet-metal constrained lens: plates, septa body and channels."""
    method: Literal["machined_metal"]
    metal: str = Field("aluminium", pattern=r"^[A-Za-z0-9_. -]+$")
    metal_density_kg_m3: float = Field(2700.0, ge=1, le=25000)
    section_pitch_mm: float | None = Field(None, ge=1.0, le=10000, description="3-D: 1:1 section gauges of both "
                                           "port surfaces at x = k·pitch (None: the element pitch)")
    gauge_depth_mm: float = Field(20.0, ge=1.0, le=1000, description="3-D: gauge height beyond the surface's "
                                  "extreme (its straight datum edge)")


class PolyfocalSpec(SpecBase):
    kind: Literal["polyfocal"]
    fabrication: MetalFabSpec
    design: PolyfocalDesignSpec

    @model_validator(mode="after")
    def _gauges_3d(self):
        if self.design.dimensions == "2d" and self.fabrication.section_pitch_mm is not None:
            raise ValueError("fabrication.section_pitch_mm: section gauges are for 3-D lenses (a 2-D lens has its "
                             "section template)")
        return self
