"""Drawing for the report: verification plots as inline SVG, pictures of the assembly as PNG.

matplotlib (Agg) only (DESIGN.md "Libraries"). Output is reproducible: fixed SVG id salt, no dates
or software stamps, glyphs as paths (the SVG needs no fonts), stable depth sorting.
"""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import trimesh  # noqa: E402
from matplotlib.collections import TriMesh  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

from antenna_cad.verification import Plot  # noqa: E402

MAX_LEGEND = 12        # more curves than this: coloured in order, only the first and last named
STYLE = {"svg.hashsalt": "antenna_cad", "svg.fonttype": "path", "font.size": 9, "axes.grid": True,
         "grid.alpha": 0.3, "figure.dpi": 100}


def draw_plot(ax, plot: Plot) -> None:
    """Draw one verification plot onto matplotlib axes (for the SVG of the page and the PDF)."""
    if plot.image is not None:          # a map over (r, z): z along x, r along y
        data, (r0, r1, z0, z1) = plot.image
        im = ax.imshow(np.asarray(data), extent=(z0, z1, r0, r1), origin="lower", aspect="equal", cmap="viridis")
        ax.figure.colorbar(im, ax=ax, shrink=0.8, label="dB")
    many = len(plot.series) > MAX_LEGEND        # a family (planes, shells): coloured in order, ends labelled
    colours = plt.get_cmap("viridis")(np.linspace(0, 0.9, len(plot.series))) if many else [None] * len(plot.series)
    for i, (s, colour) in enumerate(zip(plot.series, colours)):
        x, y = np.asarray(s.x, float), np.asarray(s.y, float)
        label = s.label if not many or i in (0, len(plot.series) - 1) else "_nolegend_"
        if s.style == "fill":
            ax.fill_between(x, y, alpha=0.35, label=label, linewidth=0, color=colour)
        elif s.style == "points":
            ax.plot(x, y, ".", markersize=3, label=label, color=colour)
        elif s.style == "steps":
            ax.step(x, y, where="post", label=label, linewidth=1.2, color=colour)
        else:
            ax.plot(x, y, "--" if s.style == "dashed" else "-", label=label, linewidth=1.2, color=colour)
    for label, value in plot.hlines:
        ax.axhline(value, color="0.3", linestyle=":", linewidth=1.0, label=label)
    if plot.equal_aspect:
        ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(plot.title)
    ax.set_xlabel(plot.x_label)
    ax.set_ylabel(plot.y_label)
    if any(s.label for s in plot.series) or plot.hlines:
        title = f"{len(plot.series)} curves, dark to light in order" if many else None
        ax.legend(loc="best", fontsize=8, title=title, title_fontsize=8)


def plot_svg(plot: Plot) -> str:
    """One verification plot as an inline SVG element (text)."""
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(7.0, 4.2) if not plot.equal_aspect else (7.0, 5.0))
        draw_plot(ax, plot)
        return figure_svg(fig)


def figure_svg(fig) -> str:
    """A finished matplotlib figure as an inline SVG element (laid out tight, then closed)."""
    fig.tight_layout()
    buf = io.StringIO()
    fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    text = buf.getvalue()
    return text[text.index("<svg"):]       # drop the XML prolog and doctype: inline in HTML


# ---- pictures of the assembly -------------------------------------------------------------

VIEWS = (  # title, view direction (from the eye into the scene), up vector; frame of DESIGN.md
    ("front (from +Z, looking along −Z)", (0.0, 0.0, -1.0), (0.0, 1.0, 0.0)),
    ("side (from +X)", (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    ("top (from +Y)", (0.0, -1.0, 0.0), (0.0, 0.0, -1.0)),
    ("isometric", (-1.0, -1.0, -1.0), (0.0, 1.0, 0.0)),
)
LIGHT = np.array([-0.4, 0.8, -0.45])


def assembly_png(meshes: list[tuple[trimesh.Trimesh, str]]) -> bytes:
    """Four shaded orthographic views (front, side, top, isometric) of coloured meshes, one PNG.

    Painter's algorithm in one collection per view: parts far to near by their centres, inside a
    part the back faces culled and the rest sorted far to near; Lambert shading. The triangles go to
    Agg in one call (a TriMesh of flat-coloured triangles, drawn in order), not as one path each
    (a third faster on the Ka arrays' 94,000 triangles)."""
    light = LIGHT / np.linalg.norm(LIGHT)
    triangles = np.concatenate([m.triangles for m, _ in meshes])
    normals = np.concatenate([m.face_normals for m, _ in meshes])
    base = np.concatenate([np.tile(matplotlib.colors.to_rgb(c), (len(m.faces), 1)) for m, c in meshes])
    part = np.repeat(np.arange(len(meshes)), [len(m.faces) for m, _ in meshes])
    part_centres = np.array([m.bounds.mean(axis=0) for m, _ in meshes])
    centres = triangles.mean(axis=1)
    with plt.rc_context(STYLE | {"axes.grid": False}):
        fig, axes = plt.subplots(2, 2, figsize=(10, 8))
        for ax, (title, view, up) in zip(axes.flat, VIEWS):
            d = np.asarray(view, float) / np.linalg.norm(view)
            right = np.cross(d, up)
            right /= np.linalg.norm(right)
            screen = np.stack([right, np.cross(right, d)], axis=-1)
            front = np.flatnonzero(normals @ d < 0)                                 # facing the eye
            front = front[np.lexsort((-(centres[front] @ d), -(part_centres[part[front]] @ d)))]  # far first
            shade = 0.45 + 0.55 * np.abs(normals[front] @ light)
            rgb = np.clip(shade[:, None] * base[front], 0, 1)
            flat = (triangles[front] @ screen).reshape(-1, 2)
            soup = TriMesh(Triangulation(flat[:, 0], flat[:, 1], np.arange(len(flat)).reshape(-1, 3)))
            soup.set_facecolor(np.repeat(np.column_stack([rgb, np.ones(len(rgb))]), 3, axis=0))
            ax.add_collection(soup, autolim=False)
            low, high = flat.min(axis=0), flat.max(axis=0)
            pad = 0.02 * (high - low).max()
            ax.set_xlim(low[0] - pad, high[0] + pad)
            ax.set_ylim(low[1] - pad, high[1] + pad)
            ax.set_aspect("equal")
            ax.set_title(title)
            ax.set_xticks([])
            ax.set_yticks([])
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", metadata={"Software": None})
        plt.close(fig)
    return buf.getvalue()
