"""Meep runner for one lattice slab: a plane wave through N unit cells of a printed lattice, JSON in,
JSON out (run by Debian's ``python3-meep`` interpreter, like :mod:`antenna_cad.fullwave.runner`).

The cell is one lattice period a (the unit length) across, periodic in x and y (k = 0, normal
incidence), with PML along z. A planar ``Ex`` (or ``Ey``) current sheet launches the wave; the DFT
field at f = a/λ is averaged over a plane one period in front of the slab and one behind it — the
average over a period is the zeroth Floquet order, the wave a homogenized slab would carry (the
higher orders decay as exp(−2π z/a) and are gone there). Two runs, the empty cell and the slab, give
the slab's reflection and transmission; :mod:`antenna_cad.printed.homogenization` retrieves n, z, εr
and μr from them.

Lattices (solid = filament, the rest air), one cell [−½, ½]² × [z_j, z_j + 1]:
- ``cubic``: three orthogonal square rods of width w through the cell centre (the FDM rectilinear
  grid stacked in z), built from Meep blocks, so Meep's anisotropic subpixel smoothing applies;
- ``gyroid``: the sheet gyroid |sin X cos Y + sin Y cos Z + sin Z cos X| ≤ t (X = 2πx …), the infill
  slicers print, rasterized on a ``MaterialGrid`` with 4³ sub-samples per pixel (ε averaged).

Imports only numpy and meep.
"""

from __future__ import annotations

import json
import sys

import numpy as np

SUBSAMPLES = 4
PML_CELLS = 3          # PML thickness along z, in lattice periods (≥ 0.45 λ at a/λ ≤ 0.15, normal incidence)
GAP_CELLS = 1          # source → reference plane → slab, in periods


def gyroid(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """The gyroid's level-set function, period 1 in each coordinate."""
    X, Y, Z = 2 * np.pi * x, 2 * np.pi * y, 2 * np.pi * z
    return np.sin(X) * np.cos(Y) + np.sin(Y) * np.cos(Z) + np.sin(Z) * np.cos(X)


def _geometry(mp, deck: dict, z0: float, res: int):
    """The slab's Meep geometry: blocks for ``cubic``, a MaterialGrid for ``gyroid``."""
    n, eps = deck["cells"], deck["eps_r"]
    solid = mp.Medium(epsilon=eps)
    if deck["lattice"] == "cubic":
        w = deck["parameter"]
        rods = [mp.Block(size=mp.Vector3(w, w, n), center=mp.Vector3(0, 0, z0 + n / 2), material=solid)]
        for j in range(n):
            c = mp.Vector3(0, 0, z0 + 0.5 + j)
            rods += [mp.Block(size=mp.Vector3(mp.inf, w, w), center=c, material=solid),
                     mp.Block(size=mp.Vector3(w, mp.inf, w), center=c, material=solid)]
        return rods
    t = deck["parameter"]
    s = (np.arange(SUBSAMPLES) + 0.5) / SUBSAMPLES / res
    xy = (np.arange(res)[:, None] / res + s).ravel() - 0.5
    zz = (np.arange(res * n)[:, None] / res + s).ravel()
    X, Y, Z = np.meshgrid(xy, xy, zz, indexing="ij")
    inside = (np.abs(gyroid(X, Y, Z)) <= t).astype(float)
    w = inside.reshape(res, SUBSAMPLES, res, SUBSAMPLES, res * n, SUBSAMPLES).mean(axis=(1, 3, 5))
    grid = mp.MaterialGrid(mp.Vector3(res, res, res * n), mp.air, solid, weights=w, do_averaging=False)
    return [mp.Block(size=mp.Vector3(1, 1, n), center=mp.Vector3(0, 0, z0 + n / 2), material=grid)]


def run(deck: dict) -> dict:
    """Reference (empty) and slab runs; the period-averaged DFT field in front of and behind the slab."""
    import meep as mp
    mp.verbosity(0)
    f, res, n = deck["a_over_lambda"], deck["resolution"], deck["cells"]
    component = {"x": mp.Ex, "y": mp.Ey}[deck["polarization"]]
    sz = 2 * PML_CELLS + 2 * GAP_CELLS + n + 2
    z0 = -n / 2
    za, zb = z0 - GAP_CELLS, z0 + n + GAP_CELLS
    source = mp.Source(mp.GaussianSource(f, fwidth=0.4 * f), component=component,
                       center=mp.Vector3(0, 0, za - 1), size=mp.Vector3(1, 1, 0))
    out = {}
    for name, geometry in (("empty", []), ("slab", None)):
        sim = mp.Simulation(cell_size=mp.Vector3(1, 1, sz), resolution=res, sources=[source],
                            geometry=_geometry(mp, deck, z0, res) if geometry is None else geometry,
                            boundary_layers=[mp.PML(PML_CELLS, direction=mp.Z)], k_point=mp.Vector3())
        planes = [sim.add_dft_fields([component], f, 0, 1, center=mp.Vector3(0, 0, z), size=mp.Vector3(1, 1, 0))
                  for z in (za, zb)]
        sim.run(until_after_sources=mp.stop_when_fields_decayed(20, component, mp.Vector3(0, 0, zb), 1e-9))
        for plane, side in zip(planes, ("front", "back")):
            e = complex(np.mean(sim.get_dft_array(plane, component, 0)))
            out[f"{name}_{side}"] = [e.real, e.imag]
        sim.reset_meep()
    out["gap"] = GAP_CELLS
    return out


def main(argv: list[str]) -> int:
    deck = json.loads(open(argv[1], encoding="utf-8").read())
    result = run(deck)
    with open(argv[2], "w", encoding="utf-8") as fh:
        json.dump(result, fh, sort_keys=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
