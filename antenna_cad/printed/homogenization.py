"""Effective permittivity of a printed lattice: retrieval from a full-wave slab, bounds, Maxwell
Garnett, and the shipped table that maps fill ↔ εr.

Retrieval (normal incidence, time e^{−iωt}; Smith, Schultz, Markoš, Soukoulis, "Determination of
effective permittivity and permeability of metamaterials from reflection and transmission
coefficients", Phys. Rev. B 65, 195104, 2002): a slab of thickness d with reflection r and
transmission t at its faces has impedance z = ±√(((1 + r)² − t²)/((1 − r)² − t²)) (Re z ≥ 0) and
e^{i n k0 d} = t / (1 − r (z − 1)/(z + 1)); the branch of n is the one nearest an estimate. Then
εr = n/z and μr = n·z. A lens law asks for the phase velocity, so the design value is
``eps_index`` = n² (equal to εr where μr = 1, the limit a/λ → 0; both are tabulated).

Bounds and mixing rules for a filament of εf in air at fill f:
- Wiener: 1/((1 − f) + f/εf) ≤ εeff ≤ 1 + f(εf − 1) (layers across / along the field);
- Maxwell Garnett with the lattice's own inclusion shapes (depolarization N): for ``cubic`` a third
  of the solid in rods along the field (N = 0) and two thirds across it (N = ½); for ``gyroid`` the
  sheet seen as plates of every orientation, two thirds along (N = 0) and one third across (N = 1).
  Each share adds f_i(εf − 1)/(1 + (1 − f)N(εf − 1)); exact to first order in f.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np

TABLE = "lattice_eps.csv"


def retrieve(r: complex, t: complex, k0d: float, n_guess: float) -> tuple[complex, complex]:
    """(n, z) of a homogeneous slab from its face-referenced r and t (Smith et al. 2002)."""
    z = np.sqrt(((1 + r) ** 2 - t**2) / ((1 - r) ** 2 - t**2))
    if z.real < 0:
        z = -z
    phase = t / (1 - r * (z - 1) / (z + 1))
    n0 = -1j * np.log(phase) / k0d
    branch = np.round((n_guess - n0.real) * k0d / (2 * np.pi))
    return n0 + 2 * np.pi * branch / k0d, z


def slab_coefficients(fields: dict, k0: float, cells: int, gap: float) -> tuple[complex, complex]:
    """Face-referenced (r, t) from the unit-cell runner's period-averaged fields (lengths in cells):
    r = (E_slab − E_empty)/E_empty in front, carried back over 2 gaps; t = E_slab/E_empty behind,
    with the vacuum path over the slab put back."""
    e = {k: complex(*v) for k, v in fields.items() if k != "gap"}
    r = (e["slab_front"] - e["empty_front"]) / e["empty_front"] * np.exp(-2j * k0 * gap)
    t = e["slab_back"] / e["empty_back"] * np.exp(1j * k0 * cells)
    return r, t


def wiener_bounds(fill, eps_f: float) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) Wiener bounds of εeff at ``fill``."""
    f = np.asarray(fill, float)
    return 1 / ((1 - f) + f / eps_f), 1 + f * (eps_f - 1)


SHAPES = {"cubic": ((1 / 3, 0.0), (2 / 3, 0.5)), "gyroid": ((2 / 3, 0.0), (1 / 3, 1.0))}


def maxwell_garnett(lattice: str, fill, eps_f: float) -> np.ndarray:
    """Maxwell Garnett εeff with the lattice's inclusion shapes (module docstring)."""
    f = np.asarray(fill, float)
    d = eps_f - 1
    return 1 + sum(share * f * d / (1 + (1 - f) * depol * d) for share, depol in SHAPES[lattice])


@dataclass(frozen=True)
class Homogenized:
    """εeff(fill) of one lattice in one filament permittivity, from the shipped table."""
    lattice: str
    eps_f: float
    fill: np.ndarray
    eps: np.ndarray             # n², the index the lens law asks for
    anisotropy: float           # largest |ε_x − ε_y| over the table's fills

    def eps_at(self, fill) -> np.ndarray:
        return np.interp(fill, self.fill, self.eps)

    def fill_for(self, eps) -> np.ndarray:
        """The fill whose εeff is ``eps`` (monotone interpolation; outside the table: its ends)."""
        return np.interp(eps, self.eps, self.fill)


@lru_cache(maxsize=None)
def table_rows() -> tuple[dict, ...]:
    """The shipped unit-cell table (``data/lattice_eps.csv``), rows as dicts of floats and strings."""
    text = resources.files("antenna_cad.printed").joinpath("data", TABLE).read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line and not line.startswith("#")]
    rows = []
    for row in csv.DictReader(lines):
        rows.append({k: (v if k in ("lattice", "polarization") else float(v)) for k, v in row.items()})
    return tuple(rows)


def homogenized(lattice: str, eps_f: float) -> Homogenized:
    """εeff(fill) for a filament of permittivity ``eps_f``: the table's rows of that lattice, scaled
    between the two tabulated filament permittivities that bracket ``eps_f`` by their fraction of
    the Wiener span (the Wiener-normalized εeff varies slowly with εf; the table says where it was
    computed)."""
    rows = [r for r in table_rows() if r["lattice"] == lattice and r["polarization"] == "x"]
    if not rows:
        raise KeyError(f"no homogenization rows for lattice {lattice!r}")
    by_eps = sorted({r["eps_f"] for r in rows})
    lo = max([e for e in by_eps if e <= eps_f], default=by_eps[0])
    hi = min([e for e in by_eps if e >= eps_f], default=by_eps[-1])
    curves = []
    for e in (lo, hi):
        sel = sorted((r for r in rows if r["eps_f"] == e), key=lambda r: r["fill"])
        f = np.array([0.0] + [r["fill"] for r in sel] + [1.0])
        eps = np.array([1.0] + [r["eps_index"] for r in sel] + [e])
        low, up = wiener_bounds(f, e)
        span = np.where(up > low, up - low, 1.0)
        curves.append((f, (eps - low) / span))
    fill = np.unique(np.concatenate([c[0] for c in curves]))
    w = 0.0 if hi == lo else (eps_f - lo) / (hi - lo)
    u = (1 - w) * np.interp(fill, *curves[0]) + w * np.interp(fill, *curves[1])
    low, up = wiener_bounds(fill, eps_f)
    aniso = [abs(r["eps_index"] - s["eps_index"]) for r in table_rows() for s in table_rows()
             if r["lattice"] == s["lattice"] == lattice and r["polarization"] == "x" and s["polarization"] == "y"
             and r["fill"] == s["fill"] and r["eps_f"] == s["eps_f"]]
    return Homogenized(lattice, eps_f, fill, low + u * (up - low), max(aniso, default=float("nan")))
