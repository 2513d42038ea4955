"""Pieces shared by the self-contained HTML pages (report.html, the sweep's index.html): the style
sheet and tables of figures (numbers right-aligned, 6 significant digits)."""

from __future__ import annotations

import html

CSS = """
body{font:14px/1.45 system-ui,sans-serif;margin:0 auto;max-width:1100px;padding:0 1.2em 3em;color:#222}
h1{margin:.6em 0 .1em}h2{border-bottom:2px solid #ddd;padding-bottom:.15em;margin-top:1.8em}
table{border-collapse:collapse;margin:.6em 0;font-size:13px}td,th{border:1px solid #ccc;padding:2px 7px;
text-align:left;vertical-align:top}th{background:#f2f2f2}td.num{text-align:right;font-variant-numeric:tabular-nums}
.pass{background:#d9f2d9}.warn{background:#fff1c2}.fail{background:#f8d0d0}
.badge{display:inline-block;padding:1px 10px;border-radius:9px;font-weight:600}
figure{margin:1em 0;page-break-inside:avoid}figure svg,figure img{max-width:100%;height:auto}
figcaption{font-size:12px;color:#555}pre{background:#f7f7f7;padding:.7em;overflow:auto;font-size:12px}
nav a{margin-right:1em}.scroll{max-height:32em;overflow:auto}
@media print{nav{display:none}.scroll{max-height:none}}
"""


def cell(value) -> str:
    if value is None:
        return "<td>—</td>"
    if isinstance(value, bool):
        return f"<td>{'yes' if value else 'no'}</td>"
    if isinstance(value, (int, float)):
        return f'<td class="num">{value:.6g}</td>'
    return f"<td>{html.escape(str(value))}</td>"


def table(columns, rows, css_id: str = "") -> str:
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in columns)
    body = "".join("<tr>" + "".join(cell(v) for v in row) + "</tr>" for row in rows)
    ident = f' id="{css_id}"' if css_id else ""
    return f'<table{ident}><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def page(title: str, heading: str, byline: str, sections, extra_css: str = "") -> str:
    """A self-contained HTML page: ``heading`` and ``byline`` (HTML) above a navigation bar and one
    ``<section>`` per (id, title, HTML content) of ``sections``; no scripts, no network."""
    nav = "".join(f'<a href="#{sid}">{name}</a>' for sid, name, _ in sections)
    body = "".join(f'<section id="{sid}"><h2>{name}</h2>{content}</section>' for sid, name, content in sections)
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width,initial-scale=1">'
            f"<title>{html.escape(title)}</title><style>{CSS}{extra_css}</style></head><body>"
            f"<h1>{html.escape(heading)}</h1><p>{byline}</p><nav>{nav}</nav>{body}</body></html>\n")
