"""Spec of the aplanatic integral mirror-lens antenna (seed-004, kind ``mirror_lens``).

A dielectric body (``material``; its εr = n²) whose front face refracts and whose metallised back
face reflects, the feed in front. Lengths of the design are given either normalised to the
aperture diameter D, as in the seed (``f0``, ``d0``, ``gamma``), or in millimetres (``f0_mm`` …),
or as the ratio ``f0_over_d0`` with the axial length ``length`` = f0 + d0 (seed-004 §3.4: 1).
``feed_on_surface`` is the seed's f0 = 0 variant (§2.4). Frame: seed-004 §1, feed at z = 0, the
body toward +z, the beam leaves toward −z.

``fabrication.method: printed``: ``material`` is the filament and ``design.refractive_index`` the
body's index n; the body is printed as a uniform lattice whose εr_eff = n² (antenna_cad.printed)
inside a solid skin.
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG, MIN_MM, MIN_RATIO
from antenna_cad.spec.common import SheetLayupSpec, SolidSpec, SpecBase, StrictModel, resolve_material
from antenna_cad.spec.printed import PrintedSpec, check_material_index

MAX_LAYUP_EPS_R = 2.0       # "foam-like": sheet stock of low-density foams and printed infill


class MirrorSpec(StrictModel):
    """The reflecting layer on the back face: its own thin part and process step."""
    metal: str = Field("aluminium", pattern=r"^[A-Za-z0-9_. -]+$")
    density_kg_m3: float = Field(2700.0, ge=1, le=25000)
    thickness_mm: float = Field(0.1, ge=MIN_MM, le=10, description="coating / plating / foil thickness")
    process: Literal["spray", "plating", "foil", "vacuum_metallization"] = "spray"


class FeedSpec(StrictModel):
    """Placeholder of the feed (a circular horn, seed-004 §4) with its aperture centre at the focus."""
    aperture_diameter_mm: float = Field(40.0, ge=MIN_MM, le=5000)
    length_mm: float = Field(80.0, ge=MIN_MM, le=10000)


class FlangeSpec(StrictModel):
    """Mounting ring on the side wall, outside the aperture and the mirror rim."""
    width_mm: float = Field(25.0, ge=MIN_MM, le=2000)
    thickness_mm: float = Field(10.0, ge=MIN_MM, le=500)
    bolt_count: int = Field(8, ge=0, le=360)
    bolt_diameter_mm: float = Field(6.0, ge=MIN_MM, le=100)


class OptimizeSpec(StrictModel):
    """Choose γ (and optionally f0, with f0 + d0 held) by minimising the seed's target A, eq. (21),
    at the material's n (seed-004 §3.4–3.5; n is the material's, not a free parameter here)."""
    mode: Literal["series", "exact"] = Field("series", description="series: (19) as the paper (reproduces "
                                              "γ* = 0.9378 for the published n, f0/d0); exact: marched geometry")
    gamma_min: float = Field(gt=0.5, le=10, description="search interval of γ (units of D)")
    gamma_max: float = Field(gt=0.5, le=10)
    free_f0: bool = Field(False, description="also move f0 (d0 = f0 + d0 − f0) inside [f0_min, f0_max]; "
                          "the paper's published point is not the 2-D optimum (seed-004 §3.5 item 2)")
    f0_min: float = Field(0.05, ge=MIN_RATIO, le=10, description="units of D")
    f0_max: float = Field(0.95, ge=MIN_RATIO, le=10)

    @model_validator(mode="after")
    def _order(self):
        if self.gamma_max <= self.gamma_min:
            raise ValueError("design.optimize.gamma_max: must be > gamma_min")
        if self.f0_max <= self.f0_min:
            raise ValueError("design.optimize.f0_max: must be > f0_min")
        return self


class MirrorLensDesign(StrictModel):
    diameter_mm: float = Field(ge=MIN_MM, le=20000, description="D, the exit aperture diameter")
    refractive_index: float | None = Field(None, gt=1, le=10,
                                           description="the body's index n: optional check that it equals √εr of "
                                           "material; with fabrication.method printed, required — the lattice "
                                           "is filled so that its εr_eff = n²")
    feed_on_surface: bool = Field(False, description="f0 = 0: the feed on the front face (seed-004 §2.4)")
    f0: float | None = Field(None, ge=MIN_RATIO, le=10, description="feed to front vertex, units of D")
    f0_mm: float | None = Field(None, ge=MIN_MM, le=200000)
    d0: float | None = Field(None, ge=MIN_RATIO, le=10, description="axial thickness, units of D")
    d0_mm: float | None = Field(None, ge=MIN_MM, le=200000)
    f0_over_d0: float | None = Field(None, ge=MIN_RATIO, le=100, description="with length = f0 + d0")
    length: float = Field(1.0, ge=MIN_RATIO, le=20, description="f0 + d0 in units of D, used with f0_over_d0")
    gamma: float | None = Field(None, gt=0.5, le=10, description="aplanatic radius (sine condition), units of D")
    gamma_mm: float | None = Field(None, ge=MIN_MM, le=200000)
    optimize: OptimizeSpec | None = Field(None, description="choose γ from the target A instead of giving it")
    field_half_angle_deg: float = Field(20.0, ge=MIN_DEG, le=60, description="largest field angle of the σ study")
    phase_error_budget_deg: float = Field(22.5, ge=MIN_DEG, le=180)
    mirror: MirrorSpec = MirrorSpec()
    feed: FeedSpec = FeedSpec()
    flange: FlangeSpec = FlangeSpec()

    @model_validator(mode="after")
    def _lengths(self):
        D = self.diameter_mm
        pairs = {"f0": (self.f0, self.f0_mm), "d0": (self.d0, self.d0_mm), "gamma": (self.gamma, self.gamma_mm)}
        for name, (norm, mm) in pairs.items():
            if norm is not None and mm is not None:
                raise ValueError(f"design.{name}_mm: give {name} (units of D) or {name}_mm, not both")
        if self.f0_over_d0 is not None and (self.f0 or self.f0_mm or self.d0 or self.d0_mm or self.feed_on_surface):
            raise ValueError("design.f0_over_d0: give f0_over_d0 (with length) or f0 and d0, not both "
                             "(and not with feed_on_surface)")
        if self.feed_on_surface and (self.f0 or self.f0_mm):
            raise ValueError("design.f0: feed_on_surface means f0 = 0; leave f0 out")
        if not self.feed_on_surface and self.f0_over_d0 is None and self.f0 is None and self.f0_mm is None:
            raise ValueError("design.f0: required (or f0_mm, or f0_over_d0), unless feed_on_surface")
        if self.f0_over_d0 is None and self.d0 is None and self.d0_mm is None:
            raise ValueError("design.d0: required (or d0_mm, or f0_over_d0)")
        has_gamma = self.gamma is not None or self.gamma_mm is not None
        if has_gamma == (self.optimize is not None):
            raise ValueError("design.gamma: give gamma (or gamma_mm) or optimize, exactly one")
        if self.gamma_mm is not None and self.gamma_mm <= D / 2:
            raise ValueError(f"design.gamma_mm: must exceed the aperture radius D/2 = {D / 2:g} mm "
                             f"(sine condition r = γ sin α; got {self.gamma_mm:g})")
        if self.optimize is not None and self.optimize.gamma_min <= self.f0_norm:
            raise ValueError(f"design.optimize.gamma_min: must be > f0 = {self.f0_norm:.4g} D "
                             "(f2 is singular at γ = f0)")
        if has_gamma and not self.feed_on_surface and abs(self.gamma_norm - self.f0_norm) < 1e-3:
            raise ValueError(f"design.gamma: γ = f0 = {self.f0_norm:.4g} makes the series singular (seed-004 §3.5)")
        return self

    @property
    def f0_norm(self) -> float:
        if self.feed_on_surface:
            return 0.0
        if self.f0_over_d0 is not None:
            return self.length * self.f0_over_d0 / (1 + self.f0_over_d0)
        return self.f0 if self.f0 is not None else self.f0_mm / self.diameter_mm

    @property
    def d0_norm(self) -> float:
        if self.f0_over_d0 is not None:
            return self.length / (1 + self.f0_over_d0)
        return self.d0 if self.d0 is not None else self.d0_mm / self.diameter_mm

    @property
    def gamma_norm(self) -> float | None:
        if self.gamma is not None:
            return self.gamma
        return self.gamma_mm / self.diameter_mm if self.gamma_mm is not None else None


class MirrorLensSpec(SpecBase):
    kind: Literal["mirror_lens"]
    design: MirrorLensDesign
    fabrication: Annotated[Union[SheetLayupSpec, SolidSpec, PrintedSpec], Field(discriminator="method")]

    @model_validator(mode="after")
    def _consistent(self):
        m = resolve_material(self.material)
        n = self.design.refractive_index
        if isinstance(self.fabrication, PrintedSpec):
            self.fabrication.check_lens(self.material, self.frequency_ghz)
            self.fabrication.check_flat_body("the mirror-lens body")
            self.fabrication.check_uniform_index(self.material, n, "the body")
            return self
        check_material_index(m, n)
        if isinstance(self.fabrication, SheetLayupSpec) and m.eps_r > MAX_LAYUP_EPS_R:
            raise ValueError(f"fabrication.method: sheet_layup is for foam-like stock (εr ≤ {MAX_LAYUP_EPS_R:g}); "
                             f"{m.name} has εr {m.eps_r:g}: use method: solid (machined or printed)")
        if isinstance(self.fabrication, SheetLayupSpec):
            self.fabrication.check_fits_lens(self.design.diameter_mm / 2, "design.diameter_mm")
        return self
