"""Spec of the bifocal (two-surface) dielectric lens collimator (seed-000 §1.3, §2.3–§2.8, §3.2;
seed-001 §3.1). Frame of :mod:`antenna_cad.synthesis.bifocal`: z the optical axis from the feed
plane (z = 0) toward the antenna under test, foci at (0, ±a), rim at (X_B, ±Y_B)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG, MIN_MM, MIN_RATIO
from antenna_cad.spec.common import AutSpec, SheetLayupSpec, SpecBase, StrictModel, TestZoneSpec


COEF = 10.0      # |normalised coefficient| (D = 1): beyond it the lens is not a lens


class KinberSpec(StrictModel):
    """Seed-001 §3.1 central-segment parameters of Kinber's construction, in units of the aperture
    D (the seed normalises D = 1; the lens is scaled to D = 2·edge_y_mm)."""
    a0: float = Field(ge=-COEF, le=COEF, description="illuminated face vertex x")
    a2: float | None = Field(None, ge=-COEF, le=COEF, description="illuminated central parabola coefficient "
                             "(None: solved from C² continuity at the junctions, seed-001 §3.1)")
    h1: float = Field(ge=MIN_RATIO, lt=0.5, description="half-height of the central segment")
    b0: float = Field(ge=-COEF, le=COEF, description="shadow face vertex x")
    b2: float | None = Field(None, ge=-COEF, le=COEF, description="shadow central parabola coefficient (None: "
                             "−a2, a symmetric lens only)")
    h2: float | None = Field(None, ge=MIN_RATIO, lt=0.5, description="shadow segment half-height (None: A–O–B collinear)")
    rho1: float = Field(ge=MIN_RATIO, le=COEF, description="focal distance of F1 from the origin")


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
            fab.check_fits_lens(self.design.edge_y_mm, "2·design.edge_y_mm")
        return self
