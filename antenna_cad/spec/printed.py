"""Spec of ``fabrication.method: printed``: one FDM filament (the spec's ``material``) printed as a
lattice whose local fill sets εr (antenna_cad.printed), inside a solid skin, split to the bed.

The cell must stay well below the wavelength in the filament so the lattice acts as a homogeneous
medium: a ≤ λ/(4·√εr_filament) (the table of antenna_cad.printed is computed at a/λ = 0.12, below
this limit for εr ≤ 4.3).
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from antenna_cad.materials import FILAMENTS
from antenna_cad.printed.lattice import Printable
from antenna_cad.spec.common import InlineMaterial, StrictModel

C_MM_GHZ = 299.792458
FILAMENT_NAMES = tuple(m.name for m in FILAMENTS)


class BedSpec(StrictModel):
    """Printer build volume; parts larger than it are split."""
    x_mm: float = Field(220.0, ge=20, le=2000)
    y_mm: float = Field(220.0, ge=20, le=2000)
    z_mm: float = Field(250.0, ge=20, le=2000)


class PinsSpec(StrictModel):
    """Registration pins across every cut: printed separately, in blind holes of solid bosses."""
    diameter_mm: float = Field(4.0, ge=1, le=50)
    length_mm: float = Field(12.0, ge=2, le=200, description="whole pin; half in each part")
    clearance_mm: float = Field(0.2, ge=0, le=2, description="hole diameter − pin diameter")


class PrintedSpec(StrictModel):
    """FDM-printed lattice lens (cubic: orthogonal rods, the rectilinear infill of a slicer; gyroid: the sheet
    gyroid, a slicer's gyroid infill)."""
    method: Literal["printed"]
    lattice: Literal["cubic", "gyroid"] = "cubic"
    cell_mm: float = Field(ge=0.5, le=100, description="lattice period; ≤ λ/(4·√εr of the filament)")
    nozzle_mm: float = Field(0.4, ge=0.1, le=2)
    min_wall_mm: float | None = Field(None, ge=0.1, le=20, description="thinnest rod or sheet (default: 2 nozzle widths)")
    min_gap_mm: float | None = Field(None, ge=0.1, le=20, description="narrowest opening or channel (default: 2 nozzle widths)")
    layer_height_mm: float = Field(0.2, ge=0.04, le=1.5)
    bed: BedSpec = BedSpec()
    orientation: Literal["axis_up", "axis_flat"] = Field(
        "axis_up", description="sphere: the beam axis along the printer's z (seam across the beam) or on the bed "
        "(seam along it); each half printed on its flat face")
    skin_mm: float = Field(1.2, ge=0, le=50, description="solid outer skin (0: none)")
    registration: PinsSpec | None = Field(PinsSpec(), description="pins across every cut; none: align by hand")
    filament_diameter_mm: float = Field(1.75, ge=1, le=3)
    flow_mm3_s: float = Field(8.0, ge=0.5, le=100, description="mean volumetric flow, for the print-time estimate")
    slicer_check: bool = Field(False, description="slice the 3MF with PrusaSlicer (prusa-slicer on the PATH) and "
                               "report its print time and filament beside the build's estimate; minutes for a "
                               "large lens")
    slicer_timeout_s: float = Field(1800.0, ge=10, le=86400, description="the slicer check's time limit; past it the "
                                    "slicer is stopped and the check warns (not judged)")

    @property
    def wall_mm(self) -> float:
        return self.min_wall_mm if self.min_wall_mm is not None else 2 * self.nozzle_mm

    @property
    def gap_mm(self) -> float:
        return self.min_gap_mm if self.min_gap_mm is not None else 2 * self.nozzle_mm

    @model_validator(mode="after")
    def _printable(self):
        if self.wall_mm < self.nozzle_mm:
            raise ValueError(f"fabrication.min_wall_mm: must be ≥ nozzle_mm ({self.wall_mm:g} < {self.nozzle_mm:g})")
        if self.layer_height_mm > 0.8 * self.nozzle_mm:
            raise ValueError(f"fabrication.layer_height_mm: must be ≤ 0.8 × nozzle_mm ({self.layer_height_mm:g} > "
                             f"{0.8 * self.nozzle_mm:g})")
        if self.wall_mm + self.gap_mm >= self.cell_mm:
            raise ValueError(f"fabrication.cell_mm: must be > min wall + min gap ({self.cell_mm:g} ≤ "
                             f"{self.wall_mm + self.gap_mm:g}): no fill is printable")
        if 0 < self.skin_mm < self.wall_mm:
            raise ValueError(f"fabrication.skin_mm: must be 0 or ≥ the min wall ({self.skin_mm:g} < {self.wall_mm:g})")
        if self.lattice == "gyroid" and Printable("gyroid", self.cell_mm, self.wall_mm, self.gap_mm).fill_range[1] == 0:
            raise ValueError(f"fabrication.cell_mm: no gyroid sheet of a {self.cell_mm:g} mm cell has walls ≥ "
                             f"{self.wall_mm:g} mm and channels ≥ {self.gap_mm:g} mm (its thinnest sheet and narrowest "
                             "channel are 0.15 and 0.27 cells at half fill): use a larger cell, thinner walls or cubic")
        return self

    def check_lens(self, material, frequency_ghz: float) -> None:
        """The filament is a printable material and the cell is small enough at ``frequency_ghz``
        (ValueError naming the field, for the lens spec's model validator)."""
        if isinstance(material, str) and material not in FILAMENT_NAMES:
            raise ValueError(f"material: a printed lens needs a filament ({', '.join(FILAMENT_NAMES)}) or an "
                             f"inline material (got {material!r})")
        eps, _ = filament_eps(material)
        limit = C_MM_GHZ / frequency_ghz / (4 * math.sqrt(eps))
        if self.cell_mm > limit:
            raise ValueError(f"fabrication.cell_mm: must be ≤ λ/(4·√εr) = {limit:.3g} mm at {frequency_ghz:g} GHz "
                             f"in εr {eps:g} (got {self.cell_mm:g})")

    def check_uniform_index(self, material, n: float | None, what: str) -> None:
        """A body printed as a uniform cubic lattice at the index ``design.refractive_index`` (the
        mirror-lens body, the collimator): n given, n² below the filament's εr and at or above the lowest
        εr_eff the printer makes (the thinnest rod, :class:`Printable`); ValueError naming the field."""
        from antenna_cad.printed.homogenization import homogenized
        if self.lattice != "cubic":
            raise ValueError(f"fabrication.lattice: {what} is printed as the cubic lattice (got {self.lattice})")
        if n is None:
            raise ValueError(f"design.refractive_index: required with fabrication.method printed ({what}'s index; "
                             "the lattice is filled so that its εr_eff = n²)")
        eps_f, name = filament_eps(material)
        if n * n >= eps_f:
            raise ValueError(f"design.refractive_index: n² = {n * n:.4g} must be below the filament's εr "
                             f"{eps_f:g} ({name}) for a lattice to print it")
        lowest = float(homogenized("cubic", eps_f).eps_at(
            Printable("cubic", self.cell_mm, self.wall_mm, self.gap_mm).fill_range[0]))
        if n * n < lowest:
            raise ValueError(f"design.refractive_index: n² = {n * n:.4g} must be ≥ {lowest:.4g}, the lowest εr_eff "
                             f"a {self.cell_mm:g} mm cell of {name} prints (rods ≥ {self.wall_mm:g} mm)")

    def check_flat_body(self, what: str) -> None:
        """A body printed along its own axis (the lens between plates, the mirror-lens body): the
        sphere's orientations and pins do not apply."""
        if self.orientation != "axis_up":
            raise ValueError(f"fabrication.orientation: {what} is printed axis_up (its axis along the printer's z; "
                             f"got {self.orientation})")

    def check_height(self, height_mm: float) -> None:
        """A parallel-plate lens holds a whole number of cells between its plates (a cell cut by a plate
        has another fill than the table's)."""
        cells = height_mm / self.cell_mm
        if round(cells) < 1 or abs(cells - round(cells)) > 1e-3:
            whole = max(1, round(cells))
            raise ValueError(f"fabrication.cell_mm: the height between the plates must be a whole number of cells "
                             f"({height_mm:g} mm / {self.cell_mm:g} mm = {cells:.3g}; e.g. {height_mm / whole:.4g} mm)")


def filament_eps(material) -> tuple[float, str]:
    """(εr, name) of a spec's filament: a library name or an inline material."""
    if isinstance(material, InlineMaterial):
        return material.eps_r, material.name
    return next(m.eps_r for m in FILAMENTS if m.name == material), material


def check_material_index(material, n: float | None) -> None:
    """Not printed: ``design.refractive_index``, when given, is a check that it equals √εr of the
    (resolved) material."""
    if n is not None and abs(n - math.sqrt(material.eps_r)) > 1e-4:
        raise ValueError(f"design.refractive_index: {n:g} ≠ √εr = {math.sqrt(material.eps_r):.5g} of material "
                         f"{material.name!r}; give the material with εr = n² = {n * n:.5g}")
