"""<name>.glb: the assembly for viewing — one glTF node per part, named as in the STEP, coloured by
material (graded dielectrics along a sequential map by εr, conductors grey).

The meshes are the report's display meshes (chord tolerance = model size / :data:`VIEW_FACETS`,
at least 0.05 mm), not the fabrication STLs: the view of a Ka array's 3,200-slot lids or a layup of
thousands of rings stays a few MB. glTF is metres and +Y up (Khronos glTF 2.0 §3.4); the model's
frame is already +Y up (DESIGN.md "Frame"), so vertices are only scaled mm → m. No normals are
stored: viewers shade the facets flat (glTF 2.0 §3.7.2.1), which reads well on CAD solids.
The bytes are reproducible (no dates, parts sorted by label).
"""

from __future__ import annotations

import json
import re
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
from matplotlib import colormaps
from matplotlib.colors import to_hex, to_rgb

from antenna_cad.export.mesh import picture_meshes
from antenna_cad.geometry.kernel import bounding_box

PALETTE = ("#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fdd0a2", "#c7e9c0", "#dadaeb", "#c6dbef",
           "#fcbba1", "#d9d9d9")
METAL = "#9a9a9a"
GRADE_MAP = colormaps["viridis_r"]             # low εr light, high εr dark
VIEW_FACETS = 200.0            # chord tolerance of the display meshes = model size / this
MERGE_ABOVE = 2000             # parts: a larger assembly is shown in the report merged per group and material
MM_TO_M = 1e-3


@dataclass(frozen=True)
class ViewPart:
    """One part as the 3-D view and the pictures show it."""
    label: str
    group: str          # parts toggled together: the label without its running number ("sheet-07" → "sheet")
    material: str
    colour: str         # "#rrggbb"
    fabricated: bool    # False: a reference body (ideal lens, allowance, envelope), hidden at first
    cutaway: bool       # left out of the static pictures so nested parts show
    mesh: trimesh.Trimesh
    count: int = 1      # parts in this one (:func:`merged`)


def view_parts(model) -> list[ViewPart]:
    """Every part of ``model`` meshed for viewing in one pass (:func:`~antenna_cad.export.mesh.picture_meshes`),
    sorted by label."""
    parts = sorted(model.parts, key=lambda p: p.label)
    colour = material_colours([p.material for p in parts])
    lo, hi = bounding_box([p.shape for p in parts])
    tol = max(float(np.linalg.norm(hi - lo)) / VIEW_FACETS, 0.05)
    meshes = picture_meshes([p.shape for p in parts], tol, [p.prism for p in parts])
    group = part_groups([p.label for p in parts])
    return [ViewPart(p.label, group[p.label], p.material.name, colour[p.material.name], p.role == "fabricated",
                     p.label in model.cutaway, m) for p, m in zip(parts, meshes)]


GRADE = re.compile(r"(?:(?:sheet|layer)-\d+-)?((?:shell|ring)-\d+)")   # a grade of a graded lens, in any sheet


def part_groups(labels: list[str]) -> dict[str, str]:
    """Label → the group it is toggled with. Shells and rings are grades: each index is a group with
    everything named after it (``shell-02-front``, ``shell-02-pin-1``, ``sheet-03-ring-02`` → shell-02 or
    ring-02), so the outer grades can be hidden one by one. Other labels drop their sheet and running
    number (``sheet-07`` → sheet, ``sheet-03-foot`` → foot), and names sharing a first word with another name gather under it
    (``box-floor``, ``box-wall-left`` → box)."""
    groups, rest = {}, {}
    for label in labels:
        grade = GRADE.match(label)
        if grade:
            groups[label] = grade.group(1)
        else:
            piece = re.sub(r"^(sheet|layer)-\d+-(?=\D)", "", label)         # a layup's piece: less its sheet
            rest[label] = re.sub(r"[-_]?\d+$", "", piece) or piece
    head = {b: re.split(r"[-_]", b)[0] for b in rest.values()}
    sharing = {h for h in head.values() if sum(v == h for v in head.values()) > 1}
    return groups | {label: head[b] if head[b] in sharing else b for label, b in rest.items()}


def material_colours(materials) -> dict[str, str]:
    """Material name → colour: conductors grey; three or more dielectrics (a graded lens) along a
    sequential map by εr, so the grades read in order; fewer from a qualitative palette."""
    unique = sorted({m.name: m for m in materials}.items(), key=lambda nm: (nm[1].eps_r, nm[0]))
    dielectrics = [name for name, m in unique if not is_metal(m)]
    graded = len(dielectrics) >= 3
    return {name: METAL if is_metal(m) else
            (to_hex(GRADE_MAP(0.15 + 0.7 * dielectrics.index(name) / (len(dielectrics) - 1))) if graded
             else PALETTE[dielectrics.index(name) % len(PALETTE)])
            for name, m in unique}


def is_metal(material) -> bool:
    """Conductors are carried as εr = 1, tanδ = 0 materials (kinds/slot_array.py)."""
    return material.eps_r == 1.0 and material.tan_delta == 0.0


def glb_bytes(parts: list[ViewPart]) -> bytes:
    """The binary glTF 2.0 of ``parts`` (Khronos glTF 2.0 §4.4 GLB): one node and one mesh per part (both
    named by its label), one material per material name (metallic for conductors); positions as float32
    metres, indices as uint32, all parts in one buffer. Written with numpy and json directly: trimesh's
    exporter spent ~18 ms a part (26 s on a layup of 1,464 rings)."""
    materials: dict[str, int] = {}
    doc: dict = {"asset": {"version": "2.0", "generator": "antenna_cad"}, "scene": 0,
                 "scenes": [{"nodes": list(range(len(parts)))}], "nodes": [], "meshes": [], "materials": [],
                 "accessors": []}
    positions, indices = [], []
    vertex_bytes = index_bytes = 0
    for i, part in enumerate(parts):
        if part.material not in materials:
            metal = part.colour == METAL
            materials[part.material] = len(doc["materials"])
            doc["materials"].append({"name": part.material, "doubleSided": True, "pbrMetallicRoughness": {
                "baseColorFactor": [round(c, 4) for c in to_rgb(part.colour)] + [1.0],
                "metallicFactor": 0.3 if metal else 0.0, "roughnessFactor": 0.6 if metal else 0.85}})
        v = (np.asarray(part.mesh.vertices, np.float64) * MM_TO_M).astype("<f4")
        f = np.asarray(part.mesh.faces, "<u4").ravel()
        doc["accessors"] += [
            {"bufferView": 0, "byteOffset": vertex_bytes, "componentType": 5126, "count": len(v), "type": "VEC3",
             "min": [float(x) for x in v.min(axis=0)], "max": [float(x) for x in v.max(axis=0)]},
            {"bufferView": 1, "byteOffset": index_bytes, "componentType": 5125, "count": len(f), "type": "SCALAR"}]
        doc["meshes"].append({"name": part.label, "primitives": [
            {"attributes": {"POSITION": 2 * i}, "indices": 2 * i + 1, "material": materials[part.material]}]})
        doc["nodes"].append({"name": part.label, "mesh": i})
        positions.append(v.tobytes())
        indices.append(f.tobytes())
        vertex_bytes += v.nbytes
        index_bytes += f.nbytes
    doc["bufferViews"] = [{"buffer": 0, "byteOffset": 0, "byteLength": vertex_bytes, "target": 34962},
                          {"buffer": 0, "byteOffset": vertex_bytes, "byteLength": index_bytes, "target": 34963}]
    binary = b"".join(positions + indices)                   # float32 and uint32: 4-byte aligned throughout
    doc["buffers"] = [{"byteLength": len(binary)}]
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = (struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary)
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def merged(parts: list[ViewPart]) -> list[ViewPart]:
    """One part per group and material (named by the group, and the material when the group has several):
    a layup of thousands of pieces draws in a few calls."""
    bins: dict[tuple[str, str], list[ViewPart]] = {}
    for p in parts:
        bins.setdefault((p.group, p.material), []).append(p)
    several = {g for g, _ in bins if sum(h == g for h, _ in bins) > 1}
    return [ViewPart(f"{g}-{m}" if g in several else g, g, m, ps[0].colour, any(p.fabricated for p in ps),
                     all(p.cutaway for p in ps), trimesh.util.concatenate([p.mesh for p in ps]), len(ps))
            for (g, m), ps in sorted(bins.items())]


@dataclass(frozen=True)
class View:
    """The assembly as the build shows it: the glb's bytes and its parts."""
    glb: bytes
    parts: tuple[ViewPart, ...]
    colours: dict[str, str]       # material -> colour, in εr order (:func:`material_colours`)


def write_view(path: Path, model) -> View:
    """Mesh ``model`` for viewing and write its glb to ``path`` (beside the STEP)."""
    parts = view_parts(model)
    data = glb_bytes(parts)
    path.write_bytes(data)
    return View(data, tuple(parts), material_colours([p.material for p in model.parts]))
