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

import numpy as np

PT_PER_MM = 72.0 / 25.4
_SPELLED = {"ε": "e", "λ": "lambda", "Δ": "d", "ρ": "rho", "↑": "^", "↓": "v", "→": "->", "≤": "<=", "≥": ">=",
            "≈": "~", "√": "sqrt", "∅": "O", "−": "-", "’": "'", "η": "eta", "σ": "sigma", "Σ": "S",
            "θ": "theta", "π": "pi", "φ": "phi"}


_SPELLING = str.maketrans(_SPELLED)


def spelled(text: str) -> str:
    """``text`` with the characters the standard fonts lack spelled out in ones they have."""
    return text.translate(_SPELLING)


def pdf_string(text: str) -> bytes:
    """``text`` as a PDF literal string in WinAnsiEncoding (unsupported characters spelled out)."""
    raw = spelled(text).encode("cp1252", errors="replace")
    return b"(" + raw.replace(b"\\", b"\\\\").replace(b"(", b"\\(").replace(b")", b"\\)") + b")"


def num(value: float) -> str:
    """A coordinate with 3 decimals and no trailing zeros (PDF has no exponent notation)."""
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


_FORMATS = np.array(["%.0f", "%.1f", "%.2f", "%.3f"])


def nums(points, sep: str, end) -> str:
    """"x{sep}y{end}" for every (x, y) of ``points`` (``end``: one string, or one per point),
    numbers as :func:`num` writes them (3 decimals, no trailing zeros, no "-0"; rounded half-way
    cases may differ by 0.001), formatted in bulk: drawings of a large layup hold millions of
    vertices."""
    if isinstance(end, str) and len(points) < 16:     # short lines: the bulk set-up costs more than it saves
        return "".join(f"{num(x)}{sep}{num(y)}{end}" for x, y, *_ in points)
    v = np.rint(np.asarray(points, dtype=float).reshape(-1, 2) * 1000.0)
    f = _FORMATS[(v % 10 != 0).astype(int) + (v % 100 != 0) + (v % 1000 != 0)]
    pattern = "".join(np.char.add(np.char.add(np.char.add(f[:, 0], sep), f[:, 1]), end).tolist())
    return pattern % tuple((v / 1000.0 + 0.0).ravel().tolist())


def polylines_ops(lines, closed: bool) -> str:
    """Path construction and stroke operators ("x y m", "x y l", …, then "s" closed or "S" open)
    for every line, formatted in one pass."""
    lines = [np.asarray(line, dtype=float)[:, :2] for line in lines if len(line)]
    if not lines:
        return ""
    counts = np.array([len(line) for line in lines])
    last = np.cumsum(counts) - 1
    ends = np.full(int(counts.sum()), " l\n", dtype="<U8")
    ends[last - counts + 1] = " m\n"
    ends[last] = np.char.add(ends[last], "s\n" if closed else "S\n")
    return nums(np.concatenate(lines), " ", ends)


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


@cache
def _glyph_units(ch: str) -> float:
    """Advance of one character as drawn (spelled out, in WinAnsiEncoding), 1/1000 em; a glyph
    the font lacks counts a full em, never too short. Helvetica's widths are whole units, so
    sums of them are exact in any order."""
    widths = _helvetica()
    drawn = spelled(ch).encode("cp1252", errors="replace").decode("cp1252")
    return sum(widths.get(c, 1000.0) for c in drawn)


def _units(text: str) -> float:
    return sum(map(_glyph_units, text))


def text_width(text: str, size: float) -> float:
    """Advance width of ``text`` as drawn in Helvetica at font size ``size`` (no kerning)."""
    return _units(text) * size / 1000.0


def wrap_text(text: str, width: float, size: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` in Helvetica at ``size`` (a
    single word wider than that stands alone, broken by characters). Remembered: a drawing's title
    block is wrapped again on each of its tiles (21,000 pages for a large layup)."""
    return list(_wrapped(text, width, size))


@lru_cache(maxsize=4096)
def _wrapped(text: str, width: float, size: float) -> tuple[str, ...]:
    """Greedy fill, linear in the text: a line's width is the sum of its words' and spaces'."""
    fits = lambda units: units * size / 1000.0 <= width      # noqa: E731  (as text_width)
    space = _glyph_units(" ")
    lines: list[str] = []
    used = 0.0                                   # units of lines[-1]
    for word in text.split(" "):
        units = _units(word)
        if lines and fits(used + space + units):
            lines[-1] = f"{lines[-1]} {word}"
            used += space + units
            continue
        while not fits(units) and len(word) > 1:
            cut, run = 1, _glyph_units(word[0])
            while cut < len(word) and fits(run + _glyph_units(word[cut])):
                run += _glyph_units(word[cut])
                cut += 1
            lines.append(word[:cut])
            word, units = word[cut:], units - run
        lines.append(word)
        used = units
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
        data = zlib.compress(content, 1)
        self._object(number, f"<< {dictionary} /Length {len(data)} /Filter /FlateDecode >>\nstream\n".encode()
                     + data + b"\nendstream")
