"""Spec of the frequency-scanning multibeam waveguide-slot array (seed-003, kind ``slot_array``).

``material`` is the dielectric that fills the guides (and the lens region of a mirror-lens beam
former); ``waveguide.fill_eps_r`` defaults to its εr. The metal of bodies, plates and mirror walls
is named in ``fabrication`` (method ``machined_plates``). The absorber of the matched loads
(``waveguide.load_material``) defaults to a carbon-loaded epoxy estimate (εr 4, tanδ 0.3,
1600 kg/m³; not in the seed: it only enters the mass figures).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from antenna_cad.spec.cam import RouterSpec
from antenna_cad.spec.bounds import MAX_LIST, MIN_GHZ, MIN_MM, MIN_RATIO
from antenna_cad.spec.common import (InlineMaterial, MaterialRef, SpecBase, StrictModel, _library_name, or_auto,
                                     resolve_material)

ABSORBER = InlineMaterial(name="absorber", eps_r=4.0, tan_delta=0.3, density_kg_m3=1600.0)


COEF = 100.0     # |normalised beam-former coefficient| (D = 1)
Coefficient = Annotated[float | None, Field(ge=-COEF, le=COEF)]
FeedSize = Annotated[float, Field(ge=MIN_MM, le=10000)]


class BandSpec(StrictModel):
    min_ghz: float = Field(ge=MIN_GHZ, le=1000)
    max_ghz: float = Field(ge=MIN_GHZ, le=1000)
    design_ghz: float = Field(ge=MIN_GHZ, le=1000, description="frequency of the synthesised slot line")


class WaveguideSpec(StrictModel):
    width_mm: float = Field(ge=0.1, le=500, description="broad-wall inner width a")
    height_mm: float = Field(ge=0.1, le=500, description="narrow-wall inner height b")
    fill_eps_r: float | None = Field(None, ge=1.0, le=100, description="default: εr of `material`")
    wall_mm: float = Field(0.0, ge=0, le=50, description="narrow (side) wall thickness; pitch ≥ a + 2·wall")
    termination: Literal["matched_load", "short"] = Field(
        "matched_load", description="far end of every guide: matched_load = absorber wedge in front of "
        "an end wall (takes the 1 − η left in the guide); short = end wall right after the last cell "
        "(the residual power reflects and radiates a mirrored beam)")
    load_length_mm: float | None = Field(None, ge=0.1, le=2000,
                                         description="absorber wedge length; default one guide wavelength "
                                         "at band.min_ghz")
    load_material: MaterialRef = Field(ABSORBER, description="lossy material of the load wedge")

    @field_validator("load_material")
    @classmethod
    def _known(cls, v):
        return _library_name(v) if isinstance(v, str) else v


class ArraySpec(StrictModel):
    count: int = Field(ge=1, le=500)
    pitch_mm: float = Field(ge=0.1, le=1000)
    length_mm: float = Field(ge=1, le=10000)


class TaperSpec(StrictModel):
    law: Literal["sin", "exp", "cos_pedestal", "uniform"] = "sin"
    eta: float = Field(0.9, ge=MIN_RATIO, lt=1)
    a0: float | None = Field(None, ge=1e-6, le=COEF, description="α(L1) cell fit, default the Ka 4-slot cell")
    b0: float | None = Field(None, ge=1e-6, le=COEF)
    pedestal: float = Field(0.3, ge=0, le=1)


class SlotsSpec(StrictModel):
    layout: Literal["longitudinal_4", "longitudinal_pair", "transverse_3"]
    width_mm: float = Field(ge=MIN_MM, le=100)
    period_mm: or_auto(Annotated[float, Field(ge=0.1, le=1000)]) = "auto"
    design_angle_deg: float | None = Field(
        None, ge=-80, le=80, description="−1st-harmonic beam angle from broadside at band.design_ghz "
        "(+ toward the guides' far end); sets period_mm: auto (default 0: broadside, p = λg)")
    taper: TaperSpec = TaperSpec()
    lengths_mm: list[Annotated[float, Field(ge=0, le=1000)]] | None = Field(None, max_length=MAX_LIST, description="per cell (or s1..s3 for transverse_3)")
    l2_ratio: float = Field(0.68, ge=MIN_RATIO, le=2)
    offset_mm: float | None = Field(None, ge=0, le=500)
    min_web_mm: float = Field(0.3, ge=0, le=100)
    wall_clearance_mm: float = Field(0.2, ge=0, le=100)
    min_coupling_gap_mm: float = Field(0.0, ge=0, le=1000, description="first slot at least this far from the "
                                       "coupling slot's far edge (d2 = 7.8 mm in seed-003 §2.4)")

    @model_validator(mode="after")
    def _angle_or_period(self):
        if self.design_angle_deg is not None and self.period_mm != "auto":
            raise ValueError("slots.design_angle_deg: only with period_mm: auto (an explicit period "
                             "fixes the angle)")
        return self


BEAMFORMER_PARAMS = {"single_mirror": ("minor_semi_axis_mm", "focal_separation_mm"),
    "bifocal_two_mirror": ("a0", "a2", "h1", "b0", "b2", "h2", "rho1"),
    "bifocal_mirror_lens": ("lens_a2", "lens_vertex", "x0", "p1", "p2", "f0", "n"),
    "trifocal_two_mirror": ("f1", "f", "c"),
    "trifocal_mirror_lens": ("f1", "f", "x_a", "gamma_a_rad", "n")}
TRIFOCAL = ("trifocal_two_mirror", "trifocal_mirror_lens")
POINT_COORD = Annotated[float, Field(ge=-5, le=5)]
POINT = tuple[POINT_COORD, POINT_COORD]     # (x, z) in the seed's frame, units of D (seed-003 §3.6)



class BeamFormerSpec(StrictModel):
    type: Literal["single_mirror", "bifocal_two_mirror", "bifocal_mirror_lens", "trifocal_two_mirror",
                  "trifocal_mirror_lens"]
    # single_mirror (ellipse, seed-003 §3.5)
    minor_semi_axis_mm: float | None = Field(None, ge=0.1, le=100000)
    focal_separation_mm: float | None = Field(None, ge=0, le=100000)
    # bifocal_two_mirror (normalised, §3.3)
    a0: Coefficient = None
    a2: Coefficient = None
    h1: Coefficient = None
    b0: Coefficient = None
    b2: Coefficient = None
    h2: Coefficient = None
    rho1: Coefficient = None
    # bifocal_mirror_lens (normalised, §3.4)
    lens_a2: Coefficient = None
    lens_vertex: Coefficient = None
    x0: Coefficient = None
    p1: Coefficient = None
    p2: Coefficient = None
    f0: Coefficient = None
    n: float | None = Field(None, ge=1.0, le=10.0, description="lens index (mirror-lens formers)")
    # trifocal formers (normalised (x, z) points in the seed's frame, §3.6–§3.8)
    f1: POINT | None = Field(None, description="focus F1 (x < 0, z < 0); F2 is its mirror image")
    f: POINT | None = Field(None, description="focus F on the axis (x = 0)")
    f2: POINT | None = Field(None, description="optional; must be the mirror image of f1 (erratum §7.7)")
    c: POINT | None = Field(None, description="point C of mirror 1 (x < 0) where the F1 central ray reflects")
    beta_c_deg: float | None = Field(None, gt=30, lt=120, description="direction of the reflected ray C→B "
                                     "below +x (not given in the seed); omitted: found by the §3.8 optimiser")
    x_a: float | None = Field(None, ge=-1, le=-1e-3, description="trifocal_mirror_lens: x of lens point A "
                              "where the F1 central ray enters (x < 0, §3.7)")
    gamma_a_rad: float | None = Field(None, ge=-1.2, le=1.2, description="trifocal_mirror_lens: angle of the lens "
                                      "tangent at A to the x axis (radians; lens z = a2 x², a2 = tg γ_A/(2 x_A))")
    o1: POINT | None = Field(None, description="trifocal_mirror_lens: mirror vertex O1 = (0, z) (not given in the "
                             "seed); omitted: found by the §3.8 optimiser")
    t_b: float | None = Field(None, ge=0, le=5, description="t at B (normalised); default: slot_line_offset_mm at x = 0")
    scale_mm: float | None = Field(None, ge=1, le=100000, description="physical size of the normalised D = 1")
    optimize: bool = Field(False, description="seed-003 §3.8: search the former's free parameters, from the given "
                           "values, for minimum σ over the 80° field of view (not the mirror–lens formers; trifocal_mirror_lens "
                           "searches O1 when o1 is omitted)")
    optimize_evaluations: int = Field(40, ge=1, le=2000, description="budget of the §3.8 search: σ curves "
                                      "computed (≈ 0.05 s ellipse, 0.4 s bifocal, 1 s trifocal each)")
    slot_line_offset_mm: float = Field(10.0, ge=0, le=10000, description="t0: last mirror → first slot line")
    layer_height_mm: float = Field(1.6, ge=MIN_MM, le=500)
    coupling_slot_mm: float = Field(1.1, ge=MIN_MM, le=500)

    @model_validator(mode="after")
    def _complete(self):
        missing = [k for k in BEAMFORMER_PARAMS[self.type] if getattr(self, k) is None]
        if missing:
            raise ValueError(f"beamformer.{missing[0]}: required for type {self.type} "
                             f"(missing: {', '.join(missing)})")
        if self.type in TRIFOCAL:
            if self.type == "trifocal_mirror_lens" and self.o1 is not None and self.o1[0] != 0:
                raise ValueError(f"beamformer.o1: must lie on the axis, x = 0 (got {self.o1[0]:g})")
            for name in ("f1", "f", "f2", "c", "o1"):
                if getattr(self, name) is not None and max(abs(v) for v in getattr(self, name)) > 5:
                    raise ValueError(f"beamformer.{name}: coordinates must lie within ±5 D")
            if self.f[0] != 0:
                raise ValueError(f"beamformer.f: must lie on the axis, x = 0 (got {self.f[0]:g})")
            if self.f1[0] >= 0 or self.f1[1] >= 0 or (self.c is not None and self.c[0] >= 0):
                raise ValueError("beamformer.f1: need x_F1 < 0, z_F1 < 0 and x_C < 0 (seed-003 §3.8 frame)")
            if self.f2 is not None and (abs(self.f2[0] + self.f1[0]) > 1e-12 or abs(self.f2[1] - self.f1[1]) > 1e-12):
                raise ValueError("beamformer.f2: must be the mirror image of f1 (erratum §7.7)")
            if self.t_b is not None and "slot_line_offset_mm" in self.model_fields_set:
                raise ValueError("beamformer.t_b: give t_b or slot_line_offset_mm, not both")
        return self

    def params(self) -> dict:
        extra = ({"t_b": self.t_b, "beta_c_deg": self.beta_c_deg} if self.type == "trifocal_two_mirror" else
                 {"t_b": self.t_b, "o1": self.o1} if self.type == "trifocal_mirror_lens" else {})
        opt = {"optimize": self.optimize, "optimize_evaluations": self.optimize_evaluations}
        return {k: getattr(self, k) for k in BEAMFORMER_PARAMS[self.type]} | extra | opt


class FeedsSpec(StrictModel):
    type: Literal["h_sectoral"] = "h_sectoral"
    throat_mm: tuple[FeedSize, FeedSize] = Field(description="(H-plane, E-plane)")
    aperture_mm: tuple[FeedSize, FeedSize] = Field(description="(H-plane, E-plane)")
    length_mm: float = Field(ge=0.1, le=10000)
    count: int = Field(1, ge=1, le=99)
    placement: Literal["optimal", "circle"] = "optimal"
    wall_mm: float = Field(1.0, ge=MIN_MM, le=50, description="H-plane side-wall thickness (the E-plane walls "
                           "are fabrication.broad_wall_mm thick, flush with the beam-former plates)")
    flange_mm: float = Field(3.0, ge=0, le=200, description="flange collar beyond the side walls at the throat")
    flange_thickness_mm: float = Field(3.0, ge=MIN_MM, le=200, description="flange (throat section) length along the axis")


class MachinedPlatesSpec(StrictModel):
    """Metal parts milled from plate: one body per guide, beam-former plates, mirror walls."""
    method: Literal["machined_plates"]
    metal: str = Field("aluminium", pattern=r"^[A-Za-z0-9_. -]+$")
    metal_density_kg_m3: float = Field(2700.0, ge=1, le=25000)
    broad_wall_mm: float = Field(0.5, ge=MIN_MM, le=50, description="slotted top wall and bottom wall")
    mirror_wall_mm: float = Field(2.0, ge=MIN_MM, le=100)
    plate_margin_mm: float = Field(10.0, ge=0, le=500, description="beam-former plate beyond mirrors")
    stock_allowance_mm: float = Field(2.0, ge=0, le=100)
    router: RouterSpec | None = Field(None, description="router G-code of the slotted lids and beam-former plates, "
                                      "one file per part (set a tool narrower than the slots)")


class SlotArraySpec(SpecBase):
    kind: Literal["slot_array"]
    fabrication: MachinedPlatesSpec
    band: BandSpec
    waveguide: WaveguideSpec
    array: ArraySpec
    slots: SlotsSpec
    beamformer: BeamFormerSpec
    feeds: FeedsSpec

    @model_validator(mode="after")
    def _consistent(self):
        b = self.band
        if not b.min_ghz <= b.design_ghz <= b.max_ghz:
            raise ValueError(f"band.design_ghz: must lie in [min_ghz, max_ghz] "
                             f"({b.design_ghz:g} not in [{b.min_ghz:g}, {b.max_ghz:g}])")
        if abs(self.frequency_ghz - b.design_ghz) > 1e-9:
            raise ValueError(f"frequency_ghz: must equal band.design_ghz ({self.frequency_ghz:g} ≠ {b.design_ghz:g})")
        for name, size in (("throat_mm", self.feeds.throat_mm), ("aperture_mm", self.feeds.aperture_mm)):
            if abs(size[1] - self.beamformer.layer_height_mm) > 1e-9:
                raise ValueError(f"feeds.{name}: E-plane size {size[1]:g} mm must equal "
                                 f"beamformer.layer_height_mm {self.beamformer.layer_height_mm:g} mm (an "
                                 "H-plane sectoral horn in the feed layer)")
        eps = self.fill_eps_r
        m = resolve_material(self.material)
        if abs(eps / m.eps_r - 1) > 0.05:
            raise ValueError(f"waveguide.fill_eps_r: {eps:g} differs > 5 % from εr {m.eps_r:g} of material {m.name}")
        return self

    @property
    def fill_eps_r(self) -> float:
        w = self.waveguide
        return w.fill_eps_r if w.fill_eps_r is not None else resolve_material(self.material).eps_r
