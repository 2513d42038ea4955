"""Nesting pieces on stock boards with rectpack (bounding rectangles, 90° rotation allowed).

Each material is nested on its own boards. Rectangles are the kerf-compensated cut paths' bounds
plus ``NEST_SPACING_MM`` all round, in whole millimetres; the packing is deterministic.

Best fit looks only at the last ``OPEN_BOARDS`` boards opened; older ones are closed. rectpack's
best fit otherwise tries every open board for every piece, which is quadratic in the piece count
(a 3 m Luneburg layup: 31 000 sector pieces on 1 300 boards took 32 s). Layups with at most
``OPEN_BOARDS`` boards per material pack exactly as before.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import rectpack
from rectpack.packer import Packer, PackerBBFMixin

from antenna_cad.fabrication.outline import NEST_SPACING_MM


OPEN_BOARDS = 16


class _WindowMixin(PackerBBFMixin):
    """Best fit over the ``OPEN_BOARDS`` newest boards; older ones are closed."""

    def add_rect(self, width, height, rid=None):
        placed = super().add_rect(width, height, rid)
        while len(self._open_bins) > OPEN_BOARDS:
            self._closed_bins.append(self._open_bins.popleft())
        return placed


class _WindowedBestFit(Packer, _WindowMixin):
    """Offline (pieces sorted by area, ``Packer.pack``) windowed best fit."""


@dataclass(frozen=True)
class Placement:
    key: str               # piece label
    board_id: str          # e.g. "xps-B01"
    x_mm: float            # lower-left corner of the piece's bounding box on the board
    y_mm: float
    rotated: bool


def nest(items: list[tuple[str, float, float]], board_w: float, board_l: float,
         prefix: str) -> list[Placement]:
    """Pack ``(key, width, height)`` rectangles onto as many ``board_w × board_l`` boards as needed."""
    if not items:
        return []
    packer = _WindowedBestFit(sort_algo=rectpack.SORT_AREA, rotation=True)
    sizes = {}
    for i, (key, w, h) in enumerate(items):
        rw, rh = math.ceil(w + 2 * NEST_SPACING_MM), math.ceil(h + 2 * NEST_SPACING_MM)
        sizes[i] = (rw, rh)
        packer.add_rect(rw, rh, rid=i)
    packer.add_bin(int(board_w), int(board_l), count=float("inf"))
    packer.pack()
    placed = {}
    for b, x, y, w, h, rid in packer.rect_list():
        rotated = (w, h) != sizes[rid]
        placed[rid] = Placement(items[rid][0], f"{prefix}-B{b + 1:02d}", x + NEST_SPACING_MM,
                                y + NEST_SPACING_MM, rotated)
    missing = [items[i][0] for i in range(len(items)) if i not in placed]
    if missing:
        raise ValueError(f"pieces do not fit a {board_w:g} × {board_l:g} mm board: {', '.join(missing)}")
    return [placed[i] for i in range(len(items))]
