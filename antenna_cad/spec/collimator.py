"""Spec of the single-surface foam lens collimator (seed-000 §1.2, §7.1)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG
from antenna_cad.spec.common import AutSpec, SheetLayupSpec, SpecBase, StrictModel, TestZoneSpec


class CollimatorDesign(StrictModel):
    diameter_mm: float = Field(ge=1, le=20000)
    focal_length_mm: float = Field(ge=1, le=200000, description="feed to lens vertex")
    phase_error_budget_deg: float = Field(22.5, ge=MIN_DEG, le=180)
    aut: AutSpec | None = Field(None, description="antenna under test behind the flat face: edge margin "
                                "(seed-000 §4.6) and pattern distortion (§4.5); default: a circle, the lens less "
                                "the GO edge margin (2.1) or the test zone if larger, 100 mm behind")
    test_zone: TestZoneSpec = TestZoneSpec()


class CollimatorSpec(SpecBase):
    kind: Literal["collimator"]
    design: CollimatorDesign

    @model_validator(mode="after")
    def _fits(self):
        fab = self.fabrication
        if isinstance(fab, SheetLayupSpec):
            fab.check_fits_lens(self.design.diameter_mm / 2, "design.diameter_mm")
        return self
