"""Spec of the single-surface foam lens collimator (seed-000 §1.2, §7.1).

``fabrication.method: printed``: ``material`` is the filament and ``design.refractive_index`` the
lens's index n; the lens is printed as a uniform cubic lattice whose εr_eff = n² (antenna_cad.printed)
inside a solid skin.
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG
from antenna_cad.spec.common import (AutSpec, SheetLayupSpec, SolidSpec, SpecBase, StrictModel, TestZoneSpec,
                                     resolve_material)
from antenna_cad.spec.printed import PrintedSpec, check_material_index


class CollimatorDesign(StrictModel):
    diameter_mm: float = Field(ge=1, le=20000)
    focal_length_mm: float = Field(ge=1, le=200000, description="feed to lens vertex")
    refractive_index: float | None = Field(None, gt=1, le=10,
                                           description="the lens's index n: optional check that it equals √εr of "
                                           "material; with fabrication.method printed, required — the lattice "
                                           "is filled so that its εr_eff = n²")
    phase_error_budget_deg: float = Field(22.5, ge=MIN_DEG, le=180)
    aut: AutSpec | None = Field(None, description="antenna under test behind the flat face: edge margin "
                                "(seed-000 §4.6) and pattern distortion (§4.5); default: a circle, the lens less "
                                "the GO edge margin (2.1) or the test zone if larger, 100 mm behind")
    test_zone: TestZoneSpec = TestZoneSpec()


class CollimatorSpec(SpecBase):
    kind: Literal["collimator"]
    design: CollimatorDesign
    fabrication: Annotated[Union[SheetLayupSpec, SolidSpec, PrintedSpec], Field(discriminator="method")]

    @model_validator(mode="after")
    def _fits(self):
        fab = self.fabrication
        if isinstance(fab, PrintedSpec):
            fab.check_lens(self.material, self.frequency_ghz)
            fab.check_flat_body("the collimator")
            fab.check_uniform_index(self.material, self.design.refractive_index, "the lens")
            return self
        check_material_index(resolve_material(self.material), self.design.refractive_index)
        if isinstance(fab, SheetLayupSpec):
            fab.check_fits_lens(self.design.diameter_mm / 2, "design.diameter_mm")
        return self
