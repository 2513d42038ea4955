"""The sweep file: a base spec, axes over its fields, a mode, the figures to collect, objectives.

    name: collimator-trade
    base: ../xps-collimator-0.5m.yaml          # a spec file (relative to this file) or an inline spec
    set: {material: {name: foam, eps_r: 1.047, tan_delta: 2.0e-4, density_kg_m3: 33}}   # fixed changes
    mode: figures                              # figures | build
    axes:                                      # dotted spec paths; their product is the sweep
      design.focal_length_mm: {from: 2000, to: 8000, steps: 13}
      fabrication.sheet_thickness_mm: [20, 30, 50]
      material.eps_r: [1.03, 1.047, 1.07]
      material.density_kg_m3: [21, 33, 49]
    linked: [[material.eps_r, material.density_kg_m3]]   # these vary together (one axis)
    figures: [thickness_mm, mass_kg, fabricated_on_axis_p2p_deg]
    objectives: {mass_kg: min, fabricated_on_axis_p2p_deg: min}
    tls: {ca_file: ca.pem, cert: client.pem, key: client-key.pem}   # for --scheduler tls://HOST:PORT

Full-wave verification is off in every variant unless the sweep file asks for it (``set`` or an axis
naming ``verification.full_wave``): a sweep of hundreds of variants runs on the fast model. Errors name the file, the field and the rule, like spec errors (:class:`antenna_cad.spec.SpecError`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal, NamedTuple, Union

import yaml
from pydantic import Field, ValidationError, model_validator

from antenna_cad.spec import SpecError
from antenna_cad.spec.common import StrictModel

MAX_VARIANTS = 100_000


class Range(StrictModel):
    """``steps`` evenly spaced values from ``from`` to ``to``, both included."""
    start: float = Field(alias="from")
    stop: float = Field(alias="to")
    steps: int = Field(ge=2, le=10_000)

    def values(self) -> list[float | int]:
        span = self.stop - self.start
        values = [self.start + span * i / (self.steps - 1) for i in range(self.steps)]
        if all(float(v).is_integer() for v in values):      # integer fields (layer counts) stay integers
            return [int(v) for v in values]
        return values


AxisValues = Union[Range, list[Any]]
FULL_WAVE = "verification.full_wave"


class TlsSpec(StrictModel):
    """Certificates for ``--scheduler tls://…`` (PEM files, relative to the sweep file)."""
    ca_file: str = Field(description="the certificate authority that signed the scheduler's and workers' certificates")
    cert: str = Field(description="this client's certificate")
    key: str | None = Field(None, description="its private key, when not in the cert file")


class SweepSpec(StrictModel):
    name: str = Field(pattern=r"^[a-z0-9][a-z0-9._-]*$", max_length=100)
    base: Union[str, dict[str, Any]] = Field(description="spec file (relative to the sweep file) or inline spec")
    set: dict[str, Any] = Field(default_factory=dict, description="dotted path → value applied to every variant")
    mode: Literal["figures", "build"] = "figures"
    axes: dict[str, AxisValues] = Field(min_length=1)
    linked: list[list[str]] = Field(default_factory=list, description="axes that vary together")
    figures: list[str] = Field(min_length=1)
    objectives: dict[str, Literal["min", "max"]] = Field(default_factory=dict)
    tls: TlsSpec | None = Field(None, description="certificates for a tls:// scheduler")

    @model_validator(mode="after")
    def _rules(self):
        for path, values in self.axes.items():
            if isinstance(values, list) and not values:
                raise ValueError(f"axes.{path}: needs at least one value")
        grouped = [p for group in self.linked for p in group]
        for path in grouped:
            if path not in self.axes:
                raise ValueError(f"linked: {path!r} is not an axis")
        if len(set(grouped)) != len(grouped):
            raise ValueError("linked: an axis is in more than one group")
        for group in self.linked:
            lengths = {len(self.axis_values(p)) for p in group}
            if len(lengths) > 1:
                raise ValueError(f"linked: {', '.join(group)} must have as many values each (got {sorted(lengths)})")
        for name in self.objectives:
            if name not in self.figures:
                raise ValueError(f"objectives.{name}: must be one of the figures collected")
        count = 1
        for group in self.axis_groups():
            count *= len(self.axis_values(group[0]))
        if count > MAX_VARIANTS:
            raise ValueError(f"axes: {count} variants (at most {MAX_VARIANTS})")
        return self

    def axis_values(self, path: str) -> list:
        values = self.axes[path]
        return values.values() if isinstance(values, Range) else list(values)

    def asks_for_full_wave(self) -> bool:
        """The sweep file sets ``verification.full_wave`` (or the whole ``verification``) or sweeps it."""
        return any(p in (FULL_WAVE, "verification") for p in (*self.set, *self.axes))

    def axis_groups(self) -> list[list[str]]:
        """Axes in file order, linked ones as one group (at the place of their first member)."""
        groups, seen = [], set()
        for path in self.axes:
            if path in seen:
                continue
            group = next((g for g in self.linked if path in g), [path])
            groups.append(list(group))
            seen.update(group)
        return groups


class SweepFile(NamedTuple):
    sweep: SweepSpec
    base: dict            # the base spec document (a mapping, not yet validated)
    base_source: str      # its file, for the spec loader's messages
    source: str           # the sweep file


def load_sweep(path: str | Path) -> SweepFile:
    """Read and validate a sweep file and read its base spec (SpecError naming file and field)."""
    path = Path(path)
    data = _read_yaml(path)
    try:
        sweep = SweepSpec.model_validate(data)
    except ValidationError as exc:
        raise SpecError([_line(str(path), e) for e in exc.errors()]) from None
    if isinstance(sweep.base, dict):
        return SweepFile(sweep, sweep.base, f"{path} (base)", str(path))
    base_path = (path.parent / sweep.base)
    base = _read_yaml(base_path)
    if not isinstance(base, dict):
        raise SpecError([f"{base_path}: <root>: must be a mapping of spec fields"])
    return SweepFile(sweep, base, str(base_path), str(path))


def _read_yaml(path: Path):
    try:
        return yaml.safe_load(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise SpecError([f"{path}: cannot read: {exc.strerror}"]) from None
    except yaml.YAMLError as exc:
        raise SpecError([f"{path}: not valid YAML: {str(exc).splitlines()[0]}"]) from None


def _line(source: str, err: dict) -> str:
    loc = ".".join(str(p) for p in err["loc"] if p not in ("Range", "list[any]", "str", "dict[str,any]"))
    msg = err["msg"].removeprefix("Value error, ")
    if not loc and ": " in msg:
        loc, msg = msg.split(": ", 1)
    if err["type"] == "extra_forbidden":
        msg = "unknown key (not allowed here)"
    return f"{source}: {loc or '<root>'}: {msg}"
