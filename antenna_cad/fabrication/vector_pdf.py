"""A minimal streaming PDF writer for vector line drawings (PDF 1.4, ISO 32000-1 §7).

Templates are many pages of thin lines and a little text; matplotlib spent ~90 ms per page laying
out every text of a drawing on every tile. Here each drawing is written once as a Form XObject
(§8.10) and every page places it with a clip rectangle and a transform, so a page costs a few
hundred bytes and well under a millisecond. Text uses the standard Helvetica font with
WinAnsiEncoding (no embedding); characters outside it are spelled out (``ε`` → ``e``).
Output is byte-reproducible: no dates, no IDs, objects numbered in writing order.
"""

from __future__ import annotations

import importlib.util
import zlib
from functools import cache, lru_cache
from pathlib import Path
from typing import BinaryIO

PT_PER_MM = 72.0 / 25.4
_SPELLED = {"ε": "e", "λ": "lambda", "Δ": "d", "ρ": "rho", "↑": "^", "↓": "v", "→": "->", "≤": "<=", "≥": ">=",
            "≈": "~", "√": "sqrt", "∅": "O", "−": "-", "’": "'", "η": "eta", "σ": "sigma", "Σ": "S",
            "θ": "theta", "π": "pi", "φ": "phi"}


def spelled(text: str) -> str:
    """``text`` with the characters the standard fonts lack spelled out in ones they have."""
    return "".join(_SPELLED.get(ch, ch) for ch in text)


def pdf_string(text: str) -> bytes:
    """``text`` as a PDF literal string in WinAnsiEncoding (unsupported characters spelled out)."""
    raw = spelled(text).encode("cp1252", errors="replace")
    return b"(" + raw.replace(b"\\", b"\\\\").replace(b"(", b"\\(").replace(b")", b"\\)") + b")"


def num(value: float) -> str:
    """A coordinate with 3 decimals and no trailing zeros (PDF has no exponent notation)."""
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def polyline_ops(points, closed: bool) -> str:
    """Path construction and stroke operators for one polyline."""
    (x, y), rest = points[0], points[1:]
    ops = [f"{num(x)} {num(y)} m"] + [f"{num(px)} {num(py)} l" for px, py in rest]
    return "\n".join(ops) + ("\ns\n" if closed else "\nS\n")


@cache
def _helvetica() -> dict[str, float]:
    """Advance widths (1/1000 em) of Helvetica's glyphs by character, read from the font's Adobe
    Font Metrics (the AFM file matplotlib ships for the PDF standard fonts; read as text, without
    importing matplotlib, so building drawings stays light) and named by the Adobe Glyph List."""
    from fontTools.agl import AGL2UV
    mpl = importlib.util.find_spec("matplotlib").submodule_search_locations[0]
    widths = {}
    for line in (Path(mpl) / "mpl-data/fonts/pdfcorefonts/Helvetica.afm").read_text(encoding="latin-1").splitlines():
        if line.startswith("C "):
            fields = dict(item.strip().split(" ", 1) for item in line.split(";") if item.strip())
            if fields["N"] in AGL2UV:
                widths[chr(AGL2UV[fields["N"]])] = float(fields["WX"])
    return widths


def text_width(text: str, size: float) -> float:
    """Advance width of ``text`` as drawn (spelled out, in WinAnsiEncoding) in Helvetica at font size
    ``size``; a glyph the font lacks counts a full em, never too short."""
    widths = _helvetica()
    drawn = spelled(text).encode("cp1252", errors="replace").decode("cp1252")
    return sum(widths.get(ch, 1000.0) for ch in drawn) * size / 1000.0


def wrap_text(text: str, width: float, size: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` in Helvetica at ``size`` (a
    single word wider than that stands alone, broken by characters). Remembered: a drawing's title
    block is wrapped again on each of its tiles (21,000 pages for a large layup, issue 16)."""
    return list(_wrapped(text, width, size))


@lru_cache(maxsize=4096)
def _wrapped(text: str, width: float, size: float) -> tuple[str, ...]:
    lines: list[str] = []
    for word in text.split(" "):
        trial = f"{lines[-1]} {word}" if lines else word
        if lines and text_width(trial, size) <= width:
            lines[-1] = trial
            continue
        while text_width(word, size) > width and len(word) > 1:
            cut = max(k for k in range(1, len(word) + 1) if k == 1 or text_width(word[:k], size) <= width)
            lines.append(word[:cut])
            word = word[cut:]
        lines.append(word)
    return tuple(lines or [""])


def text_ops(text: str, x: float, y: float, size: float) -> bytes:
    return f"BT /F1 {num(size)} Tf {num(x)} {num(y)} Td ".encode() + pdf_string(text) + b" Tj ET\n"


class VectorPdf:
    """Write objects as they come: forms (shared drawings) and pages; ``close`` adds the page
    tree, catalogue, info and cross-reference table."""

    _CATALOG, _PAGES, _FONT, _INFO = 1, 2, 3, 4

    def __init__(self, path: Path, page_size_mm: tuple[float, float], title: str):
        self._file: BinaryIO = path.open("wb")
        self._offsets: dict[int, int] = {}
        self._next = 5
        self._pages: list[int] = []
        self._media = f"[0 0 {num(page_size_mm[0] * PT_PER_MM)} {num(page_size_mm[1] * PT_PER_MM)}]"
        self._title = title
        self._file.write(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
        self._object(self._FONT, b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica "
                                 b"/Encoding /WinAnsiEncoding >>")

    def add_form(self, content: bytes, bbox: tuple[float, float, float, float]) -> int:
        """A Form XObject in its own units; returns its object number."""
        number = self._allocate()
        box = " ".join(num(v) for v in bbox)
        self._stream(number, f"/Type /XObject /Subtype /Form /BBox [{box}] "
                             f"/Resources << /Font << /F1 {self._FONT} 0 R >> >>", content)
        return number

    def add_page(self, content: bytes, forms: tuple[int, ...] = ()) -> None:
        """A page drawn in points; ``forms`` are available as /X<number>."""
        contents = self._allocate()
        self._stream(contents, "", content)
        xobjects = " ".join(f"/X{n} {n} 0 R" for n in forms)
        page = self._allocate()
        self._object(page, f"<< /Type /Page /Parent {self._PAGES} 0 R /MediaBox {self._media} "
                           f"/Resources << /Font << /F1 {self._FONT} 0 R >> /XObject << {xobjects} >> >> "
                           f"/Contents {contents} 0 R >>".encode())
        self._pages.append(page)

    @property
    def page_count(self) -> int:
        return len(self._pages)

    def close(self) -> None:
        kids = " ".join(f"{n} 0 R" for n in self._pages)
        self._object(self._PAGES, f"<< /Type /Pages /Kids [{kids}] /Count {len(self._pages)} >>".encode())
        self._object(self._CATALOG, f"<< /Type /Catalog /Pages {self._PAGES} 0 R >>".encode())
        self._object(self._INFO, b"<< /Title " + pdf_string(self._title)
                     + b" /Creator (antenna_cad) /Producer (antenna_cad) >>")
        xref = self._file.tell()
        lines = [f"xref\n0 {self._next}\n", "0000000000 65535 f \n"]
        lines += [f"{self._offsets[n]:010d} 00000 n \n" for n in range(1, self._next)]
        lines.append(f"trailer\n<< /Size {self._next} /Root {self._CATALOG} 0 R /Info {self._INFO} 0 R >>\n"
                     f"startxref\n{xref}\n%%EOF\n")
        self._file.write("".join(lines).encode())
        self._file.close()

    def __enter__(self) -> VectorPdf:
        return self

    def __exit__(self, kind, value, traceback) -> None:
        if kind is None:
            self.close()
        else:
            self._file.close()

    def _allocate(self) -> int:
        self._next += 1
        return self._next - 1

    def _object(self, number: int, body: bytes) -> None:
        self._offsets[number] = self._file.tell()
        self._file.write(f"{number} 0 obj\n".encode() + body + b"\nendobj\n")

    def _stream(self, number: int, dictionary: str, content: bytes) -> None:
        data = zlib.compress(content, 6)
        self._object(number, f"<< {dictionary} /Length {len(data)} /Filter /FlateDecode >>\nstream\n".encode()
                     + data + b"\nendstream")
