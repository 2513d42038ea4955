"""The file readers of ``make-lens check``: each re-reads one kind of file with a reader other than
the one that wrote it and compares it with the manifest entry it belongs to.

STEP: its text (solid entities and product names: any size) and gmsh's OpenCASCADE 7.x (volumes
≤ 1e-6 relative) up to :data:`STEP_GMSH_MAX_BYTES`. STL: the binary file parsed here with numpy
(triangle count, watertight as claimed with vertices merged by position, volume within area ×
chord tolerance). DXF: the group codes parsed here (CUT outline with its bulge arcs within 0.01 mm
of the manifest) beside ezdxf's audit. SVG: its mm size and the bounding box of its CUT layer.
PDF: PDFium (page count, page size, every text run inside the page and never across a template
tile's window edge, the 100 mm check bar measured in a render of each template page, each
drawing's label on some page; at most :data:`PDF_PAGES_READ` pages, evenly spread, when larger).
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ElementTree
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
STEP_GMSH_MAX_BYTES = 4_000_000   # gmsh reads ~1 MB of our STEP per CPU second; bigger: text only
PDF_PAGES_READ = 400              # pages read of a PDF (all of a smaller one); rendering costs ~20 ms a page


@dataclass(frozen=True)
class Finding:
    file: str
    check: str
    ok: bool
    message: str


# ------------------------------------------------------------------ STEP

STEP_SOLID = re.compile(rb"=\s*(?:MANIFOLD_SOLID_BREP|BREP_WITH_VOIDS)\s*\(")
STEP_PRODUCT = re.compile(rb"=\s*PRODUCT\s*\(\s*'((?:[^']|'')*)'")


def step_text(path: Path) -> tuple[int, set[str]]:
    """(solid entities, product names) of a STEP file, from its text."""
    data = path.read_bytes()
    names = {m.group(1).decode("utf-8", "replace").replace("''", "'") for m in STEP_PRODUCT.finditer(data)}
    return len(STEP_SOLID.findall(data)), names


def step_findings(path: Path, name: str, parts: list) -> Iterator[Finding]:
    """Solids and names (text), volumes (gmsh, when the file is small enough) against ``parts``."""
    labels = {p.label: p for p in parts}
    expected = sum(p.solids for p in parts)
    count, products = step_text(path)
    yield Finding(name, "step solids", count == expected, f"{count} solid entities in the text, manifest {expected}")
    missing = sorted(set(labels) - products)
    yield Finding(name, "step names", not missing, "every part a product of the STEP" if not missing
                  else f"no product for {missing[:5]}")
    size = path.stat().st_size
    if size > STEP_GMSH_MAX_BYTES:
        yield Finding(name, "step volumes", True, f"not measured: {size / 1e6:.1f} MB is over the "
                      f"{STEP_GMSH_MAX_BYTES / 1e6:g} MB read by gmsh (solids and names from the text, bytes by sha256)")
        return
    try:
        from antenna_cad.export.step_read import gmsh_solids
    except ImportError:
        yield Finding(name, "step volumes", False, "gmsh is not installed (pip install 'antenna_cad[check]')")
        return
    read = gmsh_solids(path)
    got = sum(len(v) for v in read.values())
    worst, where = (0.0, "") if got == expected else (math.inf, "solid count")
    for label, part in labels.items():
        err = abs(sum(read.get(label, [])) / part.volume_mm3 - 1)
        if err > worst:
            worst, where = err, label
    yield Finding(name, "step volumes", worst <= VOLUME_RTOL, f"gmsh reads {got} solids; largest relative volume "
                  f"error {worst:.2g}" + (f" ({where})" if where else "") + f" (limit {VOLUME_RTOL:g})")


# ------------------------------------------------------------------ STL

def read_stl(path: Path) -> np.ndarray:
    """Triangles (n, 3, 3) of a binary STL, parsed from its bytes (little-endian float32)."""
    data = path.read_bytes()
    if len(data) < 84:
        raise ValueError(f"{len(data)} bytes: shorter than an STL header")
    n = int.from_bytes(data[80:84], "little")
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    if len(data) != 84 + n * record.itemsize:
        raise ValueError(f"{n} triangles announced, {len(data)} bytes")
    return np.frombuffer(data, record, count=n, offset=84)["v"].astype(float)


def stl_closed(tri: np.ndarray) -> bool:
    """Closed oriented 2-manifold: vertices merged by exact position, every directed edge used
    once and its reverse once (an edge of four faces, or a hole, fails)."""
    if not len(tri):
        return False
    vertices, index = np.unique(tri.reshape(-1, 3), axis=0, return_inverse=True)
    return faces_closed(index.reshape(-1, 3), len(vertices))


def faces_closed(f: np.ndarray, n: int) -> bool:
    """:func:`stl_closed` of an indexed mesh (faces ``f`` into ``n`` vertices)."""
    if not len(f):
        return False
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = directed[directed[:, 0] != directed[:, 1]]
    codes, counts = np.unique(directed[:, 0] * n + directed[:, 1], return_counts=True)
    if (counts != 1).any():
        return False
    return bool(np.isin((codes % n) * n + codes // n, codes, assume_unique=True).all())


def stl_findings(path: Path, name: str, part, chord_mm: float) -> Iterator[Finding]:
    tri = read_stl(path)
    closed = stl_closed(tri)
    yield Finding(name, "stl watertight", closed == part.watertight and len(tri) == (part.triangles or len(tri)),
                  f"{len(tri)} triangles (manifest {part.triangles}), closed {closed}, manifest claims {part.watertight}")
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    volume = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)
    area = float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() / 2)
    limit = area * chord_mm + 1e-9 * abs(part.volume_mm3)
    yield Finding(name, "stl volume", abs(volume - part.volume_mm3) <= limit,
                  f"{volume:.6g} mm3 vs {part.volume_mm3:.6g} (limit ±{limit:.3g} = area × chord tolerance)")


# ------------------------------------------------------------------ DXF and SVG

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


Box = tuple[float, float, float, float]


def _union(boxes: list[Box]) -> Box | None:
    if not boxes:
        return None
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


def dxf_cut_bounds(entities: list[dict]) -> tuple[Box | None, int]:
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
    return _union(boxes), len(boxes)


def _box_error(got: Box | None, want) -> float:
    return max(abs(a - b) for a, b in zip(got, want)) if got else math.inf


def dxf_findings(path: Path, name: str, entry) -> Iterator[Finding]:
    import ezdxf
    doc = ezdxf.readfile(path)
    bbox, count = dxf_cut_bounds(dxf_entities(path))
    audit = doc.audit()
    ezdxf_count = len(doc.modelspace().query('*[layer=="CUT"]'))
    ok = not audit.has_errors and doc.header.get("$INSUNITS") == 4 and ezdxf_count == count
    yield Finding(name, "dxf readers", ok, f"ezdxf audit {len(audit.errors)} errors, units mm "
                  f"{doc.header.get('$INSUNITS') == 4}, CUT entities {count} (ezdxf {ezdxf_count})")
    err = _box_error(bbox, entry.cut_bbox_mm or ())
    size = f"{bbox[2] - bbox[0]:.3f} × {bbox[3] - bbox[1]:.3f} mm" if bbox else "no CUT outline"
    yield Finding(name, "dxf outline", err <= OUTLINE_TOL_MM,
                  f"CUT outline {size}, off the manifest by {err:.2g} mm (limit {OUTLINE_TOL_MM})")


def svg_cut_bounds(root) -> Box | None:
    """Bounding box of the CUT group's polygons, polylines and circles (model coordinates)."""
    ns = "{http://www.w3.org/2000/svg}"
    boxes = []
    for group in root.iter(f"{ns}g"):
        if group.get("id") != "CUT":
            continue
        for el in group.iter():
            tag = el.tag.removeprefix(ns)
            if tag in ("polygon", "polyline"):
                xy = np.array([float(v) for v in re.split(r"[\s,]+", el.get("points", "").strip()) if v]).reshape(-1, 2)
                if len(xy):
                    boxes.append((*xy.min(axis=0), *xy.max(axis=0)))
            elif tag == "circle":
                x, y, r = (float(el.get(k)) for k in ("cx", "cy", "r"))
                boxes.append((x - r, y - r, x + r, y + r))
            elif tag != "g":
                raise ValueError(f"unexpected <{tag}> in the CUT group")
    return _union([tuple(map(float, b)) for b in boxes])


def svg_findings(path: Path, name: str, entry, chord_mm: float) -> Iterator[Finding]:
    data = path.read_bytes()
    text = data.decode("utf-8")                     # a stray byte: UnicodeDecodeError, a failed row
    root = ElementTree.fromstring(text)
    got = [float(m.group(1)) if m else math.nan
           for m in (re.fullmatch(r"([\d.]+)mm", root.get(k, "")) for k in ("width", "height"))]
    want = entry.svg_size_mm or (math.nan, math.nan)
    ok = all(abs(g - w) <= OUTLINE_TOL_MM for g, w in zip(got, want))
    yield Finding(name, "svg size", ok, f"{got[0]:g} × {got[1]:g} mm, manifest {want[0]:g} × {want[1]:g} mm")
    err = _box_error(svg_cut_bounds(root), entry.cut_bbox_mm or ())
    limit = chord_mm + 2 * 0.001 + OUTLINE_TOL_MM       # arcs as chords, coordinates to 0.001 mm
    yield Finding(name, "svg outline", err <= limit, f"CUT layer's box off the manifest's by {err:.2g} mm "
                  f"(limit {limit:.3g}: chord tolerance + rounding)")


# ------------------------------------------------------------------ PDF

def _window_pt() -> Box:
    left, bottom = PAGE_MARGIN_MM * PT_PER_MM, (PAGE_MARGIN_MM + FOOTER_MM) * PT_PER_MM
    return left, bottom, left + WINDOW_MM[0] * PT_PER_MM, bottom + WINDOW_MM[1] * PT_PER_MM


def pages_read(count: int) -> list[int]:
    """Page indices read of a ``count``-page PDF: all, or PDF_PAGES_READ evenly spread (first and
    last included)."""
    if count <= PDF_PAGES_READ:
        return list(range(count))
    return sorted({round(k * (count - 1) / (PDF_PAGES_READ - 1)) for k in range(PDF_PAGES_READ)})


def pdf_findings(path: Path, name: str, templates: bool, pages: int | None = None,
                 words: tuple[str, ...] = ()) -> Iterator[Finding]:
    """Page count (against ``pages`` when given), size, text placement, check bar (``templates``),
    and each of ``words`` in the text (when every page is read)."""
    import pypdfium2
    pdf = pypdfium2.PdfDocument(path)
    try:
        a4 = (A4_MM[0] * PT_PER_MM, A4_MM[1] * PT_PER_MM)
        count = len(pdf)
        read = pages_read(count)
        bad_size, outside, across, bars, text = [], [], [], [], []
        for k in read:
            page = pdf[k]
            w, h = page.get_size()
            if abs(w - a4[0]) > PAGE_TOL_PT or abs(h - a4[1]) > PAGE_TOL_PT:
                bad_size.append(k + 1)
            textpage = page.get_textpage()
            boxes = [textpage.get_rect(i) for i in range(textpage.count_rects())]      # runs of text, as laid out
            text.append(textpage.get_text_range())
            if any(b[0] < -PAGE_TOL_PT or b[1] < -PAGE_TOL_PT or b[2] > w + PAGE_TOL_PT or b[3] > h + PAGE_TOL_PT
                   for b in boxes):
                outside.append(k + 1)
            if templates and any(_straddles(b, _window_pt()) for b in boxes):
                across.append(k + 1)
            if templates:
                bars.append(check_bar_mm(page))
    finally:
        pdf.close()
    sampled = "" if len(read) == count else f" (read {len(read)} of {count} pages, evenly spread)"
    ok = bool(count) and not bad_size and (pages is None or pages == count)
    yield Finding(name, "pdf page size", ok, f"{count} A4 pages" + (f", manifest {pages}" if pages is not None else "")
                  + (f"; not A4: pages {bad_size[:5]}" if bad_size else "") + sampled)
    yield Finding(name, "pdf text inside page", not outside,
                  "every text run inside its page" if not outside else f"text past the page edge on pages {outside[:5]}")
    if templates:
        yield Finding(name, "pdf text unclipped", not across, "no text run across a tile window edge"
                      if not across else f"text across the tile window edge on pages {across[:5]}")
        worst = max(bars, key=lambda b: abs(b - CHECK_BAR_MM)) if bars else math.nan
        yield Finding(name, "pdf check bar", abs(worst - CHECK_BAR_MM) <= BAR_TOL_MM,
                      f"100 mm bar measured {worst:.2f} mm between its end ticks' centres in a "
                      f"{RENDER_PX_PER_MM:g} px/mm render (worst of {len(bars)} pages)")
    if words and len(read) == count:
        joined = "\n".join(text)
        missing = [w for w in words if w not in joined]
        yield Finding(name, "pdf content", not missing, f"all {len(words)} labels in the text" if not missing
                      else f"{len(missing)} of {len(words)} labels not in the text: {missing[:5]}")


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


# ------------------------------------------------------------------ printed parts (3MF + STL)

THREE_MF_NS = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
PRINTED_VOLUME_RTOL = 1e-3      # 3MF object vs its STL (4-decimal 3MF coordinates, float32 STL)


def mesh_volume_mm3(tri: np.ndarray) -> float:
    """Enclosed volume of triangles (n, 3, 3) by the divergence theorem (outward orientation)."""
    return float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0)


def read_3mf(path: Path) -> list[tuple[str, int, np.ndarray, np.ndarray]]:
    """(name, copies, vertices, faces) of every object of a 3MF, parsed from its zip and XML."""
    import zipfile
    with zipfile.ZipFile(path) as z:
        root = ElementTree.fromstring(z.read("3D/3dmodel.model"))
    out = []
    for obj in root.iter(f"{THREE_MF_NS}object"):
        meta = {m.get("name"): m.text for m in obj.findall(f"{THREE_MF_NS}metadata")}
        v = np.array([[float(e.get(k)) for k in "xyz"] for e in obj.iter(f"{THREE_MF_NS}vertex")])
        f = np.array([[int(e.get(k)) for k in ("v1", "v2", "v3")] for e in obj.iter(f"{THREE_MF_NS}triangle")])
        out.append((obj.get("name"), int(meta.get("copies", 1)), v.reshape(-1, 3), f.reshape(-1, 3)))
    return out


def printed_findings(three_mf: Path, stls: dict[str, Path], volume_cm3: float | None, rel: str) -> Iterator[Finding]:
    """A printed build's 3MF read back: every object a closed oriented mesh, its volume its STL's
    (``stls``: part name → file) and Σ volume × copies the manifest's ``printed_volume_cm3``."""
    objects = read_3mf(three_mf)
    yield Finding(rel, "3mf objects", bool(objects), f"{len(objects)} objects")
    total = 0.0
    for name, copies, v, f in objects:
        vol = mesh_volume_mm3(v[f])
        total += vol * copies
        yield Finding(rel, "3mf closed", faces_closed(f, len(v)), f"{name}: {len(f)} triangles, closed and oriented")
        stl = stls.get(name)
        if stl is None:
            yield Finding(rel, "3mf vs stl", False, f"{name}: no printed/{name}.stl listed")
            continue
        other = mesh_volume_mm3(read_stl(stl))
        ok = abs(vol - other) <= PRINTED_VOLUME_RTOL * abs(other)
        yield Finding(rel, "3mf vs stl", ok, f"{name}: {vol / 1000:.3f} cm³ in the 3MF, {other / 1000:.3f} cm³ in its STL")
    if volume_cm3 is not None:
        ok = abs(total / 1000 - volume_cm3) <= PRINTED_VOLUME_RTOL * volume_cm3
        yield Finding(rel, "3mf volume", ok, f"Σ volume × copies {total / 1000:.3f} cm³ vs manifest "
                      f"printed_volume_cm3 {volume_cm3:.3f}")
