"""One self-contained HTML page about a kit: design table, bill of parts with pictures, the
stacking, the trace, the check's findings and build plates. Images are embedded (data: URIs), so
the page opens offline, from anywhere."""

from __future__ import annotations

import numpy as np

import base64
import html
import math

__all__ = ["data_uri", "table", "page", "figure_png"]

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:2em auto;max-width:1200px;
color:#222;line-height:1.4;padding:0 1em}
h1{margin-bottom:.2em}h2{border-bottom:2px solid #eee;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0;font-size:.92em}
th,td{border:1px solid #ddd;padding:.25em .6em;text-align:right;vertical-align:middle}
th{background:#f5f5f5}td.l,th.l{text-align:left}
.ok{color:#1a7f37;font-weight:600}.fail{color:#cf222e;font-weight:600}.warn{color:#9a6700}
.grid{display:flex;flex-wrap:wrap;gap:1em}.grid figure{margin:0}figcaption{font-size:.85em;color:#555}
img{max-width:100%}.parts img{width:150px}.steps li{margin-bottom:1em}.steps .grid img{width:120px}
"""


def data_uri(data: bytes, mime: str) -> str:
    return f"data:{mime};base64,{base64.b64encode(data).decode()}"


def transmission_figure(title: str, angle_rad, te_mm, backlash_mm, xlabel: str, ylabel: str,
                        markers: bool = True) -> bytes:
    """PNG of a gear pair's transmission error (the driven flank) and backlash, µm, against an angle
    (rad, drawn in °): the figure `trace` writes as transmission.png (``markers``: one per phase)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    deg = np.degrees(angle_rad)
    style = (("-o", "-s"), {"ms": 3}) if markers else (("-", "-"), {})
    ax.plot(deg, 1000 * te_mm, style[0][0], **style[1], label="transmission error (driven flank), µm")
    ax.plot(deg, 1000 * backlash_mm, style[0][1], **style[1], label="backlash, µm")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return figure_png(fig, 110)


def figure_png(fig, dpi: int = 110, bbox_inches: str | None = None) -> bytes:
    """PNG bytes of a matplotlib figure, which is closed afterwards (``bbox_inches="tight"``: cropped
    to what is drawn)."""
    import io

    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches=bbox_inches)
    plt.close(fig)
    return buf.getvalue()


def img(data: bytes, alt: str, mime: str = "image/png", width: int | None = None) -> str:
    w = f' width="{width}"' if width else ""
    return f'<img src="{data_uri(data, mime)}" alt="{html.escape(alt)}"{w}>'


def _cell(v) -> str:
    if isinstance(v, float):
        return f"{v:.4g}" if abs(v) < 1e4 else f"{v:.0f}"
    return str(v)


def table(header: list[str], rows: list[list], left: int = 1, raw: set[int] = frozenset()) -> str:
    """An HTML table; the first ``left`` columns are left-aligned, columns in ``raw`` are HTML."""
    th = "".join(f'<th class="{"l" if i < left else ""}">{html.escape(h)}</th>' for i, h in enumerate(header))
    body = []
    for r in rows:
        tds = "".join(f'<td class="{"l" if i < left else ""}">{v if i in raw else html.escape(_cell(v))}</td>'
                      for i, v in enumerate(r))
        body.append(f"<tr>{tds}</tr>")
    return f"<table><thead><tr>{th}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def page(title: str, sections: list[tuple[str, str]], subtitle: str = "") -> str:
    """The whole page: sections are (heading, HTML)."""
    body = "".join(f'<section><h2 id="{html.escape(h.lower().replace(" ", "-"))}">{html.escape(h)}</h2>{c}</section>'
                   for h, c in sections)
    nav = " · ".join(f'<a href="#{html.escape(h.lower().replace(" ", "-"))}">{html.escape(h)}</a>' for h, _ in sections)
    return (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{html.escape(title)}</title>"
            f"<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\"><style>{CSS}</style></head>"
            f"<body><h1>{html.escape(title)}</h1><p>{html.escape(subtitle)}</p><p>{nav}</p>{body}</body></html>\n")


def deg(rad: float) -> float:
    return math.degrees(rad)
