"""manifest.json: the machine-readable summary of a build (DESIGN.md "Output folder")."""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

from antenna_cad import __version__


def sha256(path: Path) -> str:
    """The file's SHA-256, read in blocks (a printed lens's STL is tens of MB)."""
    with path.open("rb") as f:
        return hashlib.file_digest(f, "sha256").hexdigest()


def _clean(value):
    """Floats rounded to 12 significant digits so the JSON is stable and readable; non-finite
    ones become null (strict JSON has no Infinity or NaN)."""
    if isinstance(value, float):
        return float(f"{value:.12g}") if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return value


def write_manifest(out_dir: Path, content: dict) -> None:
    """Write ``content`` plus ``files`` (path, bytes, sha256 of every other file, sorted)."""
    files = sorted(p for p in out_dir.rglob("*") if p.is_file() and p.name != "manifest.json")
    body = dict(content, antenna_cad_version=__version__, units="mm",
                files=[{"path": p.relative_to(out_dir).as_posix(), "bytes": p.stat().st_size,
                        "sha256": sha256(p)} for p in files])
    (out_dir / "manifest.json").write_text(
        json.dumps(_clean(body), indent=2, sort_keys=True, ensure_ascii=False, allow_nan=False) + "\n", encoding="utf-8")
