"""The report's interactive 3-D view: the assembly's glb and the viewer, inline in report.html.

The viewer is three.js (MIT, vendored at a pinned version in ``viewer/three.min.js``: the renderer,
OrbitControls and GLTFLoader bundled into one minified script, ``viewer/README.md`` says how) and
``viewer/viewer.js``. Everything is inline — the scripts as text, the glb as base64 — so the page
stays one file that opens offline; the static pictures stay beside it for print and for browsers
without WebGL.
"""

from __future__ import annotations

import base64
import html
import json
from importlib import resources

from antenna_cad.export.gltf import ViewPart

THREE_VERSION = "0.187.0"     # viewer/three.min.js (npm three, pinned; viewer/README.md)

VIEWER_CSS = """
#v3d{margin:.6em 0}#v3d canvas{width:100%;height:560px;display:block;border:1px solid #ddd;cursor:grab;
background:#fff}.v3d-bar{display:flex;flex-wrap:wrap;gap:.4em 1.4em;align-items:center;font-size:13px;
margin:.4em 0}.v3d-groups label{white-space:nowrap;margin-right:1em}.v3d-msg{color:#a33}
@media print{.v3d-bar{display:none}}
"""


def _asset(name: str) -> str:
    return (resources.files("antenna_cad.export") / "viewer" / name).read_text(encoding="utf-8")


def viewer_html(glb: bytes, parts: list[ViewPart]) -> str:
    """The 3-D view's figure: canvas, group toggles, section controls, the data and the scripts."""
    groups: dict[str, dict] = {}
    for p in parts:
        g = groups.setdefault(p.group, {"name": p.group, "count": 0, "colours": [], "shown": False})
        g["count"] += p.count
        g["shown"] |= p.fabricated
        if p.colour not in g["colours"] and len(g["colours"]) < 6:
            g["colours"].append(p.colour)
    info = json.dumps({"groups": list(groups.values()), "parts": {p.label: p.group for p in parts}},
                      separators=(",", ":")).replace("</", "<\\/")
    controls = ('<div class="v3d-bar"><span class="v3d-groups"><b>Parts:</b> </span></div>'
                '<div class="v3d-bar"><b>Section plane:</b><select class="v3d-axis" aria-label="section axis">'
                '<option value="">off</option><option value="x">across x</option><option value="y">across y</option>'
                '<option value="z">across z (the axis)</option></select>'
                '<input class="v3d-cut" type="range" min="0" max="1000" value="500" aria-label="section position">'
                '<span class="v3d-cut-mm" hidden></span><label><input class="v3d-flip" type="checkbox"> keep the other side'
                '</label><button class="v3d-reset" type="button">reset view</button></div>')
    count = sum(p.count for p in parts)
    model = ("the same model is the build's .glb" if count == len(parts) else
             "shown merged per group and material; the build's .glb has one node per part")
    return (f'<figure class="viewer" id="v3d"><canvas aria-label="3-D view of the assembly"></canvas>'
            f'<p class="v3d-msg"></p>{controls}<figcaption>Drag to orbit, wheel to zoom, right-drag to pan. '
            f'{count} parts in {len(groups)} groups, as in the STEP; {model}.</figcaption></figure>'
            f'<script type="text/plain" id="v3d-glb">{base64.b64encode(glb).decode("ascii")}</script>'
            f'<script type="application/json" id="v3d-parts">{info}</script>'
            f"<script>{_asset('three.min.js')}</script><script>{_asset('viewer.js')}</script>")


def licence_note() -> str:
    """One line for the page's foot: the embedded viewer, its version and its licence."""
    holder = next(line for line in _asset("LICENSE-three.txt").splitlines() if line.startswith("Copyright"))
    return f"3-D view: three.js {THREE_VERSION}, {html.escape(holder)}, MIT licence."
