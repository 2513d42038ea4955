"""Stepped vs taper-cut sheet stacks (``fabrication.edge``), measured.

    python benchmarks/taper_study.py [--full-wave]

For the Ø0.5 m lens at 20/50/100 mm sheets and the Ø1.1 m lens at 50 mm: stepped − ideal p-p and
RMS on axis by GO (the exact trace of the stack as cut) and by the fast sub-wavelength model (and by
Meep with ``--full-wave`` when python3-meep is there); the stock ``sheet_thickness_mm: auto`` picks
with and without taper; the hot-wire cut time of the taper stack and the largest G-code
reconstruction error over its sheets (the G-code written, parsed back by gcodeparser and checked as
``make-lens check`` does). Prints Markdown tables.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

import yaml

from antenna_cad.export.check_cam import check_cam
from antenna_cad.fullwave.verify import fast_model
from antenna_cad.asbuilt.revolved import modelled_stats, revolved
from antenna_cad.kinds.collimator import _lens
from antenna_cad.asbuilt.taper import Taper
from antenna_cad.pipeline import prepare
from antenna_cad.registry import adapter
from antenna_cad.spec import parse_spec

ROOT = Path(__file__).resolve().parents[1]
CASES = (("xps-collimator-0.5m.yaml", 20), ("xps-collimator-0.5m.yaml", 50), ("xps-collimator-0.5m.yaml", 100),
         ("xps-collimator-1.1m.yaml", 50))
CAM = {"travel_mm": [1600, 1600], "tower_span_mm": 200}


def spec_of(recipe: str, **fabrication):
    data = yaml.safe_load((ROOT / "recipes" / recipe).read_text())
    data["fabrication"] |= fabrication
    data.setdefault("verification", {})["full_wave"] = "auto" if "--full-wave" in sys.argv else "off"
    return parse_spec(data)


def cam_findings(spec, plan) -> list:
    """``make-lens check``'s G-code findings on the plan's files, written to a scratch folder."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name, text in plan.fab.files.items():
            (folder / name).parent.mkdir(parents=True, exist_ok=True)
            (folder / name).write_text(text)
        manifest = {"spec": json.loads(spec.model_dump_json()), "cam": list(plan.fab.cam.entries)}
        return check_cam(folder, manifest)


def cam_figures(spec, plan) -> tuple[float, float]:
    """(total cut seconds, largest reconstruction error mm) of the plan's G-code."""
    errors = [float(f.message.split(": ")[1].split(" mm")[0]) for f in cam_findings(spec, plan)
              if f.check == "cam_surface" and "cone" in f.message]
    return plan.fab.cam.seconds, max(errors)


def main() -> None:
    print("| lens | sheets mm | edge | GO p-p° | GO RMS° | model p-p° | model RMS° | full-wave p-p° | full-wave RMS° "
          "| largest gap mm | cut time min | G-code error mm |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for recipe, t in CASES:
        for edge in ("stepped", "taper"):
            extra = {"cam": CAM} if edge == "taper" else {}
            spec = spec_of(recipe, sheet_thickness_mm=t, edge=edge, **extra)
            plan = prepare(spec)
            kind = adapter(spec.kind)
            v = kind.verify(spec, plan.design, plan.layup, plan.fab).figures
            lens = _lens(spec, plan.design, plan.layup)
            model = modelled_stats(lens, fast_model(revolved(lens, plan.layup), spec.verification), "stepped", lens.feed)
            fw = [v.get(f"fullwave_stepped_minus_ideal_{k}") for k in ("p2p_deg", "rms_deg")]
            cut, err = cam_figures(spec, plan) if edge == "taper" else (None, None)
            gap = max(Taper(lens, plan.layup).largest_gap_mm()) if edge == "taper" else None
            cells = [recipe.removesuffix(".yaml"), t, edge, v["stepped_on_axis_p2p_deg"], v["stepped_on_axis_rms_deg"],
                     model.p2p_deg, model.rms_deg, *fw, gap, cut / 60 if cut else None, err]
            print("| " + " | ".join("—" if c is None else f"{c:.2f}" if isinstance(c, float) else str(c)
                                    for c in cells) + " |", flush=True)
    print("\n| lens | auto, stepped | auto, taper |\n|---|---|---|")
    for recipe in ("xps-collimator-0.5m.yaml", "xps-collimator-1.1m.yaml"):
        picks = [prepare(spec_of(recipe, sheet_thickness_mm="auto", edge=e)).layup.sheet_thickness_mm
                 for e in ("stepped", "taper")]
        print(f"| {recipe.removesuffix('.yaml')} | {picks[0]:g} mm | {picks[1]:g} mm |")


if __name__ == "__main__":
    if "--full-wave" not in sys.argv:
        os.environ.setdefault("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/false")
    main()
