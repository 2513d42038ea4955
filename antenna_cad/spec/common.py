"""Spec blocks shared by every design kind (DESIGN.md "Spec skeleton").

Units are in the field names. Models are frozen and forbid unknown keys; bounds live on fields.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal, Union

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, field_validator, model_validator

from antenna_cad.materials import LIBRARY, Material
from antenna_cad.spec.bounds import MAX_LIST, MIN_GHZ, MIN_RATIO, MIN_SHEET_MM, TINY


class StrictModel(BaseModel):
    """Frozen, no unknown keys, every number finite and either 0 or of a magnitude ≥ TINY (a
    denormal like 1e-308 is a typo, and breaks the solvers); ranges on fields (spec.bounds)."""
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    @field_validator("*", mode="after")
    @classmethod
    def _not_tiny(cls, value):
        for x in value if isinstance(value, (tuple, list)) else (value,):
            if isinstance(x, float) and 0 < abs(x) < TINY:
                raise ValueError(f"must be 0 or at least {TINY:g} in magnitude")
        return value


class InlineMaterial(StrictModel):
    """A material given in the spec instead of a library name (e.g. from a board datasheet)."""
    name: str = Field("custom", pattern=r"^[A-Za-z0-9_. -]+$")
    eps_r: float = Field(ge=1.0, le=100.0)
    tan_delta: float = Field(ge=0.0, lt=1.0)
    density_kg_m3: float = Field(ge=1.0, le=25000.0)


def _library_name(value: str) -> str:
    if value not in LIBRARY:
        raise ValueError(f"unknown material {value!r}; library: {', '.join(sorted(LIBRARY))}")
    return value


MaterialRef = Annotated[
    Union[Annotated[str, Tag("library")], Annotated[InlineMaterial, Tag("inline")]],
    Discriminator(lambda v: "library" if isinstance(v, str) else "inline"),
    Field(description="a library material name, or inline {eps_r, tan_delta, density_kg_m3}")]
UNION_TAGS = {"library", "inline", "builtin", "profile_file", "sheet_layup", "solid", "shells", "printed", "number", "auto"}
# (tags are stripped from error paths)


def or_auto(number) -> object:
    """The type ``number`` (with its bounds) or the literal ``"auto"``; a bad value gets one error,
    against the number, instead of one per union member."""
    return Annotated[Union[Annotated[number, Tag("number")], Annotated[Literal["auto"], Tag("auto")]],
                     Discriminator(lambda v: "auto" if v == "auto" else "number")]


def resolve_material(ref: str | InlineMaterial) -> Material:
    if isinstance(ref, str):
        return LIBRARY[_library_name(ref)]
    return Material(ref.name, ref.eps_r, ref.tan_delta, ref.density_kg_m3, "inline in the spec")


class BoardSpec(StrictModel):
    """Stock board size (seed-000 §3.1: XPS boards 600 × 1200 mm)."""
    width_mm: float = Field(600.0, ge=10, le=5000)
    length_mm: float = Field(1200.0, ge=10, le=10000)


class BoxSpec(StrictModel):
    """Clamping box around the pedestal (seed-000 §6.1 option 3); screws only in the box."""
    material: MaterialRef = "plywood"
    wall_thickness_mm: float = Field(12.0, ge=1, le=100)
    clearance_mm: float = Field(0.0, ge=0, le=20)
    screw_diameter_mm: float = Field(4.0, ge=1, le=20)
    screw_spacing_mm: float = Field(150.0, gt=10, le=1000)
    board: BoardSpec = BoardSpec(width_mm=1220.0, length_mm=2440.0)

    @field_validator("material")
    @classmethod
    def _known(cls, v):
        return _library_name(v) if isinstance(v, str) else v


SheetThickness = Annotated[float, Field(ge=MIN_SHEET_MM, le=200)]
XPS_STOCK_MM = (10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 80.0, 100.0)     # common XPS boards (seed-000 §3.1: 10–120 mm)


class SheetLayupSpec(StrictModel):
    """Stepped layup of stock sheets with a pedestal clamped in a box (seed-000 §6)."""
    method: Literal["sheet_layup"]
    sheet_thickness_mm: Annotated[
        or_auto(SheetThickness),
        Field(description="stock board thickness, or auto: the thickest of stock_thicknesses_mm whose "
              "unsanded stack meets the phase budget (the thinnest, with a sanding warning, when none does)")]
    stock_thicknesses_mm: tuple[SheetThickness, ...] = Field(
        XPS_STOCK_MM, min_length=1, max_length=MAX_LIST, description="board thicknesses on offer, for sheet_thickness_mm: auto")
    board: BoardSpec = BoardSpec()
    pedestal_height_mm: float = Field(80.0, ge=50, le=1000)
    pedestal_width_mm: float | None = Field(None, ge=1, le=20000, description="default: 60 % of the lens diameter")
    kerf_mm: float = Field(0.0, ge=0, le=10)
    joining: Literal["dowels", "neck"] = Field(
        "dowels", description="dowels: foam dowels tie each lens disc to its neighbours, no material "
        "added in the aperture; neck: every sheet is one piece, small discs joined to the pedestal by "
        "a neck inside the aperture (reported)")
    dowel_diameter_mm: float = Field(20.0, ge=1, le=200)
    neck_width_mm: float = Field(40.0, ge=1, le=500)
    box: BoxSpec = BoxSpec()
    edge: Literal["stepped", "taper"] = Field(
        "stepped", description="stepped: vertical sheet edges (sanded to the lens); taper: each rim cut as "
        "the cone through the lens profile at the sheet's two faces (hot wire, no sanding)")
    cam: "CamSpec | None" = Field(None, description="hot-wire/drilling G-code for the pieces (cam/)")

    @field_validator("stock_thicknesses_mm")
    @classmethod
    def _distinct(cls, v):
        if len(set(v)) != len(v):
            raise ValueError("thicknesses must be distinct")
        return tuple(sorted(v))

    def check_fits_lens(self, lens_radius_mm: float, diameter_field: str) -> None:
        """Pedestal narrower than the lens and neck narrower than its radius (raises ValueError
        naming the field, for a model validator of the lens spec)."""
        d = 2 * lens_radius_mm
        if self.pedestal_width_mm is not None and self.pedestal_width_mm >= d:
            raise ValueError(f"fabrication.pedestal_width_mm: must be < {diameter_field} "
                             f"({self.pedestal_width_mm:g} ≥ {d:g})")
        if self.edge == "taper" and self.joining == "neck":
            raise ValueError("fabrication.edge: taper needs joining: dowels (a neck inside the aperture is "
                             "no cone)")
        if self.joining == "neck" and self.neck_width_mm >= lens_radius_mm:
            raise ValueError(f"fabrication.neck_width_mm: must be < the lens radius ({lens_radius_mm:g} mm)")


class SolidSpec(StrictModel):
    """One machined (turned/milled) body from a solid blank."""
    method: Literal["solid"]
    stock_allowance_mm: float = Field(3.0, ge=0, le=100, description="blank oversize on every side")


Fabrication = Annotated[Union[SheetLayupSpec, SolidSpec], Field(discriminator="method")]


class OutputsSpec(StrictModel):
    step: bool = True
    stl: bool = True
    templates: bool = True
    report: bool = Field(True, description="report.html: figures, checks, plots, pictures, cut list")
    mesh_tolerance_mm: float = Field(0.05, ge=0.001, le=5, description="absolute chord deviation of meshes")


class TolerancesSpec(StrictModel):
    """Build tolerances for the sensitivity study of the as-built verification."""
    eps_r_tolerance: float = Field(0.01, ge=0, le=1, description="± spread of the material's εr (absolute)")
    thickness_tolerance_mm: float = Field(0.5, ge=0, le=20,
                                          description="± stock board / sheet / machining thickness")
    feed_position_tolerance_mm: float = Field(2.0, ge=0, le=200,
                                              description="± feed placement error, axial and transverse")


class VerificationSpec(StrictModel):
    """Full-wave check of the as-built lens: Meep in cylindrical coordinates, on-axis feed; the
    collimator's scan-edge feed as a sum of azimuthal orders when the budget allows."""
    full_wave: Literal["auto", "on", "off"] = Field(
        "auto", description="auto: run when Meep is installed and the estimated time fits budget_s (the "
        "report says why not otherwise); on: always (error without Meep); off: the fast model only")
    resolution_px_per_lambda: float = Field(16.0, ge=6, le=64, description="grid cells per free-space wavelength")
    plane_offset_lambda: float = Field(2.0, ge=2, le=20, description="aperture plane behind the back face (λ)")
    budget_s: float = Field(120.0, ge=1, le=86400, description="hard cap on the full-wave solver's wall time "
                            "per build (s): auto starts only what fits at the throughput measured on this machine; "
                            "whatever runs stops here, and what did not finish keeps the fast model")
    feed_pattern: Literal["dipole", "cos_q"] = Field(
        "dipole", description="feed far field: short dipole (E-plane cos θ, H-plane 1) or cos^q θ")
    feed_q: float = Field(1.0, ge=MIN_RATIO, le=50, description="q of the cos_q feed pattern")


class AutSpec(StrictModel):
    """Antenna under test in the collimator's field (seed-000 §4.5, §4.6): a circle (diameter_mm)
    or a width_mm × height_mm rectangle (x × y, the cut in the vertical y plane)."""
    diameter_mm: float | None = Field(None, ge=1, le=20000)
    width_mm: float | None = Field(None, ge=1, le=20000)
    height_mm: float | None = Field(None, ge=1, le=20000)
    distance_mm: float | None = Field(None, ge=0, le=100000, description="lens back face to the AUT "
                                      "aperture, l_ant (collimator; default 100 mm, the seed's)")
    pattern: Literal["sum", "sum_and_difference"] = Field(
        "sum_and_difference", description="patterns whose integral errors are computed (difference: odd excitation)")
    taper: int = Field(0, ge=0, le=3, description="k of the AUT amplitude cos^k(π y / L), seed-000 (1.24)")

    @model_validator(mode="after")
    def _one_shape(self):
        rect = (self.width_mm is not None, self.height_mm is not None)
        if self.diameter_mm is not None and any(rect):
            raise ValueError("design.aut: give diameter_mm or width_mm × height_mm, not both")
        if self.diameter_mm is None and not all(rect):
            raise ValueError("design.aut: give diameter_mm, or both width_mm and height_mm")
        return self

    @property
    def span_mm(self) -> float:
        """The lens diameter the AUT needs at least: its diameter or its diagonal."""
        return self.diameter_mm if self.diameter_mm is not None else float(math.hypot(self.width_mm, self.height_mm))


class TestZoneSpec(StrictModel):
    """The quiet zone, as compact ranges specify it: a cylinder (diameter × depth) starting
    ``distance_mm`` behind the back of the stack, scanned on ``planes`` planes across its depth, with
    limits on the amplitude (± about mid-range) and the phase (± about mid-range, piston and tilt
    removed per plane); defaults ±1 dB and ±22.5°/2 (seed-000 §4.1). Every size defaults from the AUT."""
    amplitude_db: float = Field(1.0, ge=0.01, le=20)
    phase_deg: float = Field(11.25, ge=0.01, le=180)
    cross_pol_db: float | None = Field(None, ge=-100, le=0, description="cross-polarization limit (dB to the "
                                       "co-polar level; none: reported, not judged)")
    diameter_mm: float | None = Field(None, ge=1, le=20000, description="default: the AUT's (a rectangle's "
                                      "diagonal), else the largest meeting the limits")
    distance_mm: float | None = Field(None, ge=0, le=100000, description="back of the stack to the zone's near "
                                      "face (default: the AUT's distance)")
    depth_mm: float | None = Field(None, ge=1, le=100000, description="along the axis, away from the lens "
                                   "(default: one zone diameter, at least 2 λ)")
    planes: int | None = Field(None, ge=2, le=200, description="planes scanned across the depth (default: at least "
                               "5, and spaced by at most half the period of the axial caustic of the lens's rim; at most 200)")

    __test__ = False


class SpecBase(StrictModel):
    name: str = Field(pattern=r"^[a-z0-9][a-z0-9._-]*$", max_length=100)
    frequency_ghz: float = Field(ge=MIN_GHZ, le=1000)
    material: MaterialRef
    fabrication: Fabrication
    outputs: OutputsSpec = OutputsSpec()
    tolerances: TolerancesSpec = TolerancesSpec()
    verification: VerificationSpec = VerificationSpec()

    @field_validator("material")
    @classmethod
    def _known_material(cls, v):
        return _library_name(v) if isinstance(v, str) else v


from antenna_cad.spec.cam import CamSpec  # noqa: E402  (the cam block uses StrictModel above)

SheetLayupSpec.model_rebuild()
