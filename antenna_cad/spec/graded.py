"""Spec of the trifocal graded-index lens (seed-001 §3.2; kind ``graded``).

A 2-D (cylindrical) lens whose index varies across the aperture only, n = n(y), synthesized in the
seed's normalised units (D = 1) and scaled by ``design.unit_mm`` (= D in millimetres). ``material``
is the base dielectric whose loss and density the slabs carry; each slab's εr comes from the
synthesized law. Fabrication ``solid``: the slabs are machined from blanks of their permittivity;
``sheet_layup``: each slab cut from foam sheets of its grade, stacked along the extrusion;
``printed``: the lens between the plates printed from one filament (``material``) as a lattice whose
fill follows εr(y) = n(y)², a whole number of cells between the plates, a solid skin on both faces.
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import Field, model_validator

from antenna_cad.spec.bounds import MIN_DEG, MIN_RATIO
from antenna_cad.spec.cam import CamSpec
from antenna_cad.spec.common import BoardSpec, SheetThickness, SolidSpec, SpecBase, StrictModel
from antenna_cad.spec.printed import PrintedSpec


class SlabsSpec(StrictModel):
    """Realization: the lens cut into slabs of constant permittivity (bands of equal thickness in |y|)."""
    count: int = Field(8, ge=1, le=200, description="slabs from the axis to the edge (mirrored below the axis)")


class GradedDesignSpec(StrictModel):
    n0: float = Field(gt=1.0, le=4.0, description="index on the axis n_o")
    m: float = Field(ge=MIN_RATIO, le=100.0, description="layer-1 law n² = n0² − m y² (3.11)")
    a2: float = Field(ge=-10.0, le=10.0, description="initial segment x1 = −d1 + a2 y² + a4 y⁴ (3.12)")
    a4: float = Field(ge=-100.0, le=100.0)
    y_a: float = Field(gt=-0.45, lt=0.0, description="lower end y_A of the initial segment (it spans y_A … −y_A)")
    rho: float = Field(gt=0.05, le=100.0, description="central focal distance ρ (from the surface-1 vertex)")
    rho_prime: float = Field(gt=0.05, le=100.0, description="ρ' (from the surface-2 vertex)")
    rho1: float = Field(gt=0.05, le=100.0, description="side focal distance ρ1 = |F1 A|")
    rho1_prime: float = Field(gt=0.05, le=100.0, description="ρ1' = |B F1'|")
    thickness: float = Field(1.0, gt=0.01, le=10.0, description="axial thickness d_o = d1 + d2")
    d1_fraction: float = Field(0.5, ge=0.01, lt=1.0, description="d1 / d_o: only places the lens on the axis "
                               "(the medium does not vary along x, so the split does not change the lens)")
    unit_mm: float = Field(gt=1.0, le=1e5, description="aperture D in millimetres (the seed's unit)")
    height_mm: float = Field(gt=0.1, le=1e4, description="extrusion height of the cylindrical lens")
    view_angle_deg: float = Field(80.0, ge=MIN_DEG, lt=120, description="full view angle of the σ study")
    points: int = Field(41, ge=11, le=401, description="points of the initial segment (construction resolution)")
    slabs: SlabsSpec = SlabsSpec()

    @model_validator(mode="after")
    def _law(self):
        if self.n0**2 - self.m * self.y_a**2 <= 1.0:
            raise ValueError("design.m: n0² − m·y_A² must stay above 1 over the initial segment")
        return self


class GradedLayupSpec(StrictModel):
    """Every slab cut from foam sheets of its grade (the slab's εr), stacked along the extrusion
    between the plates; each sheet's outline is its slab's section."""
    method: Literal["sheet_layup"]
    sheet_thickness_mm: SheetThickness = Field(description="foam sheet thickness; a top layer left over by "
                                               "design.height_mm is planed down")
    board: BoardSpec = BoardSpec()
    kerf_mm: float = Field(0.0, ge=0, le=10, description="cutting kerf (the tool path is offset by half)")
    cam: CamSpec | None = Field(None, description="hot-wire G-code per slab piece (straight cuts: the lens is "
                                "planar, so the sheet outlines are exact; cam/)")


GradedFabrication = Annotated[Union[GradedLayupSpec, SolidSpec, PrintedSpec], Field(discriminator="method")]


class GradedSpec(SpecBase):
    kind: Literal["graded"]
    fabrication: GradedFabrication
    design: GradedDesignSpec

    @model_validator(mode="after")
    def _printed(self):
        fab = self.fabrication
        if isinstance(fab, PrintedSpec):
            fab.check_lens(self.material, self.frequency_ghz)
            fab.check_height(self.design.height_mm)
            fab.check_flat_body("the graded lens")
        return self
