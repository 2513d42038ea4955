"""Slot layout (per guide, per cell, per slot) and its manufacturability checks (seed-003 §8.1, §8.3)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from antenna_cad.synthesis.checks import Check, DesignError
from antenna_cad.synthesis.slot_array.common import LAYOUTS, _lower
from antenna_cad.synthesis.slot_array.curves import Curve, offset_curve


@dataclass(frozen=True)
class SlotLayout:
    """Every slot of the array, flat arrays of equal length (frame: module docstring, mm).

    Per slot: ``guide_index`` (0 = most negative x), ``cell_index`` (0 = nearest the coupling
    slot), ``slot_in_cell``; centre ``x_mm``, ``y_mm``; ``length_mm`` (long side), ``width_mm``;
    ``offset_mm`` = x_mm − guide axis x (signed); ``angle_rad`` = angle of the long side from +y
    (0 longitudinal, π/2 transverse). Per guide: ``guide_x_mm`` (axis), ``guide_entry_y_mm``
    (on the last mirror), ``t_mm`` (entry → slot line), ``slot_line_y_mm``, ``guide_end_y_mm``
    (slot line + n_cells·period). Slots are rectangles length × width (round ends fit inside).
    """
    layout: str
    guide_index: np.ndarray
    cell_index: np.ndarray
    slot_in_cell: np.ndarray
    x_mm: np.ndarray
    y_mm: np.ndarray
    length_mm: np.ndarray
    width_mm: np.ndarray
    offset_mm: np.ndarray
    angle_rad: np.ndarray
    guide_x_mm: np.ndarray
    guide_entry_y_mm: np.ndarray
    t_mm: np.ndarray
    slot_line_y_mm: np.ndarray
    guide_end_y_mm: np.ndarray
    period_mm: float
    n_cells: int

    @property
    def count(self) -> int:
        return int(self.x_mm.size)

    def half_extents_mm(self) -> tuple[np.ndarray, np.ndarray]:
        """(half size across the guide, half size along the guide) of every slot."""
        c, s = np.abs(np.cos(self.angle_rad)), np.abs(np.sin(self.angle_rad))
        hl, hw = self.length_mm / 2, self.width_mm / 2
        return hl * s + hw * c, hl * c + hw * s

    def as_table(self) -> np.ndarray:
        """(N, 9) table: guide, cell, slot, x, y, length, width, offset, angle."""
        return np.column_stack([self.guide_index, self.cell_index, self.slot_in_cell, self.x_mm,
                                self.y_mm, self.length_mm, self.width_mm, self.offset_mm,
                                self.angle_rad])


def cell_pattern(layout: str, *, n_cells: int, period_mm: float, guide_width_mm: float,
                 lengths_mm=None, l2_mm=None, l2_ratio: float = 0.68, offset_mm=None,
                 pair_shift_mm: float | None = None,
                 transverse_spacings_mm: Sequence[float] = (1.66, 1.62)):
    """Slot pattern of one period: (dy (J,), offset (J,), lengths (n_cells, J), angle (J,)).

    * ``longitudinal_4`` (seed-003 §2.1, Fig. 1.9 lost — ASSUMED geometry): four slots at p/4
      spacing, offsets alternating +o, −o, +o, −o (o = ``offset_mm``, default a/4); the first has
      length L1 (``lengths_mm`` per cell, from the taper), the other three L2 (``l2_mm`` scalar or
      per cell, default ``l2_ratio``·L1; Table 1.1 upper rows have L2/L1 ≈ 0.68).
    * ``longitudinal_pair`` (seed-003 §2.4): two slots at ±o (default a/4) shifted
      ``pair_shift_mm`` (λg/2 at the design frequency) along the guide; length per cell.
    * ``transverse_3`` (seed-003 §2.2): three transverse slots on the axis at 0, d1, d1 + d2
      (centre spacings ``transverse_spacings_mm``), lengths s1..s3 (``lengths_mm``: 3 values).
    """
    a = guide_width_mm
    o = a / 4 if offset_mm is None else float(offset_mm)
    if layout == "longitudinal_4":
        L1 = np.broadcast_to(np.asarray(lengths_mm, float), (n_cells,))
        L2 = l2_ratio * L1 if l2_mm is None else np.broadcast_to(np.asarray(l2_mm, float), (n_cells,))
        lengths = np.column_stack([L1, L2, L2, L2])
        dy = np.arange(4) * period_mm / 4
        off = o * np.array([1.0, -1.0, 1.0, -1.0])
        ang = np.zeros(4)
    elif layout == "longitudinal_pair":
        L = np.broadcast_to(np.asarray(lengths_mm, float), (n_cells,))
        lengths = np.column_stack([L, L])
        dy = np.array([0.0, float(pair_shift_mm)])
        off = o * np.array([1.0, -1.0])
        ang = np.zeros(2)
    elif layout == "transverse_3":
        s = np.asarray(lengths_mm, float)
        if s.shape != (3,):
            raise DesignError("slots.lengths_mm", f"transverse_3 needs 3 lengths s1..s3 "
                              f"(got shape {s.shape})")
        d1, d2 = transverse_spacings_mm
        lengths = np.broadcast_to(s, (n_cells, 3))
        dy = np.array([0.0, d1, d1 + d2])
        off = np.zeros(3)
        ang = np.full(3, np.pi / 2)
    else:
        raise DesignError("slots.layout", f"unknown layout {layout!r} (use one of {LAYOUTS})")
    if np.any(np.asarray(lengths) <= 0) or not np.all(np.isfinite(lengths)):
        raise DesignError("slots.lengths_mm", f"slot lengths must be finite and > 0 "
                          f"(min {np.nanmin(lengths):.4g} mm)")
    return dy, off, np.asarray(lengths, float), ang


def build_slot_layout(*, layout: str, guide_x_mm, guide_entry_y_mm, t_mm, n_cells: int,
                      period_mm: float, width_mm: float, dy, off, lengths, ang) -> SlotLayout:
    """Broadcast the cell pattern over guides × cells (vectorised, linear in slot count)."""
    gx = np.asarray(guide_x_mm, float)
    gy = np.asarray(guide_entry_y_mm, float)
    t = np.asarray(t_mm, float)
    G, M, J = gx.size, n_cells, len(dy)
    line = gy + t
    gi = np.broadcast_to(np.arange(G)[:, None, None], (G, M, J))
    ci = np.broadcast_to(np.arange(M)[None, :, None], (G, M, J))
    si = np.broadcast_to(np.arange(J)[None, None, :], (G, M, J))
    y = line[:, None, None] + np.arange(M)[None, :, None] * period_mm + np.asarray(dy)[None, None, :]
    offs = np.broadcast_to(np.asarray(off)[None, None, :], (G, M, J))
    x = gx[:, None, None] + offs
    L = np.broadcast_to(lengths[None, :, :], (G, M, J))
    A = np.broadcast_to(np.asarray(ang)[None, None, :], (G, M, J))
    f = lambda v: np.ascontiguousarray(v).reshape(-1)
    return SlotLayout(layout, f(gi), f(ci), f(si), f(x), f(y), f(L), np.full(G * M * J, width_mm),
                      f(offs), f(A), gx, gy, t, line, line + M * period_mm, float(period_mm), M)


def check_slots_in_wall(slots: SlotLayout, guide_width_mm: float,
                        clearance_mm: float = 0.0) -> Check:
    """Every slot inside the broad wall: |offset| + half size across ≤ a/2 − clearance (§8.3)."""
    hx, _ = slots.half_extents_mm()
    ext = np.abs(slots.offset_mm) + hx
    k = int(np.argmax(ext))
    c = Check.upper("slots_inside_wall", float(ext[k]), guide_width_mm / 2 - clearance_mm, "mm",
                    f"slot reach from guide axis (guide {slots.guide_index[k]}, cell "
                    f"{slots.cell_index[k]}, slot {slots.slot_in_cell[k]}) vs a/2 − clearance")
    return c


def slot_webs_mm(slots: SlotLayout, neighbours: int = 4) -> np.ndarray:
    """Signed web between each slot and its next ``neighbours`` slots along the same guide.

    Rectangle distance: Euclidean gap when separated, negative penetration when overlapping.
    Returns (N, neighbours) with +inf where no neighbour exists.
    """
    order = np.lexsort((slots.y_mm, slots.guide_index))
    g = slots.guide_index[order]
    x, y = slots.x_mm[order], slots.y_mm[order]
    hx, hy = (h[order] for h in slots.half_extents_mm())
    n = x.size
    out = np.full((n, neighbours), np.inf)
    for k in range(1, neighbours + 1):
        i, j = np.arange(n - k), np.arange(k, n)
        same = g[i] == g[j]
        gx = np.abs(x[i] - x[j]) - (hx[i] + hx[j])
        gy = np.abs(y[i] - y[j]) - (hy[i] + hy[j])
        web = np.where((gx > 0) & (gy > 0), np.hypot(gx, gy), np.maximum(gx, gy))
        out[i, k - 1] = np.where(same, web, np.inf)
    res = np.empty_like(out)
    res[order] = out
    return res


def check_slot_webs(slots: SlotLayout, min_web_mm: float) -> Check:
    """No overlapping slots and a minimum metal web between neighbours on a guide (§8.3)."""
    webs = slot_webs_mm(slots)
    k, kk = np.unravel_index(int(np.argmin(webs)), webs.shape)
    w = float(webs[k, kk])
    what = ("slots OVERLAP" if w < 0 else "minimum web between slots") + \
        f" (guide {slots.guide_index[k]}, cell {slots.cell_index[k]}, slot {slots.slot_in_cell[k]})"
    return _lower("slot_web", w, min_web_mm, "mm", what)


def check_coupling_clearance(slots: SlotLayout, guide_curve: Curve, coupling_slot_mm: float,
                             min_gap_mm: float = 0.0) -> Check:
    """Gap along the guide from the coupling slot (strip of width d along the last mirror,
    on the guide side) to the nearest slot edge, ≥ ``min_gap_mm`` (§8.3; d2 = 7.8 mm in §2.4)."""
    hx, hy = slots.half_extents_mm()
    edge = offset_curve(guide_curve, coupling_slot_mm, "coupling_slot_edge")
    lo, hi = edge.x_range_mm
    gaps = []
    for sgn in (-1.0, 0.0, 1.0):               # slot corners and centre across the guide
        xe = np.clip(slots.x_mm + sgn * hx, lo, hi)
        gaps.append(slots.y_mm - hy - edge.y_at(xe))
    gap = np.minimum.reduce(gaps)
    k = int(np.argmin(gap))
    return _lower("coupling_slot_clearance", float(gap[k]), min_gap_mm, "mm",
                  f"gap from coupling slot to slot (guide {slots.guide_index[k]}, cell "
                  f"{slots.cell_index[k]}, slot {slots.slot_in_cell[k]})")
