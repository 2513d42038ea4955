"""Write docs/reference/spec.md from the specs' JSON Schema (``make-lens schema``): every field of
every kind with its type, unit, range, default and description.

    python docs/gen_spec_reference.py [--check]

``--check`` exits 1 when the committed page differs from what the schema gives (CI).
"""

from __future__ import annotations

import sys
from pathlib import Path

from antenna_cad.spec import json_schema

PAGE = Path(__file__).resolve().parent / "reference" / "spec.md"
UNITS = (("_px_per_lambda", "px/λ"), ("_kg_m3", "kg/m³"), ("_mm3", "mm³"), ("_mm", "mm"), ("_ghz", "GHz"),
         ("_deg", "°"), ("_db", "dB"), ("_rad", "rad"), ("_lambda", "λ"), ("_um", "µm"), ("_s", "s"),
         ("_kg", "kg"), ("_pct", "%"))


def main() -> None:
    text = page(json_schema())
    if "--check" in sys.argv:
        if PAGE.read_text(encoding="utf-8") != text:
            sys.exit(f"{PAGE}: out of date; run python docs/gen_spec_reference.py")
        return
    PAGE.parent.mkdir(exist_ok=True)
    PAGE.write_text(text, encoding="utf-8")


def page(schema: dict) -> str:
    defs = schema["$defs"]
    lines = ["# Spec reference", "",
             "Generated from the JSON Schema of specs (`make-lens schema`) by `docs/gen_spec_reference.py`; "
             "do not edit by hand. A spec is YAML with one `kind`; each section lists that kind's fields "
             "by their dotted path (the path `make-lens` names in its error messages and sweeps use as axes). "
             "Units come from the field name's suffix (`_mm`, `_ghz`, `_deg` …); fields without a suffix "
             "are dimensionless or in the unit the description states. A block given as one of several "
             "variants (`fabrication.method`, …) lists each variant's fields after its own heading.", ""]
    for ref in schema["oneOf"]:
        kind_def = _deref(defs, ref)
        kind = kind_def["properties"]["kind"]["const"]
        lines += [f"## `kind: {kind}`", ""]
        lines += _table(defs, kind_def, "", set())
    return "\n".join(lines) + "\n"


def _table(defs: dict, obj: dict, prefix: str, seen: set[str]) -> list[str]:
    rows, variants = [], []
    required = set(obj.get("required", ()))
    for name, prop in obj.get("properties", {}).items():
        path = f"{prefix}{name}"
        target = _object(defs, prop)
        choices = _variants(defs, prop)
        if choices:
            rows.append(_row(path, prop, defs, name in required, "one of the variants below"))
            variants += [(path, c) for c in choices]
        elif target is not None and _title(prop) not in seen:
            rows.append(_row(path, prop, defs, name in required, "block:"))
            rows += _rows_only(_table(defs, target, path + ".", seen | {_title(prop)}))
        else:
            rows.append(_row(path, prop, defs, name in required))
    lines = ["| field | type | unit | range | default | description |", "|---|---|---|---|---|---|", *rows, ""]
    for path, choice in variants:
        tag = next((f"{k}: {v['const']}" for k, v in choice.get("properties", {}).items() if "const" in v), "")
        lines += [f"#### `{path}` — {tag or choice.get('title', '')}", ""]
        lines += _table(defs, choice, path + ".", seen)
    return lines


def _rows_only(lines: list[str]) -> list[str]:
    """A nested block's rows merged into the parent table; its own variant sections appended after."""
    return [line for line in lines[2:] if line]


def _row(path: str, prop: dict, defs: dict, required: bool, note: str = "") -> str:
    kind = _type(defs, prop)
    unit = next((u for suffix, u in UNITS if path.endswith(suffix)), "")
    default = "required" if required else _fmt(prop.get("default", "—")) if "default" in prop else "optional"
    text = " ".join(filter(None, [prop.get("description", ""), note]))
    return f"| `{path}` | {kind} | {unit} | {_range(defs, prop)} | {default} | {_cell(text)} |"


def _type(defs: dict, prop: dict) -> str:
    if "$ref" in prop:
        return "block"
    if "discriminator" in prop:
        return "variant"
    if "const" in prop:
        return f"`{prop['const']}`"
    if "enum" in prop:
        return " \\| ".join(f"`{v}`" for v in prop["enum"])
    options = prop.get("anyOf") or prop.get("oneOf")
    if options:
        return " or ".join(_type(defs, o) for o in options)
    if prop.get("type") == "array":
        items = prop.get("items", {})
        size = prop.get("minItems"), prop.get("maxItems")
        count = f"{size[0]}" if size[0] is not None and size[0] == size[1] else ""
        inner = _type(defs, items) if items else (
            ", ".join(_type(defs, p) for p in prop.get("prefixItems", ())) or "value")
        return f"list of {count + ' ' if count else ''}{inner}"
    return {"number": "number", "integer": "integer", "string": "text", "boolean": "true/false",
            "null": "null", "object": "mapping"}.get(prop.get("type", ""), prop.get("type", "any"))


def _range(defs: dict, prop: dict) -> str:
    options = [prop] + list(prop.get("anyOf", ()))
    parts = []
    for o in options:
        low = o.get("minimum", o.get("exclusiveMinimum"))
        high = o.get("maximum", o.get("exclusiveMaximum"))
        if low is not None or high is not None:
            left = "(" if "exclusiveMinimum" in o else "["
            right = ")" if "exclusiveMaximum" in o else "]"
            parts.append(f"{left}{_fmt(low) if low is not None else '−∞'}, {_fmt(high) if high is not None else '∞'}{right}")
        if "pattern" in o:
            parts.append(f"`{o['pattern']}`")
        if "maxLength" in o:
            parts.append(f"≤ {o['maxLength']} chars")
        if "minItems" in o and o.get("minItems") != o.get("maxItems"):
            parts.append(f"≥ {o['minItems']} items")
    return ", ".join(dict.fromkeys(parts))


def _object(defs: dict, prop: dict) -> dict | None:
    """The block a field holds: its $ref, or the one $ref of an optional block (``anyOf [ref, null]``)."""
    refs = [o for o in prop.get("anyOf", ()) if "$ref" in o]
    if "$ref" in prop or len(refs) == 1:
        return _deref(defs, prop if "$ref" in prop else refs[0])
    return None


def _variants(defs: dict, prop: dict) -> list[dict]:
    options = [o for o in prop.get("oneOf", prop.get("anyOf", ())) if "$ref" in o]
    return [_deref(defs, o) for o in options] if len(options) > 1 or "discriminator" in prop else []


def _deref(defs: dict, ref: dict) -> dict:
    return defs[ref["$ref"].rsplit("/", 1)[-1]]


def _title(prop: dict) -> str:
    return prop.get("$ref") or next((o["$ref"] for o in prop.get("anyOf", ()) if "$ref" in o), "")


def _fmt(value: object) -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return _cell(", ".join(f"{k}: {_fmt(v)}" for k, v in value.items()))
    if isinstance(value, list):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return _cell(str(value))


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


if __name__ == "__main__":
    main()
