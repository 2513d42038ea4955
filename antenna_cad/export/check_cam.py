"""``make-lens check``: every G-code file of a build parsed by an independent parser (PyPI
``gcodeparser``) and held against what the manifest's ``cam[]`` promises.

Hot wire: the towers' positions on every cutting move (G1) give the wire; its points on the two
foam faces (``faces[].wire_mm`` along it, ``center_mm`` the lens axis) rebuild the cut surface. The
program's first two and last two cutting moves are the way in and out (down through waste to the
lead-in, then to the contour); the moves between them are the contour. A taper-cut lens piece must
lie kerf/2 outside the cone through the lens profile at its two faces — the profile synthesized
again from the manifest's spec — within ``CAM_TOL_MM``, at every vertex and chord midpoint (a
board strip's butt-joint planes are vertical rulings inside it); every other piece is a straight cut
(XY = UV). A Luneburg ring's edge is held to its sphere (``sphere_mm``), an inner edge kerf/2
inside it. Every move of either tower stays inside the machine's travel.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from antenna_cad.export.check import Finding

CAM_TOL_MM = 0.05
INCH_MM = 25.4


def parse_moves(text: str, axes: str) -> tuple[list[np.ndarray], list[bool]]:
    """Absolute positions (mm) of ``axes`` after every G0/G1 line, and whether the move was G1."""
    from gcodeparser import parse_gcode_lines
    scale, pos, out, cutting = 1.0, dict.fromkeys(axes, 0.0), [], []
    for line in parse_gcode_lines(text):
        letter, number = line.command
        if (letter, number) == ("G", 20):
            scale = INCH_MM
        elif (letter, number) == ("G", 21):
            scale = 1.0
        elif (letter, number) == ("G", 91):
            raise ValueError("relative moves (G91) are not expected")
        elif letter == "G" and number in (0, 1):
            for a in axes:
                if a in line.params:
                    pos[a] = float(line.params[a]) * scale
            out.append(np.array([pos[a] for a in axes]))
            cutting.append(number == 1)
    return out, cutting


def drill_cycles(text: str) -> list[tuple[float, float, float]]:
    """(X, Y, Z) of every G81 drilling cycle (mm)."""
    from gcodeparser import parse_gcode_lines
    scale, out = 1.0, []
    for line in parse_gcode_lines(text):
        if line.command in (("G", 20), ("G", 21)):
            scale = INCH_MM if line.command[1] == 20 else 1.0
        elif line.command == ("G", 81):
            out.append(tuple(float(line.params[a]) * scale for a in "XYZ"))
    return out


def _faces(entry: dict, moves: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Wire points on the two foam faces, lens frame (mm), of each move."""
    m = np.array(moves)
    xy, uv = m[:, :2], m[:, 2:4]
    span = entry["tower_span_mm"]
    c = np.array(entry["center_mm"])
    w0, w1 = (f["wire_mm"] for f in entry["faces"])
    return xy + (uv - xy) * w0 / span - c, xy + (uv - xy) * w1 / span - c


def _profile(manifest: dict):
    """r(z) of the lens at the faces' z from the manifest's spec, synthesized again (the kind's
    ``cone_radius``; None: the kind has no radius law)."""
    from antenna_cad.registry import adapter
    from antenna_cad.spec import parse_spec
    spec = parse_spec(manifest["spec"])
    kind = adapter(spec.kind)
    return kind.cone_radius(spec, kind.synthesize(spec)) if hasattr(kind, "cone_radius") else None


def cone_error_mm(entry: dict, front: np.ndarray, back: np.ndarray, radius_at) -> float:
    """Largest |distance − kerf/2| between the wire and the cone through r(z) at the two faces (each
    face's kerf, ``faces[].kerf_mm``), in the meridional plane, over the rulings on the cone and the
    midpoints of chords between them; the distance is taken toward the axis for a ring's inner edge
    (``edge: inner``)."""
    side = -1.0 if entry.get("edge") == "inner" else 1.0
    z0, z1 = (f["z_mm"] for f in entry["faces"])
    a, b = np.array([radius_at(z0), z0]), np.array([radius_at(z1), z1])
    u = (b - a) / np.linalg.norm(b - a)
    normal = np.array([u[1], -u[0]])                     # outward (+r) side of the cone line
    vertical = np.all(np.abs(front - back) < 1e-6, axis=1) & (np.abs(a[0] - b[0]) > 1e-6)

    kerfs = [f.get("kerf_mm", entry["kerf_mm"]) for f in entry["faces"]]     # each face's own kerf

    def dist(p0, p1):
        rho = np.stack([np.hypot(*p0.T), np.hypot(*p1.T)])
        return np.abs(np.stack([(np.stack([rho[i], np.full(len(p0), z)], -1) - a) @ normal - side * kerfs[i] / 2
                                for i, z in enumerate((z0, z1))])).max(axis=0)
    on = ~vertical
    err = dist(front[on], back[on])
    pair = on[:-1] & on[1:]
    mid = dist(((front[:-1] + front[1:]) / 2)[pair], ((back[:-1] + back[1:]) / 2)[pair])
    return float(max(err.max(initial=0.0), mid.max(initial=0.0)))


def hotwire_findings(folder: Path, manifest: dict, entry: dict, radius_at, travel) -> list[Finding]:
    name = entry["file"]
    moves, cutting = parse_moves((folder / name).read_text(encoding="utf-8"), entry["axes"])
    reach = np.array(moves)
    inside = bool(np.all(reach >= -1e-6) and np.all(reach[:, :2] <= np.array(travel) + 1e-6)
                  and np.all(reach[:, 2:4] <= np.array(travel) + 1e-6))
    out = [Finding(name, "cam_travel", inside, f"every move inside the {travel[0]:g} × {travel[1]:g} mm travel"
                   if inside else "a move leaves the machine's travel")]
    if "sphere_mm" in entry:                                      # a Luneburg ring's edge: its sphere
        R = float(entry["sphere_mm"])
        radius_at = lambda z: float(np.sqrt(max(R * R - z * z, 0.0)))   # noqa: E731
    cut = [p for p, g in zip(moves, cutting) if g][1:-2]         # the contour (see the module docstring)
    front, back = _faces(entry, cut)
    cone = bool(np.any(np.abs(front - back) > 1e-6))
    if not cone:
        out.append(Finding(name, "cam_surface", True, f"straight cut (XY = UV), {len(cut)} moves"))
    elif radius_at is None:
        out.append(Finding(name, "cam_surface", False, "a ruled cut, but the lens has no radius law to hold it to"))
    else:
        err = cone_error_mm(entry, front, back, radius_at)
        out.append(Finding(name, "cam_surface", err <= CAM_TOL_MM,
                           f"wire vs the lens profile's cone + kerf/2: {err:.4f} mm (≤ {CAM_TOL_MM} mm)"))
    return out


def check_cam(folder: Path, manifest: dict) -> list[Finding]:
    """Findings of every file in the manifest's ``cam[]``."""
    entries = manifest.get("cam", [])
    if not entries:
        return []
    findings = []
    if any("faces" in e for e in entries):
        from antenna_cad.cam.plan import machine_of
        from antenna_cad.spec.cam import CamSpec
        travel = machine_of(CamSpec(**manifest["spec"]["fabrication"]["cam"])).travel_mm
        radius_at = _profile(manifest)
    for entry in entries:
        if "faces" in entry:
            findings += hotwire_findings(folder, manifest, entry, radius_at, travel)
        elif not entry["file"].startswith("cam/board-"):
            findings.append(_drill_finding(folder, entry))
    boards = [e for e in entries if e["file"].startswith("cam/board-")]
    if boards:
        from antenna_cad.cam.machines import BUILT_IN
        from antenna_cad.export.check_router import board_parts, router_findings
        parts, tool_mm = board_parts(manifest)
        findings += router_findings(folder, boards, parts, tool_mm, BUILT_IN["router-3axis"].travel_mm)
    return findings


def _drill_finding(folder: Path, entry: dict) -> Finding:
    """A drilling file: its cycles go down."""
    text = (folder / entry["file"]).read_text(encoding="utf-8")
    cycles = drill_cycles(text)
    ok = len(cycles) > 0 and all(z < 0 for _, _, z in cycles)
    return Finding(entry["file"], "cam_router", ok, f"{len(cycles)} drilling cycles parsed"
                   + ("" if ok else ": none, or a cycle that does not go down"))
