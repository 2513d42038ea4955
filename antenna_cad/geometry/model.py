"""The Model value: labelled solids with their materials, and the checks of solid vs design."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from build123d import Shape

from antenna_cad.materials import Material
from antenna_cad.synthesis.checks import Check

Role = Literal["fabricated", "reference"]


@dataclass(frozen=True)
class ModelPart:
    label: str            # "lens", "sheet-07", "box-floor", ...
    material: Material
    role: Role            # fabricated: a part to make; reference: ideal body, allowance, envelope
    shape: Shape

    @property
    def volume_mm3(self) -> float:
        return float(self.shape.volume)


@dataclass(frozen=True)
class Model:
    parts: tuple[ModelPart, ...]
    checks: tuple[Check, ...]
    step_pcurves: bool = True   # False: STEP without p-curves (optional data; ~2x faster, 3x smaller
                                # for thousands of slot faces)
    cutaway: tuple[str, ...] = ()   # labels left out of the report's pictures so nested parts show

    def part(self, label: str) -> ModelPart:
        return next(p for p in self.parts if p.label == label)


def relative_volume_check(name: str, solid_mm3: float, analytic_mm3: float, what: str,
                          rel_limit: float = 1e-6) -> Check:
    """Solid volume against its analytic integral (DESIGN.md "Tests": geometry vs invariants)."""
    rel = abs(solid_mm3 / analytic_mm3 - 1.0)
    return Check.upper(name, rel, rel_limit, "", f"{what}: relative volume error")
