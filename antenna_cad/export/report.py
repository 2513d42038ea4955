"""report.html: one self-contained page per build (DESIGN.md "Output folder"; issue 6)."""

from __future__ import annotations

import html
from pathlib import Path


def write_report(path: Path, spec, figures, checks, verification, model, fab, parts) -> None:
    rows = "".join(f"<tr><td>{html.escape(c.name)}</td><td>{c.status}</td><td>{html.escape(c.message)}</td></tr>"
                   for c in checks)
    path.write_text(f"<!doctype html><html><head><meta charset='utf-8'><title>{spec.name}</title></head>"
                    f"<body><h1>{spec.name}</h1><table>{rows}</table></body></html>\n", encoding="utf-8")
