"""The runner's input (the deck) from the same profiles and sheet plan the CAD uses.

A lens of revolution as (r, z) polygons in mm, one per part with its εr (seed-000 frame: +z the axis,
toward the antenna): the ideal lens between its synthesized front and back faces; the stepped stack as
cut (every sheet's disc, :func:`antenna_cad.fabrication.section.stepped_section`); the stack as
fabricated (:func:`antenna_cad.fabrication.section.fabricated_section`: necks, dowels and board strips
cut by the plane x = 0; the body of revolution takes its upper half, y ≥ 0, away from the pedestal).
The feed's analytic field enters on a Huygens sheet ``SHEET_GAP_LAMBDA`` in front of the lens.
"""

from __future__ import annotations

import numpy as np

from antenna_cad.raytrace.trace2d import Slabs

SHEET_GAP_LAMBDA = 1.5      # Huygens sheet in front of the lens's foremost point
R_MARGIN_LAMBDA = 1.0       # air beside the rim before the radial PML
PML_R_LAMBDA = 4.0          # radial PML with the sheet feed (2 λ gave a 3° dip near the axis)
PML_Z_LAMBDA = 2.0
BACK_MARGIN_LAMBDA = 1.0    # air behind the aperture plane before the PML
PROFILE_POINTS = 400
DECIMALS = 1                # polygon coordinates to 0.1 mm: far below any grid, and the cut outlines' chord
                            # tolerance (≈ 0.002 mm) no longer tells the stack as cut from the one as fabricated


def ideal_parts(front_z, back_z, radius_mm: float, eps_r: float) -> list[dict]:
    """The ideal lens: front face z = front_z(r), back face z = back_z(r), 0 ≤ r ≤ radius."""
    r = np.linspace(0.0, radius_mm, PROFILE_POINTS)
    poly = np.concatenate([np.column_stack([r, front_z(r)]), np.column_stack([r[::-1], back_z(r[::-1])])])
    return [{"label": "lens", "eps_r": float(eps_r), "polygon": np.round(poly, DECIMALS).tolist()}]


def slab_parts(slabs: Slabs, eps_r: float, labels: list[str] | None = None) -> list[dict]:
    """A stepped section's dielectric on y ≥ 0 as rectangles in (r, z), one per sheet and run."""
    y = np.concatenate([[-np.inf], slabs.y_breaks, [np.inf]])
    parts = []
    for k, row in enumerate(slabs.material):
        z0, z1 = round(float(slabs.z_edges[k]), DECIMALS), round(float(slabs.z_edges[k + 1]), DECIMALS)
        edges = np.diff(np.concatenate([[0], row.astype(int), [0]]))
        for lo, hi in zip(y[np.nonzero(edges == 1)[0]], y[np.nonzero(edges == -1)[0]]):
            lo, hi = round(max(float(lo), 0.0), DECIMALS), round(float(hi), DECIMALS)
            if hi > lo and np.isfinite(hi):
                label = labels[k] if labels else f"slab-{k:02d}"
                parts.append({"label": label, "eps_r": float(eps_r),
                              "polygon": [[lo, z0], [hi, z0], [hi, z1], [lo, z1]]})
    return parts


def make_deck(parts: list[dict], *, frequency_ghz: float, resolution: float, feed_z_mm: float,
              feed_pattern: str, feed_q: float, radius_mm: float, plane_offset_lambda: float,
              field_map: bool = True, m: int = 1, reflected: bool = False, point_feed: str | None = None,
              volume_z_mm: tuple[float, float] | None = None) -> dict:
    """The runner's input: named parameters (εr per part, geometry in mm, feed, frequency, resolution)
    and the domain: sheet 1.5 λ before the foremost part, the aperture plane ``plane_offset_lambda``
    behind the hindmost (``reflected``: in front of the sheet, for a body that sends the beam back
    through it, seed-004; the feed itself is not meshed, so it blocks nothing), radial PML 4 λ, axial 2 λ.
    ``point_feed`` (``dipole``/``huygens``): no sheet, the runner's point source at ``feed_z_mm`` (a feed
    on the body's surface, seed-004 f0 = 0); a reflected beam's plane is then measured from the feed.
    ``volume_z_mm`` (z0, z1): the runner also records the field over the (r, z) half-plane between them
    (the quiet zone's depth), the domain reaching past z1."""
    lam = 299.792458 / frequency_ghz
    pts = np.array([p for part in parts for p in part["polygon"]]) if parts else np.zeros((1, 2))
    z_front, z_back = float(pts[:, 1].min()), float(pts[:, 1].max())
    sheet = feed_z_mm if point_feed else z_front - SHEET_GAP_LAMBDA * lam
    if reflected:
        plane = sheet - plane_offset_lambda * lam
        z_min, z_max = plane - BACK_MARGIN_LAMBDA * lam, z_back + BACK_MARGIN_LAMBDA * lam
    else:
        plane = z_back + plane_offset_lambda * lam
        z_min, z_max = sheet - 0.5 * lam, max([plane, *(volume_z_mm or ())]) + BACK_MARGIN_LAMBDA * lam
    feed = ({"kind": "point", "z_mm": float(feed_z_mm), "pattern": point_feed} if point_feed else
            {"z_mm": float(feed_z_mm), "pattern": feed_pattern, "q": float(feed_q)})
    where = {} if point_feed else {"sheet_z_mm": round(sheet, 4)}
    if volume_z_mm is not None:
        where["volume_z_mm"] = [round(float(z), 4) for z in volume_z_mm]
    return {"frequency_ghz": float(frequency_ghz), "resolution_px_per_lambda": float(resolution), "m": int(m),
            "parts": parts, "feed": feed, **where, "plane_z_mm": round(plane, 4),
            "r_max_mm": round(radius_mm + R_MARGIN_LAMBDA * lam, 4),
            "z_min_mm": round(z_min, 4), "z_max_mm": round(z_max, 4),
            "pml_r_lambda": PML_R_LAMBDA, "pml_z_lambda": PML_Z_LAMBDA, "field_map": bool(field_map)}
