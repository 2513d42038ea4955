"""``make-lens check OUT``: every file of a build folder re-read by readers other than the ones
that wrote it, against what manifest.json promises.

STEP: gmsh's OpenCASCADE 7.x (solid count, names, volumes ≤ 1e-6 relative). STL: the binary
file parsed here with numpy (triangle count, watertight as claimed with vertices merged by
position, volume within area × chord tolerance). DXF: the group codes parsed here (CUT outline
with its bulge arcs within 0.01 mm of the manifest) beside ezdxf's audit. SVG: its mm size. PDF:
PDFium (page size, every text run inside the page and never across a template tile's window
edge, the 100 mm check bar measured in a render of each template page). Manifest: strict JSON,
sizes and sha256 of every file, no unlisted file.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from antenna_cad.fabrication.templates import (A4_MM, CHECK_BAR_MM, FOOTER_MM, PAGE_MARGIN_MM, WINDOW_MM,
                                               bulge_bounds)
from antenna_cad.fabrication.vector_pdf import PT_PER_MM

VOLUME_RTOL = 1e-6
OUTLINE_TOL_MM = 0.01
PAGE_TOL_PT = 0.5
BAR_TOL_MM = 0.1            # rendered at 20 px/mm: ±1 px per end
BAR_STROKE_MM = 0.6 / PT_PER_MM   # the 0.6 pt end ticks widen the dark run by half a stroke each end
RENDER_PX_PER_MM = 20.0


@dataclass(frozen=True)
class Finding:
    file: str
    check: str
    ok: bool
    message: str


class CheckError(Exception):
    """The folder is not a build (no readable manifest)."""


def check_build(folder: Path) -> list[Finding]:
    """All findings for build folder ``folder`` (raises CheckError when it is not one)."""
    manifest = _manifest(folder)
    findings = list(_files(folder, manifest))
    step = folder / f"{manifest['name']}.step"
    if step.exists():
        findings += _step(step, manifest)
    parts = manifest.get("parts", [])
    for part in parts:
        if part.get("file"):
            findings += _stl(folder, part, manifest["tolerances"]["mesh_tolerance_mm"])
    for entry in manifest.get("templates", []):
        if "dxf" in entry:
            findings += _dxf(folder, entry)
            findings += _svg(folder, entry)
        if "pdf" in entry:
            findings += _pdf(folder, entry["pdf"], templates=True)
    if (folder / "report.pdf").exists():
        findings += _pdf(folder, "report.pdf", templates=False)
    from antenna_cad.export.check_cam import check_cam      # G-code: the wire's surfaces and the travel
    return findings + check_cam(folder, manifest)


def _manifest(folder: Path) -> dict:
    path = folder / "manifest.json"
    if not path.is_file():
        raise CheckError(f"{folder}: no manifest.json (not a build folder)")

    def refuse(constant):
        raise ValueError(f"bare {constant} is not JSON")
    try:
        return json.loads(path.read_text(encoding="utf-8"), parse_constant=refuse)
    except ValueError as exc:
        raise CheckError(f"{path}: not strict JSON: {exc}") from None


def _files(folder: Path, manifest: dict) -> Iterator[Finding]:
    listed = {e["path"]: e for e in manifest.get("files", [])}
    on_disk = {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()} - {"manifest.json"}
    for name in sorted(on_disk - set(listed)):
        yield Finding(name, "listed", False, "file not listed in manifest.json")
    bad = 0
    for name, entry in sorted(listed.items()):
        path = folder / name
        if not path.is_file():
            bad += 1
            yield Finding(name, "sha256", False, "listed in manifest.json but missing")
        elif path.stat().st_size != entry["bytes"] or hashlib.sha256(path.read_bytes()).hexdigest() != entry["sha256"]:
            bad += 1
            yield Finding(name, "sha256", False, "content differs from the manifest")
    yield Finding("manifest.json", "sha256", bad == 0, f"strict JSON; {len(listed) - bad} of {len(listed)} "
                  "listed files with their bytes and sha256")


def _step(path: Path, manifest: dict) -> Iterator[Finding]:
    try:
        from antenna_cad.export.step_read import gmsh_solids
        read = gmsh_solids(path)
    except ImportError:
        yield Finding(path.name, "step", False, "gmsh is not installed (pip install 'antenna_cad[check]')")
        return
    parts = {p["label"]: p for p in manifest["parts"]}
    count = sum(len(v) for v in read.values())
    expected = sum(p.get("solids", 1) for p in parts.values())
    yield Finding(path.name, "step solids", count == expected, f"gmsh reads {count} solids, manifest {expected}")
    names_ok = set(read) == set(parts)
    yield Finding(path.name, "step names", names_ok, "every solid under its part's name" if names_ok else
                  f"missing {sorted(set(parts) - set(read))}, unexpected {sorted(set(read) - set(parts))}")
    worst, where = 0.0, ""
    for label, part in parts.items():
        err = abs(sum(read.get(label, [])) / part["volume_mm3"] - 1)
        if err > worst:
            worst, where = err, label
    yield Finding(path.name, "step volumes", worst <= VOLUME_RTOL,
                  f"largest relative volume error {worst:.2g}" + (f" ({where})" if where else "")
                  + f" (limit {VOLUME_RTOL:g})")


def read_stl(path: Path) -> np.ndarray:
    """Triangles (n, 3, 3) of a binary STL, parsed from its bytes (little-endian float32)."""
    data = path.read_bytes()
    n = int.from_bytes(data[80:84], "little")
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    if len(data) != 84 + n * record.itemsize:
        raise ValueError(f"{n} triangles announced, {len(data)} bytes")
    return np.frombuffer(data, record, count=n, offset=84)["v"].astype(float)


def stl_closed(tri: np.ndarray) -> bool:
    """Closed oriented 2-manifold: vertices merged by exact position, every directed edge used
    once and its reverse once (an edge of four faces, or a hole, fails)."""
    _, index = np.unique(tri.reshape(-1, 3), axis=0, return_inverse=True)
    f = index.reshape(-1, 3)
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = directed[directed[:, 0] != directed[:, 1]]
    uniq, counts = np.unique(directed, axis=0, return_counts=True)
    if (counts != 1).any():
        return False
    forward = {tuple(e) for e in uniq.tolist()}
    return all((b, a) in forward for a, b in forward)


def _stl(folder: Path, part: dict, chord_mm: float) -> Iterator[Finding]:
    name = part["file"]
    try:
        tri = read_stl(folder / name)
    except (OSError, ValueError) as exc:
        yield Finding(name, "stl", False, f"unreadable: {exc}")
        return
    closed = stl_closed(tri)
    claim = part.get("watertight")
    yield Finding(name, "stl watertight", closed == claim and len(tri) == part.get("triangles", len(tri)),
                  f"{len(tri)} triangles, closed {closed}, manifest claims {claim}")
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    volume = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)
    area = float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() / 2)
    limit = area * chord_mm + 1e-9 * abs(part["volume_mm3"])
    yield Finding(name, "stl volume", abs(volume - part["volume_mm3"]) <= limit,
                  f"{volume:.6g} mm3 vs {part['volume_mm3']:.6g} (limit ±{limit:.3g} = area × chord tolerance)")


def dxf_entities(path: Path) -> list[dict]:
    """Entities of the ENTITIES section as dicts of group code → list of values (text parse)."""
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    pairs = [(lines[i].strip(), lines[i + 1].strip()) for i in range(0, len(lines) - 1, 2)]
    entities, current, inside = [], None, False
    for code, value in pairs:
        if code == "2" and current is None and value == "ENTITIES":
            inside = True
            continue
        if not inside:
            continue
        if code == "0":
            if current is not None:
                entities.append(current)
            if value == "ENDSEC":
                break
            current = {"type": value, "seq": []}
        elif current is not None:
            current["seq"].append((int(code), value))
    return entities


def _lwpolyline_path(seq) -> list[tuple[float, float, float]]:
    path: list[list[float]] = []
    for code, value in seq:
        if code == 10:
            path.append([float(value), 0.0, 0.0])
        elif code == 20:
            path[-1][1] = float(value)
        elif code == 42:
            path[-1][2] = float(value)
    return [tuple(p) for p in path]


def dxf_cut_bounds(entities: list[dict]) -> tuple[tuple[float, float, float, float] | None, int]:
    """(bounding box, entity count) of the CUT layer: polylines with their bulge arcs, circles."""
    boxes = []
    for e in entities:
        if dict(e["seq"]).get(8) != "CUT":
            continue
        values = dict(e["seq"])
        if e["type"] == "LWPOLYLINE":
            boxes.append(bulge_bounds(_lwpolyline_path(e["seq"])))
        elif e["type"] == "CIRCLE":
            x, y, r = float(values[10]), float(values[20]), float(values[40])
            boxes.append((x - r, y - r, x + r, y + r))
        else:
            raise ValueError(f"unexpected {e['type']} on layer CUT")
    if not boxes:
        return None, 0
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes),
            max(b[3] for b in boxes)), len(boxes)


def _dxf(folder: Path, entry: dict) -> Iterator[Finding]:
    import ezdxf
    name = entry["dxf"]
    try:
        doc = ezdxf.readfile(folder / name)
        bbox, count = dxf_cut_bounds(dxf_entities(folder / name))
    except (OSError, ValueError, ezdxf.DXFError) as exc:
        yield Finding(name, "dxf", False, f"unreadable: {exc}")
        return
    audit = doc.audit()
    ezdxf_count = len(doc.modelspace().query('*[layer=="CUT"]'))
    ok = not audit.has_errors and doc.header.get("$INSUNITS") == 4 and ezdxf_count == count
    yield Finding(name, "dxf readers", ok, f"ezdxf audit {len(audit.errors)} errors, units mm "
                  f"{doc.header.get('$INSUNITS') == 4}, CUT entities {count} (ezdxf {ezdxf_count})")
    want = entry["cut_bbox_mm"]
    err = max(abs(a - b) for a, b in zip(bbox, want)) if bbox else math.inf
    size = f"{bbox[2] - bbox[0]:.3f} × {bbox[3] - bbox[1]:.3f} mm" if bbox else "no CUT outline"
    yield Finding(name, "dxf outline", err <= OUTLINE_TOL_MM,
                  f"CUT outline {size}, off the manifest by {err:.2g} mm (limit {OUTLINE_TOL_MM})")


def _svg(folder: Path, entry: dict) -> Iterator[Finding]:
    name = entry["svg"]
    head = (folder / name).read_text(encoding="utf-8")[:400]
    size = [re.search(rf'\b{k}="([\d.]+)mm"', head) for k in ("width", "height")]
    got = [float(m.group(1)) if m else math.nan for m in size]
    ok = all(abs(g - w) <= OUTLINE_TOL_MM for g, w in zip(got, entry["svg_size_mm"]))
    yield Finding(name, "svg size", ok, f"{got[0]:g} × {got[1]:g} mm, manifest "
                  f"{entry['svg_size_mm'][0]:g} × {entry['svg_size_mm'][1]:g} mm")


def _window_pt() -> tuple[float, float, float, float]:
    left, bottom = PAGE_MARGIN_MM * PT_PER_MM, (PAGE_MARGIN_MM + FOOTER_MM) * PT_PER_MM
    return left, bottom, left + WINDOW_MM[0] * PT_PER_MM, bottom + WINDOW_MM[1] * PT_PER_MM


def _pdf(folder: Path, name: str, templates: bool) -> Iterator[Finding]:
    import pypdfium2
    pdf = pypdfium2.PdfDocument(folder / name)
    try:
        a4 = (A4_MM[0] * PT_PER_MM, A4_MM[1] * PT_PER_MM)
        bad_size, outside, across, bars = [], [], [], []
        for k in range(len(pdf)):
            page = pdf[k]
            w, h = page.get_size()
            if abs(w - a4[0]) > PAGE_TOL_PT or abs(h - a4[1]) > PAGE_TOL_PT:
                bad_size.append(k + 1)
            text = page.get_textpage()
            boxes = [text.get_rect(i) for i in range(text.count_rects())]      # runs of text, as laid out
            if any(b[0] < -PAGE_TOL_PT or b[1] < -PAGE_TOL_PT or b[2] > w + PAGE_TOL_PT or b[3] > h + PAGE_TOL_PT
                   for b in boxes):
                outside.append(k + 1)
            if templates and any(_straddles(b, _window_pt()) for b in boxes):
                across.append(k + 1)
            if templates:
                bars.append(check_bar_mm(page))
        pages = len(pdf)
    finally:
        pdf.close()
    yield Finding(name, "pdf page size", not bad_size, f"{pages} A4 pages" + (f"; not A4: pages {bad_size[:5]}" if bad_size else ""))
    yield Finding(name, "pdf text inside page", not outside,
                  "every text run inside its page" if not outside else f"text past the page edge on pages {outside[:5]}")
    if templates:
        yield Finding(name, "pdf text unclipped", not across, "no text run across a tile window edge"
                      if not across else f"text across the tile window edge on pages {across[:5]}")
        worst = max(bars, key=lambda b: abs(b - CHECK_BAR_MM)) if bars else math.nan
        yield Finding(name, "pdf check bar", abs(worst - CHECK_BAR_MM) <= BAR_TOL_MM,
                      f"100 mm bar measured {worst:.2f} mm between its end ticks' centres in a "
                      f"{RENDER_PX_PER_MM:g} px/mm render (worst of {len(bars)} pages)")


def _straddles(box, window) -> bool:
    """A text run crossing one of the window's edges (partly inside, partly outside)."""
    l, b, r, t = box
    wl, wb, wr, wt = window
    if r <= wl or l >= wr or t <= wb or b >= wt:
        return False
    return l < wl - 0.1 or r > wr + 0.1 or b < wb - 0.1 or t > wt + 0.1


def check_bar_mm(page) -> float:
    """Length (mm) of the page-space 100 mm check bar, measured in a render of the strip that holds
    it: the longest run of dark pixels in one pixel row."""
    k = PT_PER_MM
    band = (PAGE_MARGIN_MM - 3, PAGE_MARGIN_MM + 5, PAGE_MARGIN_MM + CHECK_BAR_MM + 3, PAGE_MARGIN_MM + 11)  # mm
    w, h = page.get_size()
    crop = (band[0] * k, band[1] * k, w - band[2] * k, h - band[3] * k)
    image = page.render(scale=RENDER_PX_PER_MM / k, crop=crop, grayscale=True).to_numpy()
    dark = (image[..., 0] if image.ndim == 3 else image) < 128
    best = 0
    for row in dark:
        edges = np.flatnonzero(np.diff(np.concatenate([[0], row.astype(np.int8), [0]])))
        if len(edges):
            best = max(best, int((edges[1::2] - edges[0::2]).max()))
    return best / RENDER_PX_PER_MM - BAR_STROKE_MM
