"""The 3-D view's model: parts grouped for toggling, merged per group for very large assemblies,
written as glTF with one named node per part (the browser side is in tests/test_report.py)."""

import pytest
import trimesh

from antenna_cad.export.gltf import ViewPart, glb_bytes, merged, part_groups
from antenna_cad.export.view3d import viewer_html


def test_parts_are_grouped_by_name_and_grades_stay_apart():
    groups = part_groups(["box-floor", "box-wall-left", "sheet-01", "sheet-02", "lens", "sanding-allowance-03",
                          "shell-02-front", "shell-02-pin-1", "shell-03-back", "sheet-04-ring-02", "sheet-05-ring-02",
                          "sheet-05-foot", "waveguide-12", "waveguide-13"])
    assert groups == {"box-floor": "box", "box-wall-left": "box", "sheet-01": "sheet", "sheet-02": "sheet",
                      "lens": "lens", "sanding-allowance-03": "sanding-allowance", "shell-02-front": "shell-02",
                      "shell-02-pin-1": "shell-02", "shell-03-back": "shell-03", "sheet-04-ring-02": "ring-02",
                      "sheet-05-ring-02": "ring-02", "sheet-05-foot": "foot", "waveguide-12": "waveguide",
                      "waveguide-13": "waveguide"}


def _parts():
    return [ViewPart(f"sheet-{i:02d}-ring-0{k}", f"ring-0{k}", f"foam-{k}", f"#00000{k}", True, False,
                     trimesh.creation.box(extents=(10, 10, 10 * k)).apply_translation((0, 0, 20 * i)))
            for i in range(4) for k in (1, 2)]


def test_glb_has_one_named_node_per_part_in_metres():
    parts = _parts()
    scene = trimesh.load(trimesh.util.wrap_as_stream(glb_bytes(parts)), file_type="glb", force="scene")
    assert sorted(scene.graph.nodes_geometry) == sorted(p.label for p in parts)
    assert scene.bounds[1][2] == pytest.approx(0.070)     # 3 × 20 mm + a half-height of 10 mm, in metres
    assert glb_bytes(parts) == glb_bytes(_parts())         # reproducible bytes


def test_a_large_assembly_is_shown_merged_per_group_and_material():
    shown = merged(_parts())
    assert [(p.label, p.count, len(p.mesh.faces)) for p in shown] == [("ring-01", 4, 48), ("ring-02", 4, 48)]
    page = viewer_html(glb_bytes(shown), shown)
    assert "8 parts in 2 groups" in page and "merged per group" in page
