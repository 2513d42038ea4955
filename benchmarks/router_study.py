"""Router files of the flat parts, measured: for the Luneburg ring layup (``cam: {}``) and the X-band
slot array (``fabrication.router`` with a Ø1 mm tool), every board's estimated machine time and the
largest distance error of its toolpath from its parts' outlines ± the tool radius, as
``make-lens check`` measures it (the G-code written, parsed back by gcodeparser).

    ANTENNA_CAD_MEEP_PYTHON=/usr/bin/false python benchmarks/router_study.py

Prints a Markdown table per recipe.
"""

from __future__ import annotations

import sys
from pathlib import Path

import yaml

from antenna_cad.pipeline import prepare
from antenna_cad.spec import parse_spec
from taper_study import cam_findings       # benchmarks/ is the script's folder

ROOT = Path(__file__).resolve().parents[1]
METAL = {"tool_diameter_mm": 1.0, "pass_depth_mm": 0.5, "feed_mm_min": 600, "plunge_mm_min": 100,
         "ramp_length_mm": 5, "tab_width_mm": 2, "tab_height_mm": 0.4}
CASES = (("luneburg-layup-200.yaml", {"cam": {}}), ("x-slot-array-ellipse.yaml", {"router": METAL}))


def study(recipe: str, fabrication: dict) -> list[str]:
    data = yaml.safe_load((ROOT / "recipes" / recipe).read_text())
    data["fabrication"] |= fabrication
    data["outputs"] = {"step": False, "stl": False, "templates": False}
    spec = parse_spec(data)
    plan = prepare(spec)
    findings = {f.file: f for f in cam_findings(spec, plan)}
    rows = [f"### {recipe}", "", "| file | parts | machine time min | toolpath error mm | check |", "|---|---|---|---|---|"]
    errors = []
    for e in plan.fab.cam.entries:
        f = findings[e["file"]]
        err = float(f.message.split("/2 ")[1].split(" mm")[0])
        errors.append(err)
        rows.append(f"| {e['file']} | {len(e['part'].split(', '))} | {e['seconds'] / 60:.1f} | {err:.4f} | "
                    f"{'pass' if f.ok else 'FAIL'} |")
    total = sum(e["seconds"] for e in plan.fab.cam.entries) / 60
    rows += [f"| total | | {total:.1f} | max {max(errors):.4f} | |", ""]
    return rows


if __name__ == "__main__":
    for recipe, fab in CASES:
        sys.stdout.write("\n".join(study(recipe, fab)) + "\n")
