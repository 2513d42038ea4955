"""``fabrication.cam.machine: <file>.yaml``: a machine profile kept in its own YAML file, read once
when the spec is loaded (relative to the spec's folder) and put in the spec inline, so the build,
its manifest and ``make-lens check`` all see the same profile and nothing else is read later.

The file holds the keys of an inline profile (:class:`antenna_cad.spec.cam.MachineSpec`); a bad
one is refused in one line naming the spec's field, the file and the profile's key.
"""

from __future__ import annotations

from pathlib import Path

from pydantic import ValidationError

from antenna_cad.spec import _WORDING
from antenna_cad.spec.cam import MachineSpec
from antenna_cad.spec.reader import ReadError, read_yaml

SUFFIXES = (".yaml", ".yml")
FIELD = "fabrication.cam.machine"


def inline_machine_file(data: object, folder: Path, source: str) -> tuple[object, list[str]]:
    """``data`` with a profile file named by ``fabrication.cam.machine`` replaced by its contents,
    and the problem lines (``source: fabrication.cam.machine: …``) of a file that cannot be used."""
    cam = data.get("fabrication", {}).get("cam") if isinstance(data, dict) and isinstance(
        data.get("fabrication"), dict) else None
    name = cam.get("machine") if isinstance(cam, dict) else None
    if not isinstance(name, str) or not name.lower().endswith(SUFFIXES):
        return data, []
    path = folder / name
    try:
        profile = read_yaml(path)
    except ReadError as exc:
        return data, [f"{source}: {FIELD}: {name}: {str(exc).removeprefix('file: ')}"]
    if not isinstance(profile, dict):
        return data, [f"{source}: {FIELD}: {name}: must be a mapping of profile keys (kind, axes, travel_mm, …)"]
    try:
        MachineSpec.model_validate(profile)
    except ValidationError as exc:
        return data, [_line(source, name, e) for e in exc.errors()]
    fabrication = data["fabrication"] | {"cam": cam | {"machine": profile}}
    return data | {"fabrication": fabrication}, []


def _line(source: str, name: str, err: dict) -> str:
    key = ".".join(str(p) for p in err["loc"]) or "<root>"
    msg = err["msg"].removeprefix("Value error, ")
    for long, short in _WORDING:
        msg = msg.replace(long, short)
    if err["type"] == "extra_forbidden":
        return f"{source}: {FIELD}: {name}: {key}: unknown key (not allowed here)"
    got = "" if err["type"] == "missing" else f" (got {err.get('input')!r})"
    return f"{source}: {FIELD}: {name}: {key}: {msg}{got}"
