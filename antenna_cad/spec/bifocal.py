"""Spec of the bifocal (two-surface) dielectric lens collimator (seed-000 §1.3, §2.3–§2.8, §3.2;
seed-001 §3.1). Frame of :mod:`antenna_cad.synthesis.bifocal`: z the optical axis from the feed
plane (z = 0) toward the antenna under test, foci at (0, ±a), rim at (X_B, ±Y_B)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG, MIN_MM, MIN_RATIO
from antenna_cad.spec.common import AutSpec, SheetLayupSpec, SpecBase, StrictModel, TestZoneSpec


COEF = 10.0      # |normalised coefficient| (D = 1): beyond it the lens is not a lens


H_PARAM = Annotated[float, Field(ge=MIN_RATIO, lt=0.5)]


class KinberSpec(StrictModel):
    """Seed-001 §3.1 central-segment parameters of Kinber's construction, in units of the aperture
    D (the seed normalises D = 1; the lens is scaled to D = 2·edge_y_mm)."""
    a0: float = Field(ge=-COEF, le=COEF, description="illuminated face vertex x")
    a2: float | None = Field(None, ge=-COEF, le=COEF, description="illuminated central parabola coefficient "
                             "(None: solved from C² continuity at the junctions, seed-001 §3.1)")
    h1: H_PARAM | Literal["optimise"] = Field(
        description="half-height of the central segment, or optimise: h1 = h2 in h_range for the least max "
        "σ (3.10) over view_angle_deg (a2 then from C² continuity)")
    b0: float = Field(ge=-COEF, le=COEF, description="shadow face vertex x")
    b2: float | None = Field(None, ge=-COEF, le=COEF, description="shadow central parabola coefficient (None: "
                             "−a2, a symmetric lens only)")
    h2: float | None = Field(None, ge=MIN_RATIO, lt=0.5, description="shadow segment half-height (None: A–O–B collinear)")
    rho1: float = Field(ge=MIN_RATIO, le=COEF, description="focal distance ρ1 = F1A (from the entry point A)")
    rho2: float | None = Field(None, ge=MIN_RATIO, le=COEF, description="image distance ρ2 = BF1' of a point-image "
                               "lens (the seed's lenses 1 and 2); None: plane output fronts (lens 3)")
    h_range: tuple[H_PARAM, H_PARAM] = Field((0.02, 0.09), description="search range of h1 = h2 (h1: optimise)")
    view_angle_deg: float = Field(40.0, ge=1.0, le=120.0, description="full view angle of the σ analysis "
                                  "(and of the h optimisation); the seed's 40°")
    focal_axis_x: float | None = Field(None, ge=-COEF, le=COEF, description="where the focal circle through F1, "
                                       "F2 crosses the axis (seed frame, origin at the lens centre); None: "
                                       "optimised for the least max σ over the view")

    @model_validator(mode="after")
    def _optimise_consistent(self):
        if self.h1 == "optimise":
            for name in ("a2", "h2"):
                if getattr(self, name) is not None:
                    raise ValueError(f"design.kinber.{name}: with h1: optimise, h2 = h1 and a2 is solved from "
                                     "C² continuity for every trial h; leave it out")
        if not self.h_range[0] < self.h_range[1]:
            raise ValueError("design.kinber.h_range: needs [low, high] with low < high")
        return self


class HornSpec(StrictModel):
    """H-plane sectoral horn between the plates, its aperture centred on the design focus O1 and its
    axis aimed at the illuminated vertex (seed-001 §3.1 FEM: input 7.2×3.4 mm, output 13×3.4 mm)."""
    input_width_mm: float = Field(7.2, ge=MIN_MM, le=1000, description="broad wall of the feeding guide")
    aperture_width_mm: float = Field(13.0, ge=MIN_MM, le=5000, description="H-plane aperture width")
    length_mm: float | None = Field(None, ge=MIN_MM, le=10000, description="flare length along the axis "
                                    "(None: the optimum H-plane horn, aperture² = 3 λ · slant length)")
    feed_length_mm: float = Field(10.0, ge=MIN_MM, le=1000, description="straight guide behind the flare")
    wall_mm: float = Field(1.0, ge=MIN_MM, le=50, description="side-wall thickness")


class ParallelPlateSpec(StrictModel):
    """The lens between two metal plates spaced by height_mm (seed-001 §3.1: a 3.4 mm parallel-plate
    waveguide at 37.5 GHz), with its feed horn."""
    plate_thickness_mm: float = Field(2.0, ge=MIN_MM, le=100)
    margin_mm: float = Field(10.0, ge=0, le=1000, description="plates beyond the lens and the horn")
    metal: str = Field("aluminium", pattern=r"^[A-Za-z0-9_. -]+$")
    metal_density_kg_m3: float = Field(2700.0, ge=1, le=25000)
    horn: HornSpec | None = Field(HornSpec(), description="the H-plane horn at O1 (null: plates only)")


class BifocalDesignSpec(StrictModel):
    edge_x_mm: float | None = Field(None, ge=0.1, le=200000,
                                    description="X_B: axial position of the zero-thickness rim (nikulina)")
    edge_y_mm: float = Field(ge=0.1, le=10000, description="Y_B: aperture half-size (rim radius)")
    focus_offset_mm: float | None = Field(None, ge=MIN_MM, le=200000, description="a: foci at (0, ±a); or give beam_tilt_deg")
    beam_tilt_deg: float | None = Field(None, ge=MIN_DEG, lt=90, description="α: beam tilt of each focus; or give a")
    antenna_x_mm: float | None = Field(None, ge=0.1, le=1e6, description="c: antenna-under-test plane "
                                       "(default: 100 mm beyond the (3.15) limit)")
    shape: Literal["revolved", "cylindrical"] = Field(
        "revolved", description="revolved: the section turned about the axis (a ring of foci); "
        "cylindrical: the section extruded by height_mm (exact in every section)")
    height_mm: float | None = Field(None, ge=0.1, le=20000, description="extrusion height (cylindrical only)")
    construction: Literal["nikulina", "kinber"] = "nikulina"
    kinber: KinberSpec | None = Field(None, description="construction: kinber only — its parameters")
    phase_error_budget_deg: float = Field(22.5, ge=MIN_DEG, le=180, description="budget of the scan-range study")
    aut: AutSpec | None = Field(None, description="antenna under test on the antenna_x_mm plane (its "
                                "distance_mm is that plane); default: a circle, the lens less the GO edge "
                                "margin or the test zone if larger")
    test_zone: TestZoneSpec = TestZoneSpec()
    parallel_plate: ParallelPlateSpec | None = Field(None, description="cylindrical lens only: the lens "
                                                     "between metal plates spaced height_mm, with its H-plane horn")

    @model_validator(mode="after")
    def _consistent(self):
        if self.aut is not None and self.aut.distance_mm is not None:
            raise ValueError("design.aut.distance_mm: the bifocal AUT plane is design.antenna_x_mm")
        if self.construction == "kinber":
            given = [k for k in ("edge_x_mm", "focus_offset_mm", "beam_tilt_deg") if getattr(self, k) is not None]
            if self.kinber is None:
                raise ValueError("design.kinber: construction kinber needs its central-segment parameters "
                                 "{a0, a2, h1, b0, b2, h2, rho1} (seed-001 §3.1)")
            if given:
                raise ValueError(f"design.{given[0]}: an output of the kinber construction (the foci, tilt and "
                                 "rim follow from its parameters); leave it out")
            return self._shape_fits()
        if self.kinber is not None:
            raise ValueError("design.kinber: only for construction: kinber")
        if self.edge_x_mm is None:
            raise ValueError("design.edge_x_mm: required by the nikulina construction (the zero-thickness rim)")
        if self.focus_offset_mm is None and self.beam_tilt_deg is None:
            raise ValueError("design.beam_tilt_deg: give beam_tilt_deg or focus_offset_mm "
                             "(the other is solved from the equal-edge ellipse (3.6))")
        return self._shape_fits()

    def _shape_fits(self):
        if self.parallel_plate is not None and self.shape != "cylindrical":
            raise ValueError("design.parallel_plate: only for shape: cylindrical (the plates bound the extrusion)")
        if self.shape == "cylindrical" and self.height_mm is None:
            raise ValueError("design.height_mm: required for shape: cylindrical")
        if self.shape == "revolved" and self.height_mm is not None:
            raise ValueError("design.height_mm: only for shape: cylindrical (a revolved lens has none)")
        return self


class BifocalSpec(SpecBase):
    kind: Literal["bifocal"]
    design: BifocalDesignSpec

    @model_validator(mode="after")
    def _fits(self):
        fab = self.fabrication
        if isinstance(fab, SheetLayupSpec):
            if self.design.shape != "revolved":
                raise ValueError("fabrication.method: sheet_layup makes a lens of revolution (disc sheets); "
                                 "a cylindrical bifocal lens needs method: solid")
            if self.design.kinber is not None and self.design.kinber.rho2 is not None:
                raise ValueError("fabrication.method: a point-image Kinber lens (design.kinber.rho2) is verified by "
                                 "its σ over the view, not by the layup's plane-front trace; use method: solid")
            fab.check_fits_lens(self.design.edge_y_mm, "2·design.edge_y_mm")
        return self
