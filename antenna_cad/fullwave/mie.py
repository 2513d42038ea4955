"""Exact fields of a multilayer sphere in a plane wave (Mie series, PyPI ``scattnlay``): the reference
for full-wave runs of Luneburg spheres (seed-002 §2.4), and the sphere as the runner's parts.

Incident wave x̂·e^{ikz} (time e^{−iωt}, as Meep's and the runner's), sphere centred at the origin; shell
i spans radii_mm[i−1] ≤ r ≤ radii_mm[i] with permittivity eps[i] (lossless or complex)."""

from __future__ import annotations

import os
import sys
from contextlib import contextmanager

import numpy as np

SEMICIRCLE_POINTS = 181


@contextmanager
def quiet_stdout():
    """scattnlay's C++ core prints convergence notes on file descriptor 1: send them to /dev/null
    (library code never prints)."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "wb") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def mie_field(radii_mm, eps, wavelength_mm: float, points_mm: np.ndarray) -> np.ndarray:
    """Total E (N, 3) at ``points_mm`` (N, 3: x, y, z) around/inside the sphere, incident amplitude 1."""
    from scattnlay import fieldnlay
    k = 2 * np.pi / wavelength_mm
    p = np.asarray(points_mm, float) * k
    with quiet_stdout():
        _, e, _ = fieldnlay(k * np.asarray(radii_mm, float), np.sqrt(np.asarray(eps, complex)), p[:, 0], p[:, 1], p[:, 2])
    return np.asarray(e)


def shell_parts(radii_mm, eps, center_z_mm: float = 0.0) -> list[dict]:
    """The sphere's shells as (r, z) polygons for the runner: a half disc, then half annuli."""
    a = np.linspace(-np.pi / 2, np.pi / 2, SEMICIRCLE_POINTS)
    parts, inner = [], 0.0
    for i, (outer, e) in enumerate(zip(radii_mm, eps)):
        arc = np.column_stack([outer * np.cos(a), center_z_mm + outer * np.sin(a)])
        back = np.column_stack([inner * np.cos(a[::-1]), center_z_mm + inner * np.sin(a[::-1])])
        poly = np.concatenate([arc, back]) if inner > 0 else arc
        parts.append({"label": f"shell-{i + 1:02d}", "eps_r": float(np.real(e)), "polygon": np.round(poly, 4).tolist()})
        inner = outer
    return parts
