"""Printed lattice lenses: the cell-by-cell lattice mesh, the fill mapping and its clipping, the
trimmed parts with pins and bed cuts, the 3MF/STL writers, and the spec's refusals."""

import io
import math
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from antenna_cad.printed.export3mf import stl_bytes, three_mf_bytes
from antenna_cad.printed.fill import fill_integral_mm3, fill_map
from antenna_cad.printed.lattice import Printable, fill_fraction
from antenna_cad.printed.lattice_mesh import lattice_triangles, weld
from antenna_cad.printed.parts import Pins, build_printed_lens, closed_and_oriented, mesh_volume
from antenna_cad.spec import SpecError, load_spec, parse_spec


def _mesh(idx, w, a):
    return weld(lattice_triangles(np.array(idx), np.array(w, float), a))


def test_lattice_mesh_is_closed_and_its_volume_is_the_fill():
    rng = np.random.default_rng(3)
    g = np.arange(3)
    idx = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    a = 2.5
    w = np.round(rng.uniform(0.3, 2.0, len(idx)), 2)
    v, f = _mesh(idx, w, a)
    assert closed_and_oriented(f)
    assert mesh_volume(v, f) == pytest.approx(float((fill_fraction("cubic", w / a) * a**3).sum()), rel=1e-9)
    assert not closed_and_oriented(f[1:])                       # a hole is seen
    assert not closed_and_oriented(np.concatenate([f[:1, ::-1], f[1:]]))   # so is a flipped triangle


def test_equal_neighbours_share_their_face_without_internal_triangles():
    v, f = _mesh([(0, 0, 0), (1, 0, 0)], [1.0, 1.0], 3.0)
    assert len(f) == 2 * 40 + 8 + 10 * 2      # 20 arm sides each, one rod core to core, 10 end caps
    assert closed_and_oriented(f) and mesh_volume(v, f) == pytest.approx(2 * fill_fraction("cubic", 1 / 3) * 27)
    v2, f2 = _mesh([(0, 0, 0), (1, 0, 0)], [1.0, 1.5], 3.0)
    assert len(f2) == 2 * 48 + 10 * 2 + 8     # a square ring out of the wider rod
    assert closed_and_oriented(f2)


def test_fill_follows_the_law_inside_the_printable_range_and_reports_the_clip():
    pr = Printable("cubic", 3.6, 0.8, 0.8)
    R = 60.0
    fm = fill_map(lambda r: 2 - (r / R) ** 2, R, "cubic", 2.7, pr)
    inside = (fm.eps_law > fm.eps_range[0]) & (fm.eps_law < fm.eps_range[1])
    assert np.abs(fm.eps_error[inside]).max() < 1e-6
    (region,) = fm.clipped_regions()
    assert region["r_to_mm"] == R and region["side"] == "below the thinnest wall"
    assert region["max_abs_eps_error"] == pytest.approx(fm.eps_range[0] - 1.0, abs=1e-9)
    assert fm.fill_range[0] == pytest.approx(fill_fraction("cubic", 0.8 / 3.6), abs=1e-3)


def _small_lens(bed=(200.0, 200.0, 200.0), pins=Pins(3.0, 8.0, 0.2, 0.8)):
    R, a, skin = 16.0, 3.0, 1.0
    fm = fill_map(lambda r: 2 - (r / R) ** 2, R, "cubic", 2.7, Printable("cubic", a, 0.8, 0.8))
    ref = fill_integral_mm3(fm, R - skin, "sphere") + 4 / 3 * math.pi * (R**3 - (R - skin) ** 3)
    return build_printed_lens("sphere", R, None, fm, skin_mm=skin, wall_mm=0.8, gap_mm=0.8, width_step_mm=0.05,
                              bed_mm=bed, pins=pins, tolerance_mm=0.02, reference_volume_mm3=ref)


def test_printed_sphere_parts_are_closed_and_hold_the_fill_integral():
    lens = _small_lens()
    assert abs(lens.body_volume_mm3 / lens.reference_volume_mm3 - 1) < 0.03
    assert all(closed_and_oriented(p.faces) for p in lens.parts)
    assert [(p.label, p.count) for p in lens.parts] == [("lens-01", 2), ("pin", 3)]
    assert lens.parts[0].size_mm == pytest.approx((32.0, 32.0, 16.0), abs=0.05)


def test_a_lens_larger_than_the_bed_is_cut_with_pins_across_the_cut():
    lens = _small_lens(bed=(20.0, 200.0, 200.0))
    halves = [p for p in lens.parts if p.role == "lens"]
    assert lens.cuts == 1 and len(halves) == 2
    assert all(p.size_mm[0] <= 20.0 + 1e-6 for p in halves)
    assert lens.pins > 3                                         # the equator's three and the cut's
    assert all(closed_and_oriented(p.faces) for p in lens.parts)


def test_3mf_holds_one_object_per_part_and_is_reproducible():
    lens = _small_lens()
    objs = [{"name": p.label, "vertices": p.vertices, "faces": p.faces, "metadata": {"copies": str(p.count)}}
            for p in lens.parts]
    data = three_mf_bytes(objs, {"Title": "t", "make-lens:nozzle_mm": "0.4"})
    assert data == three_mf_bytes(objs, {"Title": "t", "make-lens:nozzle_mm": "0.4"})
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    root = ET.fromstring(zipfile.ZipFile(io.BytesIO(data)).read("3D/3dmodel.model"))
    found = root.findall("m:resources/m:object", ns)
    assert [o.get("name") for o in found] == [p.label for p in lens.parts]
    for o, p in zip(found, lens.parts):
        assert len(o.findall("m:mesh/m:triangles/m:triangle", ns)) == len(p.faces)
        assert len(o.findall("m:mesh/m:vertices/m:vertex", ns)) == len(p.vertices)
    assert len(root.findall("m:build/m:item", ns)) == len(lens.parts)
    stl = stl_bytes(lens.parts[0].vertices, lens.parts[0].faces, "x")
    assert len(stl) == 84 + 50 * len(lens.parts[0].faces)


BASE = {"name": "p", "kind": "luneburg", "frequency_ghz": 12.0, "material": "pla",
        "design": {"diameter_mm": 120, "law": "classic"},
        "fabrication": {"method": "printed", "cell_mm": 3.6}}


@pytest.mark.parametrize("change, expected", [
    ({"fabrication": {"method": "printed", "cell_mm": 5.0}}, "fabrication.cell_mm: must be ≤ λ/(4·√εr) = 3.8 mm"),
    ({"material": "xps"}, "material: a printed lens needs a filament"),
    ({"fabrication": {"method": "printed", "cell_mm": 3.6, "lattice": "gyroid"}}, "fabrication.cell_mm: no gyroid sheet"),
    ({"fabrication": {"method": "printed", "cell_mm": 1.5}}, "fabrication.cell_mm: must be > min wall + min gap"),
])
def test_printed_spec_refuses_with_one_line_naming_the_field(change, expected):
    with pytest.raises(SpecError) as exc:
        parse_spec(BASE | change, "s.yaml")
    assert len(exc.value.lines) == 1 and expected in exc.value.lines[0]


def test_printed_spec_accepts_a_filament_and_an_inline_one():
    assert parse_spec(BASE, "s.yaml").fabrication.wall_mm == pytest.approx(0.8)
    inline = {"name": "tpu", "eps_r": 2.9, "tan_delta": 0.02, "density_kg_m3": 1200}
    assert parse_spec(BASE | {"material": inline}, "s.yaml").material.eps_r == 2.9


def test_cli_refuses_a_bad_printed_spec_with_exit_2(tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text("name: p\nkind: luneburg\nfrequency_ghz: 12\nmaterial: pla\ndesign: {diameter_mm: 120}\n"
                    "fabrication: {method: printed, cell_mm: 9}\n", encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "antenna_cad", "validate", str(spec)], capture_output=True, text=True)
    assert run.returncode == 2
    lines = [line for line in (run.stdout + run.stderr).splitlines() if line.strip()]
    assert len(lines) == 1 and "fabrication.cell_mm" in lines[0] and "Traceback" not in run.stderr


def test_printed_cylinder_holds_whole_cells_and_flags_a_cut_without_room_for_pins():
    with pytest.raises(SpecError) as exc:
        parse_spec(BASE | {"design": {"diameter_mm": 100, "shape": "cylinder", "height_mm": 6.0}}, "s.yaml")
    assert "fabrication.cell_mm: the height between the plates must be a whole number of cells" in exc.value.lines[0]
    R, a, h = 20.0, 3.0, 6.0
    fm = fill_map(lambda r: 2 - (r / R) ** 2, R, "cubic", 2.7, Printable("cubic", a, 0.8, 0.8))
    ref = fill_integral_mm3(fm, R - 0.8, "cylinder", h) + math.pi * (R**2 - (R - 0.8) ** 2) * h
    lens = build_printed_lens("cylinder", R, h, fm, skin_mm=0.8, wall_mm=0.8, gap_mm=0.8, width_step_mm=0.05,
                              bed_mm=(25.0, 100.0, 100.0), pins=Pins(5.0, 8.0, 0.2, 0.8), tolerance_mm=0.02,
                              reference_volume_mm3=ref)
    assert abs(lens.body_volume_mm3 / ref - 1) < 0.02
    assert lens.cuts == 1 and lens.unpinned_cuts == 1 and lens.pins == 0
    assert all(closed_and_oriented(p.faces) and p.size_mm[2] == pytest.approx(h) for p in lens.parts)
    thin = build_printed_lens("cylinder", R, h, fm, skin_mm=0.8, wall_mm=0.8, gap_mm=0.8, width_step_mm=0.05,
                              bed_mm=(25.0, 100.0, 100.0), pins=Pins(3.0, 8.0, 0.2, 0.8), tolerance_mm=0.02,
                              reference_volume_mm3=ref)
    assert thin.unpinned_cuts == 0 and thin.pins == 2                # a Ø3 mm pin's boss fits the 6 mm slab


def test_the_fabricated_variant_is_the_printed_profile_under_its_skin():
    from antenna_cad.kinds.luneburg import synthesize
    from antenna_cad.kinds.luneburg_printed import printed_medium
    spec = parse_spec(BASE | {"fabrication": {"method": "printed", "cell_mm": 3.6, "skin_mm": 0.8}}, "s.yaml")
    design = synthesize(spec)
    medium = printed_medium(spec, design, shells=40)
    R = design.radius_mm
    eps = medium.n**2
    assert medium.radii[-1] == R and medium.radii[-2] == pytest.approx(R - 0.8) and eps[-1] == 2.7
    mid = (np.concatenate([[0.0], medium.radii[:-2]]) + medium.radii[:-1]) / 2
    law = 2 - (mid / R) ** 2
    free = law > 1.17                                        # inside the printable range (εr ≥ 1.164)
    assert np.abs(eps[:-1][free] - law[free]).max() < 1e-5     # the fill map sampled on 401 radii
    assert np.all(eps[:-1][~free] == pytest.approx(eps[:-1][~free][0]))   # clipped to the thinnest wall
    assert eps[:-1][~free][0] > law[~free].max()


@pytest.mark.slow
def test_printed_recipe_builds_and_its_files_read_back(tmp_path, monkeypatch):
    import csv
    import json
    from pathlib import Path
    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    monkeypatch.setenv("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/false")
    spec = load_spec(Path(__file__).resolve().parents[1] / "recipes" / "luneburg-printed-120mm-pla.yaml")
    result = build(spec, tmp_path)
    assert result.status != "fail"
    out = result.out_dir
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    root = ET.fromstring(zipfile.ZipFile(out / "printed" / f"{spec.name}.3mf").read("3D/3dmodel.model"))
    assert [o.get("name") for o in root.findall("m:resources/m:object", ns)] == ["lens-01", "pin"]
    stl = (out / "printed" / "lens-01.stl").read_bytes()
    tris = np.frombuffer(stl[84:], dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])["v"].astype(float)
    volume = float(np.einsum("ij,ij->i", tris[:, 0], np.cross(tris[:, 1], tris[:, 2])).sum() / 6)
    rows = list(csv.DictReader((out / "cutlist.csv").open(encoding="utf-8")))
    halves = [r for r in rows if r["kind"] == "printed-lens"]
    assert len(halves) == 2 and float(halves[0]["mass_kg"]) == pytest.approx(volume * 1240e-9, abs=5e-4)
    figures = json.loads((out / "manifest.json").read_text(encoding="utf-8"))["verification"]["figures"]
    assert figures["mie_fabricated_focal_gain_dbi"] < figures["mie_ideal_focal_gain_dbi"]
    assert abs(figures["printed_volume_error"]) < 0.02


def test_kinds_without_a_printed_method_refuse_it_by_name():
    data = load_spec("recipes/bifocal-dielectric-160mm.yaml").model_dump(mode="json", exclude_none=True)
    with pytest.raises(SpecError) as exc:
        parse_spec(data | {"fabrication": {"method": "printed", "cell_mm": 3}}, "s.yaml")
    assert any("fabrication.method: must be one of" in line
               and "kinds luneburg, graded, mirror_lens and collimator so far" in line for line in exc.value.lines)


def test_a_hemisphere_taller_than_the_bed_is_refused():
    data = BASE | {"fabrication": {"method": "printed", "cell_mm": 3.6, "bed": {"z_mm": 50}}}
    with pytest.raises(SpecError) as exc:
        parse_spec(data, "s.yaml")
    assert exc.value.lines == ["s.yaml: fabrication.bed.z_mm: a hemisphere 60 mm tall does not fit (horizontal cuts "
                               "are not made; got 50)"]


def test_a_lattice_of_too_many_cells_is_refused_before_meshing():
    from antenna_cad.kinds.luneburg import synthesize
    from antenna_cad.kinds.luneburg_printed import fabricate_printed
    from antenna_cad.synthesis.checks import DesignError
    spec = parse_spec(BASE | {"design": {"diameter_mm": 400, "law": "classic", "layers": {"count": 8}},
                              "fabrication": {"method": "printed", "cell_mm": 3.6}}, "s.yaml")
    with pytest.raises(DesignError, match="lattice cells exceed the limit"):
        fabricate_printed(spec, synthesize(spec))


def test_cad_free_validate_plans_no_mesh_and_a_build_from_it_meshes(tmp_path):
    """``validate --fast`` (api.validate without solids or a folder) plans a printed lens without
    its lattice mesh — the limits and fill checks made, no files, no mesh checks — and a build from
    that validation plans again with the mesh."""
    from antenna_cad import api
    small = BASE | {"name": "small", "design": {"diameter_mm": 40, "law": "classic"},
                    "outputs": {"step": False, "stl": False, "templates": False, "report": False}}
    light = api.validate(small)
    names = {c.name for c in light.checks}
    assert not light.plan.cad and light.plan.fab.lens is None and not light.plan.fab.files
    assert {"printed_cell_size", "printed_fill_clipped"} <= names and "printed_volume" not in names
    full = api.validate(small, solids=True)
    assert full.plan.cad and full.plan.fab.lens is not None and "printed_volume" in {c.name for c in full.checks}
    built = api.build(light, tmp_path)
    assert (tmp_path / "small" / "printed" / "small.3mf").exists()
    assert "printed_volume" in {c.name for c in built.checks}


def test_check_reads_the_3mf_back_against_the_stls_and_the_volume(tmp_path):
    """``make-lens check`` on printed parts: each 3MF object closed and of its STL's volume, Σ volume
    × copies the manifest's; a dropped triangle, another part's STL or a wrong total each fail."""
    from antenna_cad.export.check_readers import printed_findings
    lens = _small_lens()
    objects = [{"name": p.label, "vertices": p.vertices, "faces": p.faces, "metadata": {"copies": str(p.count)}}
               for p in lens.parts]
    stls = {}
    for p in lens.parts:
        stls[p.label] = tmp_path / f"{p.label}.stl"
        stls[p.label].write_bytes(stl_bytes(p.vertices, p.faces, p.label))
    total = sum(p.volume_mm3 * p.count for p in lens.parts) / 1000

    def failed(objs, files, volume):
        (tmp_path / "x.3mf").write_bytes(three_mf_bytes(objs, {}))
        return sorted({f.check for f in printed_findings(tmp_path / "x.3mf", files, volume, "x.3mf") if not f.ok})
    assert failed(objects, stls, total) == []
    holed = [dict(objects[0], faces=objects[0]["faces"][1:])] + objects[1:]
    assert "3mf closed" in failed(holed, stls, total)
    assert len(lens.parts) == 2                                       # the hemisphere and the pin
    swapped = {a: stls[b] for a, b in zip(stls, list(stls)[::-1])}
    assert failed(objects, swapped, total) == ["3mf vs stl"]
    assert failed(objects, stls, total * 1.01) == ["3mf volume"]
