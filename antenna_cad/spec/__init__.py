"""Spec loading and validation: YAML → frozen pydantic model of the design kind.

Errors come back as one line per problem: ``file: field.path: rule (got value)``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Union

from pydantic import BaseModel, Field, TypeAdapter, ValidationError

from antenna_cad.spec.bifocal import BifocalSpec
from antenna_cad.spec.collimator import CollimatorSpec
from antenna_cad.spec.common import UNION_TAGS
from antenna_cad.spec.graded import GradedSpec
from antenna_cad.spec.luneburg import LuneburgSpec
from antenna_cad.spec.mirror_lens import MirrorLensSpec
from antenna_cad.spec.reader import ReadError, read_yaml
from antenna_cad.spec.polyfocal import PolyfocalSpec
from antenna_cad.spec.slot_array import SlotArraySpec
from antenna_cad.spec.strict import strict_data

SPEC_MODELS: dict[str, type[BaseModel]] = {
    "collimator": CollimatorSpec,
    "bifocal": BifocalSpec,
    "luneburg": LuneburgSpec,
    "slot_array": SlotArraySpec,
    "mirror_lens": MirrorLensSpec,
    "polyfocal": PolyfocalSpec,
    "graded": GradedSpec,
}


class SpecError(ValueError):
    """A spec that cannot be used; ``lines`` holds one message per problem."""

    def __init__(self, lines: list[str]):
        super().__init__("\n".join(lines))
        self.lines = lines


_WORDING = (("Input should be ", "must be "), ("greater than or equal to ", "≥ "),
            ("greater than ", "> "), ("less than or equal to ", "≤ "), ("less than ", "< "),
            ("Field required", "required field is missing"), ("String should match pattern", "must match the pattern"))


MAX_GOT = 60          # characters of the offending value quoted in a message
MAX_LINES = 20       # problems listed; the rest summed up


def _got(value: object) -> str:
    text = repr(value)
    return text if len(text) <= MAX_GOT else text[:MAX_GOT - 1] + "…"


def _loc(parts) -> str:
    """A field path, odd keys quoted: one line, unambiguous."""
    return ".".join(p if isinstance(p, str) and p.isidentifier() else repr(p) if isinstance(p, str) else str(p)
                    for p in parts if p not in UNION_TAGS)


def _format(source: str, err: dict) -> str:
    loc = _loc(err["loc"])
    msg = err["msg"].removeprefix("Value error, ")
    for long, short in _WORDING:
        msg = msg.replace(long, short)
    got = "" if err["type"] in ("missing", "model_type") else f" (got {_got(err.get('input'))})"
    head = msg.split(": ", 1)[0]
    if (": " in msg and head.replace("_", "").replace(".", "").isalnum()
            and (not loc or head.split(".")[0] == loc.split(".")[0])):
        loc, msg = msg.split(": ", 1)           # model validators name their field and the number
        got = ""
    if err["type"] == "extra_forbidden":
        msg, got = "unknown key (not allowed here)", ""
    if err["type"] in ("union_tag_invalid", "union_tag_not_found"):   # name the tag, not the whole block
        ctx = err.get("ctx", {})
        key = str(ctx.get("discriminator", "")).strip("'")
        loc = f"{loc}.{key}" if loc and key else (key or loc)
        if err["type"] == "union_tag_not_found":
            msg, got = f"required field is missing (one of {ctx.get('expected_tags', '?')})", ""
        else:
            msg, got = f"must be one of {ctx.get('expected_tags', '?')}", f" (got {_got(ctx.get('tag'))})"
            if key == "method" and ctx.get("tag") == "printed":
                msg += " (a printed lattice is made for kinds luneburg, graded, mirror_lens and collimator so far)"
    return f"{source}: {loc or '<root>'}: {msg}{got}"


def parse_spec(data: object, source: str = "<spec>") -> BaseModel:
    """Validate a parsed YAML document; raise SpecError naming every bad field."""
    if not isinstance(data, dict):
        raise SpecError([f"{source}: <root>: must be a mapping of spec fields (got {_got(data)})"])
    kind = data.get("kind")
    if not isinstance(kind, str) or kind not in SPEC_MODELS:
        raise SpecError([f"{source}: kind: must be one of {', '.join(sorted(SPEC_MODELS))} (got {_got(kind)})"])
    data, problems = strict_data(SPEC_MODELS[kind], data)
    lines = [f"{source}: {_loc(loc)}: {rule} (got {_got(value)})" for loc, rule, value in problems]
    if not lines:
        try:
            return SPEC_MODELS[kind].model_validate(data)
        except ValidationError as exc:
            lines = [_format(source, e) for e in exc.errors()]
    if len(lines) > MAX_LINES:
        lines = lines[:MAX_LINES] + [f"{source}: <root>: … and {len(lines) - MAX_LINES} more problems"]
    raise SpecError(lines) from None


def load_spec(path: str | Path) -> BaseModel:
    """Read and validate a spec file (bounded strict YAML, :mod:`antenna_cad.spec.reader`), with a
    machine profile file it names put inline (:mod:`antenna_cad.spec.machine_file`)."""
    from antenna_cad.spec.machine_file import inline_machine_file
    path = Path(path)
    try:
        data = read_yaml(path)
    except ReadError as exc:
        raise SpecError([f"{path}: {exc}"]) from None
    data, problems = inline_machine_file(data, path.parent, str(path))
    if problems:
        raise SpecError(problems)
    return parse_spec(data, str(path))


def json_schema() -> dict:
    """JSON Schema of every spec kind (discriminated on ``kind``)."""
    models = tuple(SPEC_MODELS.values())
    union = models[0] if len(models) == 1 else Annotated[Union[models], Field(discriminator="kind")]
    schema = TypeAdapter(union).json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "antenna_cad lens spec"
    return schema


def json_schema_text() -> str:
    return json.dumps(json_schema(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"
