"""Spec of the bifocal (two-surface) dielectric lens collimator (seed-000 §1.3, §2.3–§2.8, §3.2;
seed-001 §3.1). Frame of :mod:`antenna_cad.synthesis.bifocal`: z the optical axis from the feed
plane (z = 0) toward the antenna under test, foci at (0, ±a), rim at (X_B, ±Y_B)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from antenna_cad.spec.common import SheetLayupSpec, SpecBase, StrictModel


class BifocalDesignSpec(StrictModel):
    edge_x_mm: float = Field(gt=0, le=200000, description="X_B: axial position of the zero-thickness rim")
    edge_y_mm: float = Field(gt=0, le=10000, description="Y_B: aperture half-size (rim radius)")
    focus_offset_mm: float | None = Field(None, gt=0, description="a: foci at (0, ±a); or give beam_tilt_deg")
    beam_tilt_deg: float | None = Field(None, gt=0, lt=90, description="α: beam tilt of each focus; or give a")
    antenna_x_mm: float | None = Field(None, gt=0, description="c: antenna-under-test plane "
                                       "(default: 100 mm beyond the (3.15) limit)")
    shape: Literal["revolved", "cylindrical"] = Field(
        "revolved", description="revolved: the section turned about the axis (a ring of foci); "
        "cylindrical: the section extruded by height_mm (exact in every section)")
    height_mm: float | None = Field(None, gt=0, le=20000, description="extrusion height (cylindrical only)")
    construction: Literal["nikulina", "kinber"] = "nikulina"
    phase_error_budget_deg: float = Field(22.5, gt=0, le=180, description="budget of the scan-range study")

    @model_validator(mode="after")
    def _consistent(self):
        if self.focus_offset_mm is None and self.beam_tilt_deg is None:
            raise ValueError("design.beam_tilt_deg: give beam_tilt_deg or focus_offset_mm "
                             "(the other is solved from the equal-edge ellipse (3.6))")
        if self.construction == "kinber":
            raise ValueError("design.construction: 'kinber' is built from the seed's own central-segment "
                             "parameters, not from edge/focus/tilt inputs (fitting them is unstable at the "
                             "rim); use construction: nikulina")
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
