"""Strict numbers in specs: a numeric field takes numbers only. A boolean (YAML 1.1 reads ``on``,
``off``, ``yes``, ``no`` as booleans) or a string (``'1e2'``, or the YAML 1.1 forms ``4:00`` and
``0x78`` that the reader keeps as strings) is refused with its field named, instead of becoming
1, 100, 240 or 120. A field whose values are ``on``/``off`` takes the YAML booleans for them.

The parsed YAML is walked beside the spec model's field types before pydantic sees it (pydantic's
own conversions are lax: ``True`` → 1.0, ``'1e2'`` → 100.0)."""

from __future__ import annotations

import types
from typing import Annotated, Literal, Union, get_args, get_origin

from pydantic import BaseModel

NOT_BOOLEAN = "must be a number, not a boolean (YAML reads on/off/yes/no/true/false as booleans)"
NOT_STRING = "must be a number, not a string (a quoted number, or a YAML 1.1 form such as 4:00 or 0x78)"
Problem = tuple[tuple, str, object]          # (location, rule, value)


def strict_data(model: type[BaseModel], data: object, loc: tuple = ()) -> tuple[object, list[Problem]]:
    """``data`` (a mapping for ``model``) with on/off booleans as words, and every boolean or
    string given to a numeric field."""
    if not isinstance(data, dict):
        return data, []
    out, problems = dict(data), []
    for key, value in data.items():
        field = model.model_fields.get(key) if isinstance(key, str) else None
        if field is not None:
            out[key], found = _value(field.annotation, value, loc + (key,))
            problems += found
    return out, problems


def _value(annotation, value, loc: tuple) -> tuple[object, list[Problem]]:
    origin, args = get_origin(annotation), get_args(annotation)
    if origin is Annotated:
        return _value(args[0], value, loc)
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return strict_data(annotation, value, loc)
    if origin is Literal:
        if isinstance(value, bool) and {"on", "off"} <= set(args):
            return ("on" if value else "off"), []
        return value, []
    if origin in (Union, types.UnionType):
        if isinstance(value, str) and any(value in _words(m) for m in args):
            return value, []
        models = [m for m in map(_bare, args) if isinstance(m, type) and issubclass(m, BaseModel)]
        if models and isinstance(value, dict):
            chosen = [m for m in models if _matches(m, value)]
            return strict_data(chosen[0], value, loc) if len(chosen) == 1 else (value, [])
        for member in args:
            value, found = _value(member, value, loc)
            if found:
                return value, found
        return value, []
    if origin in (tuple, list) and isinstance(value, (list, tuple)):
        kinds = [a for a in args if a is not Ellipsis]
        out, problems = [], []
        for i, item in enumerate(value):
            if len(kinds) == 1 or i < len(kinds):
                item, found = _value(kinds[0] if len(kinds) == 1 else kinds[i], item, loc + (i,))
                problems += found
            out.append(item)
        return out, problems
    if annotation in (int, float) and isinstance(value, (bool, str)):
        return value, [(loc, NOT_BOOLEAN if isinstance(value, bool) else NOT_STRING, value)]
    return value, []


def _bare(annotation):
    return get_args(annotation)[0] if get_origin(annotation) is Annotated else annotation


def _words(annotation) -> tuple:
    annotation = _bare(annotation)
    return get_args(annotation) if get_origin(annotation) is Literal else ()


def _matches(model: type[BaseModel], value: dict) -> bool:
    """Every Literal field of ``model`` (a discriminator such as ``method``) given in ``value`` has
    one of its words."""
    return all(value[k] in _words(f.annotation) for k, f in model.model_fields.items()
               if _words(f.annotation) and k in value)
