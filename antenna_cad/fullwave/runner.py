"""Meep runner: one body-of-revolution FDTD run, JSON in, npz out.

Executed by the interpreter that has Debian's ``python3-meep`` (built against Debian's numpy, so never
imported by the pipeline itself): ``python3 -m antenna_cad.fullwave.runner deck.json result.npz`` or
``python3 runner.py deck.json result.npz``. It imports only numpy, matplotlib (for the point-in-polygon
test) and meep; nothing else of the package.

Set-up (measured, DESIGN.md "Verification models"): ``dimensions=CYLINDRICAL`` with azimuthal order
``m`` (+1 carries the co-polar field of a linearly polarized on-axis feed), unit length = λ0 so the
resolution is in px/λ. The lens is ε(r, z) from the deck's (r, z) polygons, one per part, rasterized
with 5×5 sub-samples per pixel (area-weighted ε: subpixel smoothing) into a ``MaterialGrid``. The feed
enters through a Huygens current sheet (J = ẑ×H, M = −ẑ×E of the analytic feed field) on the plane
``sheet_z_mm``, extended through the radial PML; empty space between the feed and the lens is not
meshed. A laterally displaced feed comes as one azimuthal order m per run, its sheet fields tabulated
in the deck (``sheet``, :mod:`antenna_cad.fullwave.offaxis`). Or (feed ``kind: point``, a Luneburg
sphere's feed touching its surface) point sources on the axis at the feed: ``Er`` alone (a transverse
electric dipole, circularly polarized in m = +1) or, for ``pattern: huygens``, with the crossed
magnetic dipole ``Hφ`` that makes it a Huygens element radiating toward +z (seed-002 §2.4.5).
``graded``: spheres whose ε(r) is a table (r_mm, eps_r), sampled at the same sub-samples (the
continuous law as a per-pixel ε).

A part with ``"metal": true`` (no εr) is a perfect conductor: Meep 1.25 averages only lossless
dielectrics, so it is stair-stepped: every cell at least half inside becomes metal, one ``mp.metal``
block per run of cells along z. Meep still averages over each node's voxel and a node is a conductor
only when its whole voxel is, so the blocks are grown by half a cell: the raster's faces are then the
conducting surfaces (measured: a flat plate behind a slab within 3° of the Yee-grid plane-wave
theory at 16–24 px/λ, 45° off without the growth). The aperture plane may lie on either side of the
sheet: in front of it (z < sheet) it sees the wave a reflecting body sends back through the sheet
(plus the sheet's own weak back lobe, which a run without parts measures).

Gaussian pulse, DFT at f0. Output: Er, Eφ at f0 on the plane ``plane_z_mm`` (r_i = i/res, Meep 1.25's
metadata being wrong in cylindrical coordinates) and |E| over the (r, z) cell, decimated; with
``far_field`` the radiated power density against θ from a near-to-far surface around feed and lens
(its directivity: :func:`antenna_cad.fullwave.sphere.far_directivity_dbi`). With ``volume_z_mm``
[z0, z1] (the quiet zone's depth, :mod:`antenna_cad.quietzone`), also the complex Er over the (r, z)
half-plane r ≤ ``r_max_mm``, z0 ≤ z ≤ z1, undecimated (``volume_er`` [r, z], its axes
``volume_r_mm``, ``volume_z_mm``): one run gives every plane of the zone.
"""

from __future__ import annotations

import json
import os
import sys
import time

import numpy as np

C_MM_GHZ = 299.792458          # speed of light, mm·GHz
SUBSAMPLES = 5
MAP_MAX_PX = 240               # field map decimated to at most this many pixels a side
EXTRA_PERIODS = 30.0           # after the pulse has crossed the cell (≤ 0.03° change past 30, fullwave-notes)
FWIDTH = 0.5                   # Gaussian pulse bandwidth, units of f0
FAR_MARGIN_LAMBDA = 0.25     # near-to-far surface this far inside the PML-free cell
FAR_POINTS = 181
FAR_RADIUS_LAMBDA = 1000.0
HUYGENS_HP = 1.0               # Hφ/Er of the point Huygens element (η0 = 1): front/back 54 dB toward +z
                               # (an Hr source at r = 0 does nothing in Meep 1.25; the wrong sign radiates to −z)


def feed_pattern(theta: np.ndarray, pattern: str, q: float) -> tuple[np.ndarray, np.ndarray]:
    """(E-plane, H-plane) far-field amplitude of the feed: a short dipole along the polarization
    (cos θ, 1) or a cos^q horn (cos^q θ in both planes)."""
    c = np.cos(theta)
    if pattern == "dipole":
        return c, np.ones_like(c)
    cq = np.clip(c, 0.0, None) ** q
    return cq, cq


def feed_fields(r: np.ndarray, dz: np.ndarray, k: float, pattern: str, q: float):
    """m = +1 parts of the feed's (Er, Eφ, Hr, Hφ) at radius r, axial distance dz > 0 from the feed
    (η0 = 1, time e^{−iωt}): E = g·(cos φ F_E θ̂ − sin φ F_H φ̂), H = r̂ × E; cos φ → 1, sin φ → −i
    (common factor ½ dropped)."""
    R = np.hypot(r, dz)
    theta = np.arctan2(r, dz)
    fe, fh = feed_pattern(theta, pattern, q)
    g = np.exp(1j * k * R) / R
    ct = np.cos(theta)
    return fe * ct * g, 1j * fh * g, -1j * fh * ct * g, fe * g


def fill_fraction(parts, r_edges: np.ndarray, z_edges: np.ndarray) -> np.ndarray:
    """ε of each cell [r_i, r_i+1] × [z_j, z_j+1] (shape (Nr, Nz)): 1 + Σ (εr − 1)·(area fraction of
    the part's polygon), from SUBSAMPLES² points per cell."""
    from matplotlib.path import Path
    nr, nz = len(r_edges) - 1, len(z_edges) - 1
    s = (np.arange(SUBSAMPLES) + 0.5) / SUBSAMPLES
    rs = (r_edges[:-1, None] + np.diff(r_edges)[:, None] * s).ravel()
    zs = (z_edges[:-1, None] + np.diff(z_edges)[:, None] * s).ravel()
    eps = np.ones((nr, nz))
    for part in parts:
        poly = np.asarray(part["polygon"], float)
        i0, i1 = np.searchsorted(rs, [poly[:, 0].min(), poly[:, 0].max()])
        j0, j1 = np.searchsorted(zs, [poly[:, 1].min(), poly[:, 1].max()])
        i0, j0 = (i0 // SUBSAMPLES) * SUBSAMPLES, (j0 // SUBSAMPLES) * SUBSAMPLES
        i1 = min(len(rs), -(-i1 // SUBSAMPLES) * SUBSAMPLES)
        j1 = min(len(zs), -(-j1 // SUBSAMPLES) * SUBSAMPLES)
        if i1 <= i0 or j1 <= j0:
            continue
        rr, zz = np.meshgrid(rs[i0:i1], zs[j0:j1], indexing="ij")
        inside = Path(poly).contains_points(np.column_stack([rr.ravel(), zz.ravel()])).reshape(rr.shape)
        frac = inside.reshape((i1 - i0) // SUBSAMPLES, SUBSAMPLES, (j1 - j0) // SUBSAMPLES, SUBSAMPLES).mean(axis=(1, 3))
        eps[i0 // SUBSAMPLES:i1 // SUBSAMPLES, j0 // SUBSAMPLES:j1 // SUBSAMPLES] += (part["eps_r"] - 1.0) * frac
    return eps


def metal_blocks(parts, r_edges: np.ndarray, z_edges: np.ndarray) -> list[tuple[float, float, float, float]]:
    """(r0, r1, z0, z1) of the stair-stepped metal: per radial column, each run of cells whose fill
    fraction of a metal part is ≥ ½, grown by half a cell (the nodes on its faces then conduct)."""
    blocks = []
    grow = 0.5 * (r_edges[1] - r_edges[0])
    for part in parts:
        solid = fill_fraction([dict(part, eps_r=2.0)], r_edges, z_edges) >= 1.5
        edges = np.diff(np.pad(solid.astype(int), ((0, 0), (1, 1))), axis=1)
        for i, j in zip(*np.nonzero(edges == 1)):
            j1 = j + int(np.argmax(edges[i, j + 1:] == -1)) + 1
            blocks.append((r_edges[i] - grow, r_edges[i + 1] + grow, z_edges[j] - grow, z_edges[j1] + grow))
    return blocks


def graded_fill(graded, r_edges: np.ndarray, z_edges: np.ndarray) -> np.ndarray:
    """ε − 1 of each cell from the graded spheres (centre z, table r → εr, air beyond the table),
    averaged over SUBSAMPLES² points per cell."""
    s = (np.arange(SUBSAMPLES) + 0.5) / SUBSAMPLES
    rs = (r_edges[:-1, None] + np.diff(r_edges)[:, None] * s).ravel()
    zs = (z_edges[:-1, None] + np.diff(z_edges)[:, None] * s).ravel()
    add = np.zeros((len(rs), len(zs)))
    for g in graded:
        top = g["r"][-1]
        i1 = np.searchsorted(rs, top, side="right")                      # only the sphere's bounding box
        j0, j1 = np.searchsorted(zs, [g["center_z"] - top, g["center_z"] + top])
        rho = np.hypot(rs[:i1, None], zs[None, j0:j1] - g["center_z"])
        add[:i1, j0:j1] += np.interp(rho, g["r"], np.asarray(g["eps_r"]) - 1.0, right=0.0)
    return add.reshape(len(r_edges) - 1, SUBSAMPLES, len(z_edges) - 1, SUBSAMPLES).mean(axis=(1, 3))


def domain(deck: dict) -> dict:
    """The cell in units of λ0: radial size ``sr`` and axial ``sz`` with the PML (whole pixels),
    its centre ``zc`` (meep z = z/λ − zc), pixel counts and the run time in periods."""
    lam = C_MM_GHZ / deck["frequency_ghz"]
    res = float(deck["resolution_px_per_lambda"])
    r_in = deck["r_max_mm"] / lam
    z0, z1 = deck["z_min_mm"] / lam, deck["z_max_mm"] / lam
    nr = int(np.ceil((r_in + deck["pml_r_lambda"]) * res))
    nz = int(np.ceil((z1 - z0 + 2 * deck["pml_z_lambda"]) * res))
    sr, sz = nr / res, nz / res
    eps = [p.get("eps_r", 1.0) for p in deck["parts"]] + [max(g["eps_r"]) for g in deck.get("graded", [])]
    n_max = np.sqrt(max(eps + [1.0]))
    after = n_max * np.hypot(sz, sr) + EXTRA_PERIODS
    return dict(lam=lam, res=res, r_in=r_in, z0=z0, z1=z1, sr=sr, sz=sz, zc=0.5 * (z0 + z1), nr=nr, nz=nz,
                after=after, periods=after + 2 * 5.0 / FWIDTH)


def cell_updates(deck: dict) -> float:
    """Cells × time steps (Courant 0.5) of the run: what its cost scales with."""
    d = domain(deck)
    return d["nr"] * d["nz"] * 2 * d["res"] * d["periods"]


def sheet_sources(mp, src, deck: dict, d: dict) -> list:
    """The Huygens current sheet carrying the feed field (J = ẑ×H, M = −ẑ×E): the analytic on-axis
    feed, or a displaced feed's azimuthal order tabulated in the deck (``sheet``, offaxis.py)."""
    feed, lam, res, sr, zc = deck["feed"], d["lam"], d["res"], d["sr"], d["zc"]
    k = 2 * np.pi
    zs = deck["sheet_z_mm"] / lam - zc
    dz = (deck["sheet_z_mm"] - feed["z_mm"]) / lam
    m_scale = 1.0 / np.cos(np.pi / res)     # M sits half a cell from J: balance the pair (back lobe ≈ −26 dB)
    table = deck.get("sheet")

    def fields_at(r):
        if table is None:
            return feed_fields(np.array(r), np.array(dz), k, feed["pattern"], feed.get("q", 1.0))
        return [np.interp(r, table["r_lambda"], table[c][0]) + 1j * np.interp(r, table["r_lambda"], table[c][1])
                for c in ("er", "ep", "hr", "hp")]

    r0 = table["r_lambda"][0] if table else 0.0

    def amp(index):
        def f(p):                                                       # p relative to the line's centre
            er, ep, hr, hp = fields_at(p.x + (r0 + sr) / 2)
            return complex((-hp, hr, m_scale * ep, -m_scale * er)[index])   # J_r, J_φ, M_r, M_φ
        return f

    line = dict(center=mp.Vector3((r0 + sr) / 2, 0, zs), size=mp.Vector3(sr - r0, 0, 0))
    return [mp.Source(src, component=c, amp_func=amp(i), **line) for i, c in enumerate((mp.Er, mp.Ep, mp.Hr, mp.Hp))]


def point_sources(mp, src, feed: dict, lam: float, zc: float) -> list:
    """A point feed on the axis: an electric dipole (Er), plus the crossed magnetic dipole (Hφ) of a
    Huygens element for ``pattern: huygens``."""
    at = mp.Vector3(0, 0, feed["z_mm"] / lam - zc)
    sources = [mp.Source(src, component=mp.Er, center=at)]
    if feed["pattern"] == "huygens":
        sources.append(mp.Source(src, component=mp.Hp, center=at, amplitude=HUYGENS_HP))
    return sources


def far_surface(sim, mp, d: dict):
    """Near-to-far surface of a deck with ``far_field``: the cylinder side and both end caps
    ``FAR_MARGIN_LAMBDA`` inside the PML-free cell, enclosing the feed and the lens."""
    rs = d["r_in"] - FAR_MARGIN_LAMBDA
    za, zb = d["z0"] - d["zc"] + FAR_MARGIN_LAMBDA, d["z1"] - d["zc"] - FAR_MARGIN_LAMBDA
    return sim.add_near2far(1.0, 0, 1,
                            mp.Near2FarRegion(center=mp.Vector3(rs, 0, (za + zb) / 2), size=mp.Vector3(0, 0, zb - za)),
                            mp.Near2FarRegion(center=mp.Vector3(rs / 2, 0, zb), size=mp.Vector3(rs, 0, 0)),
                            mp.Near2FarRegion(center=mp.Vector3(rs / 2, 0, za), size=mp.Vector3(rs, 0, 0), weight=-1))


def far_power(sim, mp, n2f) -> tuple[np.ndarray, np.ndarray]:
    """Radial power density Re(E × H*)/2 at f0 against θ from +z, 0 … 180° in FAR_POINTS steps, on a
    sphere of FAR_RADIUS_LAMBDA (m = 1: the same in every φ plane)."""
    theta = np.linspace(0.0, np.pi, FAR_POINTS)
    power = []
    for t in theta:
        u = np.array([np.sin(t), 0.0, np.cos(t)])
        ff = np.asarray(sim.get_farfield(n2f, mp.Vector3(*(FAR_RADIUS_LAMBDA * u))))
        power.append(float(np.real(0.5 * np.cross(ff[:3], np.conj(ff[3:]))) @ u))
    return theta, np.array(power)


def run(deck: dict) -> dict:
    import meep as mp
    d = domain(deck)
    lam, res, r_in, z0, z1, sr, sz, zc, nr, nz = (d[k] for k in ("lam", "res", "r_in", "z0", "z1", "sr", "sz",
                                                                   "zc", "nr", "nz"))
    pml_r, pml_z = deck["pml_r_lambda"], deck["pml_z_lambda"]
    r_edges = np.linspace(0.0, sr, nr + 1)
    z_edges = np.linspace(-sz / 2, sz / 2, nz + 1)
    parts = [dict(p, polygon=[(r / lam, z / lam - zc) for r, z in p["polygon"]]) for p in deck["parts"]]
    metal = [p for p in parts if p.get("metal")]
    parts = [p for p in parts if not p.get("metal")]
    eps = fill_fraction(parts, r_edges, z_edges)
    graded = [{"center_z": g["center_z_mm"] / lam - zc, "r": np.asarray(g["r_mm"]) / lam, "eps_r": g["eps_r"]}
              for g in deck.get("graded", [])]
    if graded:
        eps += graded_fill(graded, r_edges, z_edges)
    eps_max = max([p["eps_r"] for p in parts] + [float(eps.max()), 1.0 + 1e-6])
    grid = mp.MaterialGrid(mp.Vector3(nr, 1, nz), mp.air, mp.Medium(epsilon=eps_max),
                           weights=((eps - 1.0) / (eps_max - 1.0))[:, None, :], do_averaging=False)
    geometry = [mp.Block(size=mp.Vector3(sr, 0, sz), center=mp.Vector3(sr / 2, 0, 0), material=grid)]
    geometry += [mp.Block(size=mp.Vector3(r1 - r0, 0, z1 - z0), center=mp.Vector3((r0 + r1) / 2, 0, (z0 + z1) / 2),
                          material=mp.metal) for r0, r1, z0, z1 in metal_blocks(metal, r_edges, z_edges)]

    feed = deck["feed"]
    src = mp.GaussianSource(1.0, fwidth=FWIDTH)
    sources = point_sources(mp, src, feed, lam, zc) if feed.get("kind") == "point" else sheet_sources(mp, src, deck, d)
    sim = mp.Simulation(cell_size=mp.Vector3(sr, 0, sz), dimensions=mp.CYLINDRICAL, m=deck.get("m", 1),
                        resolution=res, geometry=geometry, sources=sources, force_complex_fields=True,
                        boundary_layers=[mp.PML(pml_r, direction=mp.R), mp.PML(pml_z, direction=mp.Z)])
    zp = deck["plane_z_mm"] / lam - zc
    plane = sim.add_dft_fields([mp.Er, mp.Ep], 1.0, 0, 1, center=mp.Vector3(sr / 2, 0, zp),
                               size=mp.Vector3(sr, 0, 0))
    far = far_surface(sim, mp, d) if deck.get("far_field") else None
    whole = (sim.add_dft_fields([mp.Er, mp.Ep, mp.Ez], 1.0, 0, 1, center=mp.Vector3(r_in / 2, 0, 0),
                                size=mp.Vector3(r_in, 0, z1 - z0)) if deck.get("field_map", True) else None)
    volume = deck.get("volume_z_mm")
    if volume is not None:
        zv0, zv1 = volume[0] / lam - zc, volume[1] / lam - zc
        volume = sim.add_dft_fields([mp.Er], 1.0, 0, 1, center=mp.Vector3(r_in / 2, 0, (zv0 + zv1) / 2),
                                    size=mp.Vector3(r_in, 0, zv1 - zv0))
    t0 = time.perf_counter()
    sim.run(until_after_sources=d["after"])
    seconds = time.perf_counter() - t0
    out = {"er": np.asarray(sim.get_dft_array(plane, mp.Er, 0)),
           "ep": np.asarray(sim.get_dft_array(plane, mp.Ep, 0)),
           "seconds": seconds, "cells": nr * nz, "lambda_mm": lam}
    out["r_mm"] = np.arange(len(out["er"])) / res * lam
    if far is not None:
        out["far_theta"], out["far_power"] = far_power(sim, mp, far)
    if whole is not None:
        e = sum(np.abs(np.asarray(sim.get_dft_array(whole, c, 0))) ** 2 for c in (mp.Er, mp.Ep, mp.Ez)) ** 0.5
        if abs(e.shape[0] - r_in * res) > abs(e.shape[0] - (z1 - z0) * res):
            e = e.T                                   # stored as [r, z]
        step = max(1, int(np.ceil(max(e.shape) / MAP_MAX_PX)))
        out["map_abs"] = e[::step, ::step]
        out["map_extent_mm"] = np.array([0.0, r_in * lam, z0 * lam, z1 * lam])
    if volume is not None:
        out |= volume_field(sim, mp, volume, d)
    return out


def volume_field(sim, mp, volume, d: dict) -> dict:
    """The DFT Er over the quiet zone's half-plane as [r, z] with its axes in mm: r_i = i/res (as on the
    plane), z from Meep's metadata (right along z)."""
    e = np.asarray(sim.get_dft_array(volume, mp.Er, 0))
    z = np.asarray(sim.get_array_metadata(dft_cell=volume)[2], float)
    if e.shape[1] != len(z):
        e = e.T
    return {"volume_er": e, "volume_r_mm": np.arange(e.shape[0]) / d["res"] * d["lam"],
            "volume_z_mm": (z + d["zc"]) * d["lam"]}


def die_with_parent() -> None:
    """On Linux, have the kernel end this run when the process that started it dies, even by SIGKILL
    (PR_SET_PDEATHSIG); a run whose parent (``ANTENNA_CAD_PARENT_PID``) is already gone stops at once."""
    parent = int(os.environ.get("ANTENNA_CAD_PARENT_PID", os.getppid()))
    try:
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(1, 9)           # PR_SET_PDEATHSIG, SIGKILL
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:
        sys.exit(1)


def main(argv: list[str]) -> int:
    die_with_parent()
    deck_path, out_path = argv
    with open(deck_path, encoding="utf-8") as fh:
        deck = json.load(fh)
    import meep as mp
    mp.verbosity(0)
    result = run(deck)
    result["meep_version"] = np.array(mp.__version__)
    np.savez_compressed(out_path, **result)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
