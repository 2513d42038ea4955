"""End-to-end build of the slot_array kind (seed-003) through the pipeline and the CLI."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
import yaml

from antenna_cad.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
X_RECIPE = ROOT / "recipes" / "x-slot-array-ellipse.yaml"
KA_RECIPE = ROOT / "recipes" / "ka-slot-array-two-mirror.yaml"
ML_RECIPE = ROOT / "recipes" / "ka-slot-array-mirror-lens.yaml"
TRI_RECIPE = ROOT / "recipes" / "ka-slot-array-trifocal-two-mirror.yaml"
TRI_ML_RECIPE = ROOT / "recipes" / "ka-slot-array-trifocal-mirror-lens.yaml"


@pytest.fixture(scope="module")
def x_build(tmp_path_factory):
    from antenna_cad.pipeline import build
    from antenna_cad.registry import synthesize
    spec = load_spec(X_RECIPE)
    design, _ = synthesize(spec)
    return spec, design, build(spec, tmp_path_factory.mktemp("slot"))


@pytest.mark.parametrize("recipe", [X_RECIPE, KA_RECIPE, ML_RECIPE, TRI_RECIPE, TRI_ML_RECIPE])
def test_recipes_validate_and_synthesise(recipe):
    from antenna_cad.registry import synthesize
    spec = load_spec(recipe)
    design, checks = synthesize(spec)
    assert spec.kind == "slot_array"
    assert not [c for c in checks if c.status == "fail"]
    if recipe is KA_RECIPE:
        assert 3000 <= design.slots.count <= 3400 and spec.array.count == 40


def test_x_build_outputs(x_build):
    spec, design, result = x_build
    files = set(result.files)
    guides = spec.array.count
    assert {f"{spec.name}.step", "slots.csv", "cutlist.csv", "manifest.json",
            f"templates/{spec.name}-templates.pdf"} <= files
    for g in range(guides):
        assert f"stl/waveguide-{g:02d}.stl" in files and f"stl/core-{g:02d}.stl" in files
        assert f"templates/top-{g:02d}.dxf" in files
    assert {"templates/plate-0.dxf", "templates/plate-1.dxf", "templates/mirror-1.dxf",
            "stl/mirror-1.stl", "stl/horn-3.stl"} <= files
    assert not [c for c in result.checks if c.status == "fail"]
    assert {c.name: c for c in result.checks}["model_slot_count"].status == "pass"


def test_step_reimport_parts_and_labels(x_build):
    from build123d import import_step
    spec, design, result = x_build
    top = import_step(str(result.out_dir / f"{spec.name}.step"))
    groups = {g.label: [c.label for c in g.children] for g in top.children}
    n = spec.array.count
    expected_fab = {f"{kind}-{g:02d}" for g in range(n) for kind in ("waveguide", "top", "core", "load")} \
        | {"plate-0", "plate-1", "mirror-1"} | {f"horn-{k}" for k in range(1, spec.feeds.count + 1)}
    assert set(groups) == {"fabricated"}
    assert set(groups["fabricated"]) == expected_fab


def test_waveguide_body_stl_watertight(x_build):
    import trimesh
    _, _, result = x_build
    for label in ("waveguide-00", "top-00", "top-09", "core-09", "load-09", "horn-1", "plate-1"):
        mesh = trimesh.load(result.out_dir / "stl" / f"{label}.stl")
        mesh.merge_vertices()
        assert mesh.is_watertight, label
    import json
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    assert all(p["valid"] and p["watertight"] for p in manifest["parts"])


def test_slots_csv_matches_synthesis(x_build):
    _, design, result = x_build
    with open(result.out_dir / "slots.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == design.slots.count
    assert {"guide", "slot", "x_mm", "y_mm", "length_mm", "width_mm", "offset_mm"} <= set(rows[0])
    assert abs(float(rows[5]["length_mm"]) - float(design.slots.length_mm[5])) < 1e-3


def test_dxf_audit_and_slot_count(x_build):
    import ezdxf
    spec, design, result = x_build
    for g in (0, spec.array.count // 2):
        doc = ezdxf.readfile(result.out_dir / "templates" / f"top-{g:02d}.dxf")
        auditor = doc.audit()
        assert not auditor.has_errors
        cut = [e for e in doc.modelspace() if e.dxf.layer == "CUT"]
        assert len(cut) == 1 + int((design.slots.guide_index == g).sum())   # outline + slots
        assert doc.units == ezdxf.units.MM
    doc = ezdxf.readfile(result.out_dir / "templates" / "plate-1.dxf")
    assert not doc.audit().has_errors
    assert len([e for e in doc.modelspace() if e.dxf.layer == "CUT"]) == 2   # outline + coupling slot


def test_bad_spec_fails_slot_check_cli_exit_2(tmp_path):
    from typer.testing import CliRunner

    from antenna_cad.cli import app
    data = yaml.safe_load(X_RECIPE.read_text())
    data["slots"]["width_mm"] = 9.0           # slots wider than the broad wall allows
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2
    assert "slots.width_mm" in result.output


def test_bad_beamformer_params_name_the_field(tmp_path):
    from antenna_cad.spec import SpecError, parse_spec
    data = yaml.safe_load(X_RECIPE.read_text())
    del data["beamformer"]["focal_separation_mm"]
    with pytest.raises(SpecError, match="beamformer.focal_separation_mm"):
        parse_spec(data)


@pytest.mark.slow
def test_ka_build_writes_its_step(tmp_path):
    """The Ka recipe end to end with its STEP (its time is benchmarks/run.py's, not a test's)."""
    from antenna_cad.pipeline import build
    spec = load_spec(KA_RECIPE)
    spec = spec.model_copy(update={"outputs": spec.outputs.model_copy(update={"stl": False, "templates": False})})
    result = build(spec, tmp_path)
    step = result.out_dir / f"{spec.name}.step"
    assert f"{spec.name}.step" in result.files and step.read_text(errors="replace").startswith("ISO-10303-21;")


# --- horns, plates, guide ends (model and layout) ---------------------------------------------

@pytest.fixture(scope="module")
def x_model():
    from antenna_cad.registry import adapter, synthesize
    spec = load_spec(X_RECIPE)
    design, _ = synthesize(spec)
    kind = adapter(spec.kind)
    return spec, design, kind.model(spec, design, None, ()), kind


def test_horns_are_hollow_open_and_flanged(x_model):
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_IN

    from antenna_cad.geometry import kernel
    from antenna_cad.geometry.slot_layout import horn_outlines
    spec, design, model, kind = x_model
    t, h = spec.fabrication.broad_wall_mm, spec.beamformer.layer_height_mm
    f = design.feeds
    for k, horn in enumerate(horn_outlines(design, kind._sizes(spec)), start=1):
        solid = model.part(f"horn-{k}").shape
        assert kernel.is_valid(solid) and len(kernel.solids(solid)) == 1
        # metal = footprint over the full height less the channel over the layer height
        analytic = horn.footprint.area * (2 * t + h) - horn.channel.area * h
        assert kernel.volume(solid) == pytest.approx(analytic, rel=1e-6)
        assert horn.channel.area > 0.5 * horn.footprint.area              # hollow, not an envelope
        zc = float(np.mean(kernel.bounding_box([solid]), axis=0)[2])
        c, aim = f.aperture_centres_mm[k - 1], f.aim[k - 1]
        inside = lambda p, dz=0.0: BRepClass3d_SolidClassifier(                     # noqa: E731
            solid, gp_Pnt(float(p[0]), float(p[1]), zc + dz), 1e-6).State() == TopAbs_IN
        assert not inside(c - 1.0 * aim) and not inside(c - f.length_mm / 2 * aim)   # channel is air
        back = c - (f.length_mm + spec.feeds.flange_thickness_mm / 2) * aim
        assert not inside(back)                                                      # throat port
        side = np.array([-aim[1], aim[0]])
        collar = back + side * (f.throat_mm[0] / 2 + spec.feeds.wall_mm + spec.feeds.flange_mm / 2)
        assert inside(collar)                                                        # flange metal
        assert inside(c - 1.0 * aim, h / 2 + t / 2)                                  # E-plane wall
        assert f.throat_mm[1] == f.aperture_mm[1] == h                               # matches the layer


def test_plates_are_notched_along_the_horn_apertures(x_model):
    from shapely.geometry import Point

    from antenna_cad.geometry.slot_layout import horn_outlines, plate_polygon
    spec, design, model, kind = x_model
    horns = horn_outlines(design, kind._sizes(spec))
    for k in (0, 1):
        plate = plate_polygon(design, k, kind._sizes(spec), horns)
        for horn, c in zip(horns, design.feeds.aperture_centres_mm):
            assert plate.intersection(horn.footprint).area < 1e-6
            assert plate.exterior.distance(Point(c)) < 1e-6          # the layer opens into the horn
    assert {c.name: c for c in model.checks}["feed_horns_clear_of_beamformer"].status == "pass"


def test_matched_loads_fill_the_guide_ends(x_model):
    from antenna_cad.geometry.kernel import bounding_box, volume
    spec, design, model, _ = x_model
    a, h = spec.waveguide.width_mm, spec.waveguide.height_mm
    lam_g = float(__import__("antenna_cad.synthesis.slot_array", fromlist=["x"]).guide_wavelength_mm(
        spec.band.min_ghz, a, spec.fill_eps_r))
    assert design.termination == "matched_load" and design.load_length_mm == pytest.approx(lam_g)
    for g in (0, 7):
        load, core = model.part(f"load-{g:02d}").shape, model.part(f"core-{g:02d}").shape
        assert volume(load) == pytest.approx(a * design.load_length_mm * h / 2, rel=1e-9)     # wedge
        lo, hi = bounding_box([model.part(f"waveguide-{g:02d}").shape])
        cavity_len = hi[1] - spec.fabrication.broad_wall_mm - lo[1]            # end wall closes it
        assert volume(core) + volume(load) == pytest.approx(a * h * cavity_len, rel=1e-9)


def test_short_circuit_ends_warn_and_have_no_load(tmp_path):
    from antenna_cad.registry import adapter, synthesize
    data = yaml.safe_load(X_RECIPE.read_text())
    data["waveguide"]["termination"] = "short"
    from antenna_cad.spec import parse_spec
    spec = parse_spec(data)
    design, checks = synthesize(spec)
    c = {c.name: c for c in checks}["termination"]
    assert c.status == "warn" and "-10.0 dB" in c.message
    model = adapter(spec.kind).model(spec, design, None, ())
    labels = {p.label for p in model.parts}
    assert not any(label.startswith("load-") for label in labels) and "waveguide-03" in labels


def test_design_angle_sets_the_auto_period():
    from antenna_cad.registry import synthesize
    from antenna_cad.spec import SpecError, parse_spec
    from antenna_cad.synthesis.slot_array import period_for_angle_mm
    data = yaml.safe_load(KA_RECIPE.read_text())
    data["slots"] |= {"period_mm": "auto", "design_angle_deg": 10.0}
    data["beamformer"]["slot_line_offset_mm"] = 9.0
    design, _ = synthesize(parse_spec(data))
    assert design.slots.period_mm == pytest.approx(period_for_angle_mm(30.0, 5.0, 2.2, np.radians(80.0)))
    assert np.degrees(np.pi / 2 - design.scan.beta_design_rad) == pytest.approx(10.0, abs=1e-9)
    data["slots"]["period_mm"] = 8.6
    with pytest.raises(SpecError, match="slots.design_angle_deg"):
        parse_spec(data)


def test_min_coupling_gap_is_enforced(tmp_path):
    from typer.testing import CliRunner

    from antenna_cad.cli import app
    data = yaml.safe_load(X_RECIPE.read_text())
    data["slots"]["min_coupling_gap_mm"] = 7.8          # d2 of seed-003 §2.4
    path = tmp_path / "gap.yaml"
    path.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2 and "beamformer.slot_line_offset_mm" in result.output


# --- as-built verification -----------------------------------------------------------

def test_verification_figures_reach_the_manifest(x_build):
    import json
    _, _, result = x_build
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    fig = manifest["verification"]["figures"]
    assert fig["design_focus_phase_rms_deg"] < 1e-4
    assert 0 <= fig["phase_rms_deg_ideal_worst_feed"] < 5 and fig["phase_rms_deg_as_built_worst_feed"] < 5
    assert fig["period_written_mm"] == pytest.approx(23.5, abs=1e-6)
    assert {k for k in fig if k.startswith("tolerance_loss_db_")} >= {
        "tolerance_loss_db_fill_eps_r_all_guides", "tolerance_loss_db_guide_width_all_guides",
        "tolerance_loss_db_feed_position_along_the_axis"}
    tables = {t["name"]: t for t in manifest["verification"]["tables"]}
    assert set(tables) == {"feeds", "slots", "sensitivity", "fov-sigma", "slot-patterns"}
    from antenna_cad.synthesis.slot_array.fov import reference_curves
    rows = tables["fov-sigma"]["rows"]                                     # this design + the reference formers
    assert len(rows) == 1 + len(reference_curves()) and "trifocal_mirror_lens" in {r[0] for r in rows}
    assert 0 < fig["sigma_fov80_design"] < 5.6e-4 * 2
    assert len(tables["slot-patterns"]["rows"]) == 2 * 5                   # ideal and as written, every horn
    assert 20 < fig["frequency_scan_sector_deg_fabricated"] < 40           # thesis (FEM): single mirror ≈ 30°
    assert fig["pattern_fabricated_horn3_gain_dbi"] < fig["pattern_fabricated_horn3_directivity_dbi"]
    assert len(tables["feeds"]["rows"]) == 5
    assert [r[-1] for r in tables["sensitivity"]["rows"]].count("dominant") == 1
    assert {c.name for c in result.checks} >= {"as_built_phase_rms", "slot_table_period", "tolerance_budget"}


def test_verification_plots_are_complete(x_model):
    from antenna_cad.registry import adapter
    spec, design, _, kind = x_model
    fab = kind.fabricate(spec, design, None, ())
    v = adapter(spec.kind).verify(spec, design, None, fab)
    plots = {p.name: p for p in v.plots}
    assert set(plots) == {"scan-curves", "beamformer-rays", "slot-phase", "sensitivity", "fov-sigma",
                          "pattern-elevation", "gain-vs-frequency", "beam-vs-frequency"}
    assert plots["beamformer-rays"].equal_aspect
    for p in v.plots:
        for s in p.series:
            assert s.x.shape == s.y.shape and s.x.ndim == 1
    labels = [s.label for s in plots["scan-curves"].series]
    assert {"harmonic -1, design", "harmonic 0, design", "harmonic -2, design",
            "centre feed, traced as built", "band edge 8.5 GHz"} <= set(labels)
    assert sum(s.label.startswith("horn-") for s in plots["beamformer-rays"].series) == spec.feeds.count


def test_slot_outlines_hold_the_template_chord_tolerance():
    # round ends circumscribed: the cut slot contains the nominal one, vertices ≤ CHORD_TOL_MM out
    from shapely.geometry import LineString, Polygon

    from antenna_cad.fabrication.outline import CHORD_TOL_MM
    from antenna_cad.geometry.slot_layout import slot_outline
    for length, width, angle in ((2.5, 0.4, 0.0), (8.0, 1.5, 0.3), (2.4, 0.44, np.pi / 2)):
        ring = Polygon(slot_outline(1.0, 2.0, length, width, angle))
        u = np.array([np.sin(angle), np.cos(angle)]) * (length - width) / 2
        nominal = LineString([tuple(np.array([1.0, 2.0]) - u), tuple(np.array([1.0, 2.0]) + u)]).buffer(width / 2, 4096)
        assert ring.is_valid and ring.exterior.is_ccw
        assert ring.buffer(1e-9).contains(nominal)
        assert ring.hausdorff_distance(nominal) <= CHORD_TOL_MM


@pytest.mark.slow
@pytest.mark.parametrize("recipe", [KA_RECIPE, ML_RECIPE, TRI_RECIPE, TRI_ML_RECIPE],
                         ids=["two-mirror", "mirror-lens", "trifocal", "trifocal-mirror-lens"])
def test_ka_recipes_build_everything(recipe, recipe_build):
    import json

    import ezdxf
    from pypdf import PdfReader

    spec = load_spec(recipe)
    result = recipe_build(recipe)
    assert not [c for c in result.checks if c.status == "fail"]
    manifest = json.loads((result.out_dir / "manifest.json").read_text())
    parts = {p["label"]: p for p in manifest["parts"]}
    assert all(p["valid"] and p["watertight"] for p in parts.values())
    assert {f"top-{g:02d}" for g in range(40)} <= set(parts) and "horn-1" in parts
    with open(result.out_dir / "slots.csv") as fh:
        assert sum(1 for _ in fh) - 1 == result.figures["slot_count"] == 3200
    doc = ezdxf.readfile(result.out_dir / "templates" / "top-17.dxf")
    assert not doc.audit().has_errors and len([e for e in doc.modelspace() if e.dxf.layer == "CUT"]) == 81
    pdf = PdfReader(result.out_dir / "templates" / f"{spec.name}-templates.pdf")
    w, h = (float(v) * 25.4 / 72 for v in pdf.pages[0].mediabox.upper_right)
    assert (round(w), round(h)) == (210, 297) and len(pdf.pages) >= 40
    fig = manifest["verification"]["figures"]
    # trifocal: the C¹ Hermite curves between the march's exact points leave ≈ 2e-8 D of path error
    assert fig["design_focus_phase_rms_deg"] < (1e-3 if recipe is TRI_RECIPE else 1e-4)
    assert fig["phase_rms_deg_as_built_worst_feed"] < 22.5
