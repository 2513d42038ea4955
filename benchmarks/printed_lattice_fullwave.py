"""Homogenization error of a real printed lattice: a direct 3-D Meep run of a small printed Luneburg sphere
(classic law, PLA, cubic lattice of the 120 mm recipe's cell, wall and skin; Ø3 λ by default, the
printed-lenses guide gives the cost) with its rods as printed, against its homogenized twin (the unit-cell table's εr_eff of each cell's fill, on a continuous
εr(r), the skin solid), same grid, same feed. Reports the forward directivity (from the aperture plane's
E and H, over the power the feed radiates) and the aperture phase across the lens.

Set-up: unit length λ0; an x-polarized point dipole on the axis just outside the skin at the design focus
(b = R); two mirror planes (x odd, y even) cut the cell to a quarter. The voxel ε is the volume average of
``SUB``³ sub-samples of the geometry (rods or twin), given to Meep as a MaterialGrid on its own pixels
(no further averaging): a rod narrower than a pixel is a partly filled voxel, not lost. Lossless PLA.
The directivity on axis from the aperture plane z = R + ``GAP`` λ: U = k²/(32π²η)·|∫(Ex + η·Hy) dA|²
(the Huygens aperture integral), D = 4πU/P with P the flux out of a box around lens and feed (Meep's
flux is ∫Re(E*×H), twice the mean power: P = flux/2).

    PYTHONPATH=. python benchmarks/printed_lattice_fullwave.py [--diameter-lambda 3] [--resolution 24] [-o out.json]

The driver (this file, the project's Python) computes the voxel ε of both models, writes them to an npz,
runs this same file under the interpreter that has Meep (``--meep in.npz out.npz``) once per model, and
writes benchmarks/results-printed-lattice-fullwave.json.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

C_MM_GHZ = 299.792458
F_GHZ = 12.0
CELL_MM, WALL_MM, GAP_MM_PRINT, SKIN_MM, STEP_MM = 3.6, 0.8, 0.8, 0.8, 0.05   # the 120 mm recipe's lattice
EPS_F = 2.7
SUB = 3                 # sub-samples per voxel edge (volume-averaged ε)
GAP = 0.3               # λ: lens to aperture plane, lens to PML, feed side margin
PML = 0.5               # λ
FEED_OFFSET = 0.05      # λ outside the skin
ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results-printed-lattice-fullwave.json"


# ---------------------------------------------------------------- driver side (project Python)
def models(radius_mm: float, res: int) -> tuple[np.ndarray, np.ndarray, float, dict]:
    """Voxel ε of the lattice and of its homogenized twin on the cube |x|, |y|, |z| ≤ R (px of λ/res)."""
    from antenna_cad.printed.fill import fill_map
    from antenna_cad.printed.lattice import Printable
    from antenna_cad.printed.parts import rounded_widths
    law = lambda r: 2.0 - (np.asarray(r) / radius_mm) ** 2            # classic Luneburg (seed-002 §2.1)
    fmap = fill_map(law, radius_mm, "cubic", EPS_F, Printable("cubic", CELL_MM, WALL_MM, GAP_MM_PRINT))
    lam = C_MM_GHZ / F_GHZ
    px = lam / res
    n = int(math.ceil(radius_mm / px))
    r_in = radius_mm - SKIN_MM
    centers = (np.arange(-n, n) + 0.5) * px                           # voxel centres, mm
    offs = ((np.arange(SUB) + 0.5) / SUB - 0.5) * px
    lat = np.zeros((2 * n,) * 3, np.float32)
    twin = np.zeros_like(lat)
    a = CELL_MM
    for ix, x in enumerate(centers):
        pts = _subpoints(x, centers, offs)                            # (sx, y, sy, z, sz, 3)
        r = np.linalg.norm(pts, axis=-1)
        # cell centres (i, j, k + ½)·a with the cell's rod width; inside a cell a point is solid when two
        # of its three local coordinates are within w/2 (the union of the cell's three rods)
        c = np.stack([np.round(pts[..., 0] / a), np.round(pts[..., 1] / a), np.floor(pts[..., 2] / a) + 0.5], -1) * a
        w = rounded_widths(fmap, np.linalg.norm(c, axis=-1).ravel(), STEP_MM, WALL_MM, GAP_MM_PRINT).reshape(r.shape)
        inside = (np.abs(pts - c) < w[..., None] / 2).sum(-1) >= 2
        solid = np.where(r <= r_in, inside, r <= radius_mm)
        lat[ix] = (1 + (EPS_F - 1) * solid).mean(axis=(0, 2, 4))
        eps_h = np.where(r <= r_in, np.interp(r, fmap.r_mm, fmap.eps_printed), np.where(r <= radius_mm, EPS_F, 1.0))
        twin[ix] = eps_h.mean(axis=(0, 2, 4))
    info = {"cells_in_sphere": int(round(4 / 3 * math.pi * r_in**3 / a**3)), "voxel_mm": px}
    wmin = rounded_widths(fmap, np.array([0.0, r_in]), STEP_MM, WALL_MM, GAP_MM_PRINT)
    info["rod_width_mm"] = [float(wmin.min()), float(wmin.max())]
    info["rod_width_px"] = [float(wmin.min() / px), float(wmin.max() / px)]
    return lat, twin, px, info


def _subpoints(x: float, centers: np.ndarray, offs: np.ndarray) -> np.ndarray:
    """Sub-sample points of the voxel slab at x: shape (SUB, ny, SUB, nz, SUB, 3) as (sx, y, sy, z, sz)."""
    m = len(centers)
    px_ = (x + offs).reshape(SUB, 1, 1, 1, 1)
    py_ = (centers[:, None] + offs[None, :]).reshape(1, m, SUB, 1, 1)
    pz_ = (centers[:, None] + offs[None, :]).reshape(1, 1, 1, m, SUB)
    shape = (SUB, m, SUB, m, SUB)
    return np.stack(np.broadcast_arrays(px_, py_, pz_), -1).reshape(*shape, 3)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--diameter-lambda", type=float, default=3.0)
    ap.add_argument("--resolution", type=int, default=24, help="px per λ0")
    ap.add_argument("--python", default=os.environ.get("ANTENNA_CAD_MEEP_PYTHON", "/usr/bin/python3"))
    ap.add_argument("--only", choices=("lattice", "twin"))
    ap.add_argument("-o", "--output", default=str(RESULTS))
    args = ap.parse_args(argv)
    lam = C_MM_GHZ / F_GHZ
    radius = args.diameter_lambda * lam / 2
    t0 = time.perf_counter()
    lat, twin, px, info = models(radius, args.resolution)
    t_eps = time.perf_counter() - t0
    out = {"diameter_lambda": args.diameter_lambda, "diameter_mm": 2 * radius, "frequency_ghz": F_GHZ,
           "resolution_px_per_lambda": args.resolution, "subsamples": SUB, "eps_seconds": t_eps, **info,
           "mean_eps_lattice": float(lat.mean()), "mean_eps_twin": float(twin.mean()), "runs": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for name, eps in (("twin", twin), ("lattice", lat)):
            if args.only and name != args.only:
                continue
            deck = Path(tmp) / f"{name}.npz"
            res = Path(tmp) / f"{name}-out.npz"
            np.savez(deck, eps=eps, radius_lambda=radius / lam, resolution=args.resolution)
            t = time.perf_counter()
            subprocess.run([args.python, __file__, "--meep", str(deck), str(res)], check=True)
            r = np.load(res)
            out["runs"][name] = {"directivity_dbi": float(r["directivity_dbi"]), "seconds": time.perf_counter() - t,
                                 "voxels": int(r["voxels"]), "steps": int(r["steps"]),
                                 "aperture_samples": r["shape"].tolist(),
                                 "phase_deg_x": r["phase_x"].tolist(), "phase_deg_y": r["phase_y"].tolist(),
                                 "amp_x": r["amp_x"].tolist(), "amp_y": r["amp_y"].tolist(),
                                 "axis_lambda": r["axis"].tolist()}
    if len(out["runs"]) == 2:
        out |= compare(out["runs"]["lattice"], out["runs"]["twin"], radius / lam)
    Path(args.output).write_text(json.dumps(out, indent=1) + "\n")
    brief = {k: v for k, v in out.items() if k != "runs"} | {
        k: {kk: vv for kk, vv in v.items() if not isinstance(vv, list)} for k, v in out["runs"].items()}
    print(json.dumps(brief, indent=1))
    return 0


def compare(a: dict, b: dict, radius_lambda: float) -> dict:
    """Lattice ``a`` against twin ``b``: directivity difference, and over the lens aperture (|ρ| ≤ 0.8 R,
    both cuts) the mean phase difference and the RMS of the difference about that mean."""
    keep = np.abs(np.asarray(a["axis_lambda"])) <= 0.8 * radius_lambda
    phase = {k: np.radians(np.concatenate([np.asarray(run[f"phase_deg_{c}"])[keep] for c in "xy"]))
             for k, run in (("lattice", a), ("twin", b))}
    mean, rms = _spread(phase["lattice"] - phase["twin"])
    return {"gain_error_db": a["directivity_dbi"] - b["directivity_dbi"], "phase_mean_deg": mean, "phase_rms_deg": rms,
            "aperture_phase_rms_lattice_deg": _spread(phase["lattice"])[1],
            "aperture_phase_rms_twin_deg": _spread(phase["twin"])[1]}


def _spread(phase: np.ndarray) -> tuple[float, float]:
    """Circular mean of the phases (deg) and their RMS about it (deg)."""
    z = np.exp(1j * phase)
    mean = np.angle(np.mean(z))
    return float(np.degrees(mean)), float(np.degrees(np.sqrt(np.mean(np.angle(z * np.exp(-1j * mean)) ** 2))))


# ---------------------------------------------------------------- Meep side (Debian's python3-meep)
def meep_run(deck_path: str, out_path: str) -> None:
    import meep as mp
    d = np.load(deck_path)
    eps, R, res = d["eps"], float(d["radius_lambda"]), int(d["resolution"])
    half_xy = R + GAP + PML
    z_lo, z_hi = -R - FEED_OFFSET - GAP - PML, R + 2 * GAP + PML
    cell = mp.Vector3(2 * half_xy, 2 * half_xy, z_hi - z_lo)
    zc = (z_hi + z_lo) / 2
    side = eps.shape[0] / res
    grid = mp.MaterialGrid(mp.Vector3(*eps.shape), mp.air, mp.Medium(epsilon=EPS_F),
                           weights=(eps - 1) / (EPS_F - 1), do_averaging=False)
    geometry = [mp.Block(size=mp.Vector3(side, side, side), center=mp.Vector3(0, 0, -zc), material=grid)]
    src_z = -R - FEED_OFFSET - zc
    sources = [mp.Source(mp.GaussianSource(1.0, fwidth=0.5), component=mp.Ex, center=mp.Vector3(0, 0, src_z))]
    sim = mp.Simulation(cell_size=cell, resolution=res, geometry=geometry, sources=sources,
                        boundary_layers=[mp.PML(PML)], eps_averaging=False,
                        symmetries=[mp.Mirror(mp.X, phase=-1), mp.Mirror(mp.Y, phase=+1)])
    ap_z = R + GAP - zc
    span = 2 * (R + GAP)
    plane = mp.Volume(center=mp.Vector3(0, 0, ap_z), size=mp.Vector3(span, span, 0))
    dft = sim.add_dft_fields([mp.Ex, mp.Hy], 1.0, 0, 1, where=plane)
    box = R + GAP * 0.9
    zb_lo, zb_hi = -R - FEED_OFFSET - GAP * 0.9 - zc, R + GAP * 1.5 - zc
    zm, zs = (zb_lo + zb_hi) / 2, zb_hi - zb_lo
    faces = [mp.FluxRegion(center=mp.Vector3(0, 0, zb_hi), size=mp.Vector3(2 * box, 2 * box, 0), weight=+1),
             mp.FluxRegion(center=mp.Vector3(0, 0, zb_lo), size=mp.Vector3(2 * box, 2 * box, 0), weight=-1),
             mp.FluxRegion(center=mp.Vector3(box, 0, zm), size=mp.Vector3(0, 2 * box, zs), weight=+1),
             mp.FluxRegion(center=mp.Vector3(-box, 0, zm), size=mp.Vector3(0, 2 * box, zs), weight=-1),
             mp.FluxRegion(center=mp.Vector3(0, box, zm), size=mp.Vector3(2 * box, 0, zs), weight=+1),
             mp.FluxRegion(center=mp.Vector3(0, -box, zm), size=mp.Vector3(2 * box, 0, zs), weight=-1)]
    flux = sim.add_flux(1.0, 0, 1, *faces)
    path = (z_hi - z_lo) * math.sqrt(2.0) + 2 * half_xy
    sim.run(until_after_sources=path + 10)
    ex = sim.get_dft_array(dft, mp.Ex, 0)
    hy = sim.get_dft_array(dft, mp.Hy, 0)
    p = mp.get_fluxes(flux)[0]
    da = (span / (ex.shape[0] - 1)) * (span / (ex.shape[1] - 1))
    k = 2 * math.pi
    u = k**2 / (32 * math.pi**2) * abs(np.sum(ex + hy) * da) ** 2
    axis = np.linspace(-span / 2, span / 2, ex.shape[0])
    mid_x, mid_y = ex.shape[0] // 2, ex.shape[1] // 2
    np.savez(out_path, directivity_dbi=10 * math.log10(4 * math.pi * u / (p / 2)), voxels=int(np.prod(
        [int(round(c * res)) for c in (cell.x, cell.y, cell.z)])), steps=int(round(sim.meep_time() * res * 2)),
        phase_x=np.degrees(np.angle(ex[:, mid_y])), phase_y=np.degrees(np.angle(ex[mid_x, :])),
        amp_x=np.abs(ex[:, mid_y]), amp_y=np.abs(ex[mid_x, :]), axis=axis, shape=np.array(ex.shape))


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--meep":
        meep_run(sys.argv[2], sys.argv[3])
        sys.exit(0)
    sys.exit(main())
