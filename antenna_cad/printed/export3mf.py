"""Writers of printable meshes: a 3MF package (one object per printable part, material and print
settings as metadata) and binary STL, both byte-reproducible (fixed zip dates, fixed number format).

3MF: 3MF Consortium, "3MF Core Specification" 1.3 (2022): an OPC zip with ``3D/3dmodel.model``
(millimetres; vertices, triangles counter-clockwise seen from outside), build items placing each
object, model-level ``metadata`` (name/value).
"""

from __future__ import annotations

import io
import queue
import threading
import zipfile
from collections.abc import Iterable
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from antenna_cad.printed.lattice_mesh import cross_rows

_CONTENT_TYPES = ('<?xml version="1.0" encoding="UTF-8"?>\n'
                  '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
                  '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
                  '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
                  '</Types>\n')
_RELS = ('<?xml version="1.0" encoding="UTF-8"?>\n'
         '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
         '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
         'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>\n')
_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_DATE = (2020, 1, 1, 0, 0, 0)
GAP_MM = 10.0       # between build items laid out in a row


CHUNK = 50_000      # rows formatted at a time (bounds the memory of the Python floats)
DEFLATE_LEVEL = 1   # 3× faster than zlib's default on the mesh text, 20 % larger (a 12 M-triangle body: 20 s → 7 s)


def _rows(fmt: str, array: np.ndarray):
    """Every row of ``array`` through ``fmt``, a chunk of rows per piece of text."""
    for i in range(0, len(array), CHUNK):
        part = array[i:i + CHUNK]
        yield (fmt * len(part)) % tuple(part.ravel().tolist())


_VERTEX = '<vertex x="%.4f" y="%.4f" z="%.4f"/>\n'
_TRIANGLE = '<triangle v1="%d" v2="%d" v3="%d"/>\n'
_BETWEEN = "</vertices><triangles>\n"


def mesh_rows(vertices: np.ndarray, faces: np.ndarray):
    """An object's vertices and triangles as 3dmodel.model text, in pieces (``rows`` of :func:`model_xml`)."""
    yield from _rows(_VERTEX, np.asarray(vertices, float))
    yield _BETWEEN
    yield from _rows(_TRIANGLE, np.asarray(faces))


def mesh_rows_bound(vertices: np.ndarray, faces: np.ndarray) -> int:
    """Bytes :func:`mesh_rows` takes at most (numbers as wide as the widest coordinate and index)."""
    v, f = np.asarray(vertices, float), np.asarray(faces)
    wide = len(f"{-float(np.abs(v).max(initial=0.0)):.4f}")
    index = len(str(-int(f.max(initial=0))))
    return (len(v) * (len(_VERTEX % (0, 0, 0)) + 3 * (wide - 6)) + len(_BETWEEN)
            + len(f) * (len(_TRIANGLE % (0, 0, 0)) + 3 * (index - 1)))


def mesh_rows_into(out, vertices: np.ndarray, faces: np.ndarray) -> list[int]:
    """:func:`mesh_rows` as UTF-8 written one piece after the other into the buffer ``out`` (of
    :func:`mesh_rows_bound` bytes); the end of each piece."""
    ends, at = [], 0
    for text in mesh_rows(vertices, faces):
        data = text.encode("utf-8")
        out[at:at + len(data)] = data
        at += len(data)
        ends.append(at)
    return ends


def model_xml(objects: Iterable[dict], metadata: dict[str, str]):
    """The 3dmodel.model text, in pieces: ``objects`` are dicts with name, vertices (n, 3), faces (m, 3)
    and their own metadata, and may carry ``rows``, their mesh text made beforehand (:func:`mesh_rows`,
    str or UTF-8 bytes-like); build items in a row along x, each on the bed."""
    out = [f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xml:lang="en-US" xmlns="{_NS}">\n']
    out += [f'<metadata name={quoteattr(k)}>{escape(str(v))}</metadata>\n' for k, v in sorted(metadata.items())]
    out.append("<resources>\n")
    items = []
    x = 0.0
    for oid, obj in enumerate(objects, start=1):
        v = np.asarray(obj["vertices"], float)
        f = np.asarray(obj["faces"])
        name = quoteattr(obj["name"])
        out.append(f'<object id="{oid}" type="model" name={name}>\n')
        for key, value in sorted(obj.get("metadata", {}).items()):
            out.append(f'<metadata name={quoteattr(key)}>{escape(str(value))}</metadata>\n')
        out.append("<mesh><vertices>\n")
        yield "".join(out)
        yield from obj["rows"] if "rows" in obj else _ahead(mesh_rows(v, f))
        out = ["</triangles></mesh></object>\n"]
        lo = v.min(axis=0)
        items.append(f'<item objectid="{oid}" transform="1 0 0 0 1 0 0 0 1 {x - lo[0]:.4f} {-lo[1]:.4f} {-lo[2]:.4f}"/>\n')
        x += float(v[:, 0].max() - lo[0]) + GAP_MM
    out.append("</resources>\n<build>\n")
    out += items
    out.append("</build>\n</model>\n")
    yield "".join(out)


def _ahead(pieces, depth: int = 2):
    """The pieces of an iterator, made in a thread ``depth`` pieces ahead: the text of the next chunk is
    formatted while zlib (which releases the GIL) deflates this one; the same pieces in the same order."""
    box: queue.Queue = queue.Queue(depth)
    stop = threading.Event()
    end = object()

    def make():
        try:
            for piece in pieces:
                while not stop.is_set():
                    try:
                        box.put((piece, None), timeout=0.1)
                        break
                    except queue.Full:
                        continue
                if stop.is_set():
                    return
            box.put((end, None))
        except BaseException as exc:            # re-raised in the caller
            box.put((end, exc))

    worker = threading.Thread(target=make, daemon=True, name="3mf-text")
    worker.start()
    try:
        while True:
            piece, exc = box.get()
            if piece is end:
                if exc is not None:
                    raise exc
                return
            yield piece
    finally:
        stop.set()
        worker.join()


def three_mf_bytes(objects: Iterable[dict], metadata: dict[str, str]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        for name, pieces in (("[Content_Types].xml", [_CONTENT_TYPES]), ("_rels/.rels", [_RELS]),
                             ("3D/3dmodel.model", model_xml(objects, metadata))):
            info = zipfile.ZipInfo(name, _DATE)            # a fixed date: the bytes are reproducible
            info.compress_type = zipfile.ZIP_DEFLATED
            info._compresslevel = DEFLATE_LEVEL            # as ZipFile.open sets it for a member named by a string
            with z.open(info, "w") as member:
                for text in pieces:
                    member.write(text.encode("utf-8") if isinstance(text, str) else text)
    return buf.getvalue()


_STL_RECORD = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def stl_size(triangles: int) -> int:
    """Bytes of a binary STL of ``triangles``."""
    return 84 + _STL_RECORD.itemsize * triangles


def stl_into(out, vertices: np.ndarray, faces: np.ndarray, name: str) -> None:
    """Binary STL of a triangle mesh (normals from the counter-clockwise winding) written into the
    writable buffer ``out`` of :func:`stl_size` bytes."""
    t = np.asarray(vertices, np.float64)[np.asarray(faces, np.int64)]
    n = cross_rows(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
    rec = np.frombuffer(out, _STL_RECORD, len(t), 84)
    rec["n"], rec["v"], rec["attr"] = n, t, 0
    out[:84] = name.encode("ascii", "replace")[:80].ljust(80, b" ") + np.uint32(len(t)).tobytes()


def stl_bytes(vertices: np.ndarray, faces: np.ndarray, name: str) -> bytes:
    """Binary STL of a triangle mesh (:func:`stl_into`)."""
    out = bytearray(stl_size(len(faces)))
    stl_into(out, vertices, faces, name)
    return bytes(out)
