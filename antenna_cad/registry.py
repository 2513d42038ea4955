"""Design kinds: kind name → its adapter module (synthesize, plan, model, fabricate, summary).

Adapters import CAD libraries lazily, so listing kinds or validating a spec stays fast.
"""

from __future__ import annotations

import importlib
from types import ModuleType

from antenna_cad.spec import SPEC_MODELS

ADAPTERS: dict[str, str] = {
    "collimator": "antenna_cad.kinds.collimator",
    "bifocal": "antenna_cad.kinds.bifocal",
    "luneburg": "antenna_cad.kinds.luneburg",
    "slot_array": "antenna_cad.kinds.slot_array",
    "mirror_lens": "antenna_cad.kinds.mirror_lens",
    "polyfocal": "antenna_cad.kinds.polyfocal",
    "graded": "antenna_cad.kinds.graded",
}
assert set(ADAPTERS) == set(SPEC_MODELS), "every spec kind needs an adapter"


def adapter(kind: str) -> ModuleType:
    return importlib.import_module(ADAPTERS[kind])


def synthesize(spec):
    """Synthesis only (fast, no CAD imports): the design and its physics checks."""
    design = adapter(spec.kind).synthesize(spec)
    return design, list(design.checks)
