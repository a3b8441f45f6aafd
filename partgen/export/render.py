"""Shaded pictures of meshes without a display: an orthographic view drawn with matplotlib
(faces turned away are culled, the rest drawn back to front with Lambert shading)."""

from __future__ import annotations

import io
import math

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.colors import to_rgb  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

__all__ = ["view_matrix", "render"]

LIGHT = np.array([-0.4, 0.5, 0.77])


def view_matrix(elev_deg: float = 30.0, azim_deg: float = -60.0) -> np.ndarray:
    """(3, 3) world → camera rotation: camera x right, y up, z toward the viewer."""
    a, e = math.radians(azim_deg), math.radians(elev_deg)
    Rz = np.array([[math.cos(-a - math.pi / 2), -math.sin(-a - math.pi / 2), 0],
                   [math.sin(-a - math.pi / 2), math.cos(-a - math.pi / 2), 0], [0, 0, 1]])
    Rx = np.array([[1, 0, 0], [0, math.cos(e - math.pi / 2), -math.sin(e - math.pi / 2)],
                   [0, math.sin(e - math.pi / 2), math.cos(e - math.pi / 2)]])
    return Rx @ Rz


def render(meshes: list[tuple[np.ndarray, np.ndarray, str]], size_px: tuple[int, int] = (360, 300),
           elev: float = 30.0, azim: float = -60.0, title: str = "") -> bytes:
    """PNG bytes of meshes seen from (elev, azim). meshes: (vertices (n, 3) mm, faces (m, 3), colour)."""
    R = view_matrix(elev, azim)
    polys, shades = [], []
    for v, f, colour in meshes:
        c = np.asarray(v, dtype=float) @ R.T
        tri = c[np.asarray(f)]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        norm = np.linalg.norm(n, axis=1)
        ok = norm > 1e-12
        n[ok] /= norm[ok, None]
        front = ok & (n[:, 2] > 0)
        tri, n = tri[front], n[front]
        light = LIGHT / np.linalg.norm(LIGHT)
        k = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
        rgb = np.clip(np.outer(k, to_rgb(colour)), 0, 1)
        polys.append(tri)
        shades.append(np.column_stack([rgb, tri[:, :, 2].mean(axis=1)]))
    tri = np.concatenate(polys) if polys else np.zeros((0, 3, 3))
    sh = np.concatenate(shades) if shades else np.zeros((0, 4))
    order = np.argsort(sh[:, 3], kind="stable")  # far first
    fig, ax = _canvas(tuple(size_px), title)
    ax.add_collection(PolyCollection(tri[order][:, :, :2], facecolors=sh[order, :3], edgecolors="none",
                                     linewidths=0, antialiased=False), autolim=False)  # the limits are set below
    if len(tri):
        lo, hi = tri[:, :, :2].reshape(-1, 2).min(axis=0), tri[:, :, :2].reshape(-1, 2).max(axis=0)
        pad = 0.04 * max(hi - lo)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_axis_off()
    if title:
        fig.suptitle(title, fontsize=9)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    return buf.getvalue()


DPI = 100
_CANVASES: dict = {}  # size -> (figure, axes) of the untitled pictures: made once, cleared for each


def _canvas(size_px: tuple[int, int], title: str):
    """A figure of ``size_px`` with one bare axes filling it (below a title when there is one)."""
    def make():
        fig = Figure(figsize=(size_px[0] / DPI, size_px[1] / DPI), dpi=DPI)
        FigureCanvasAgg(fig)
        return fig, fig.add_axes([0, 0, 1, 0.92 if title else 1])
    if title:
        return make()
    if size_px not in _CANVASES:
        _CANVASES[size_px] = make()
    fig, ax = _CANVASES[size_px]
    for c in list(ax.collections):
        c.remove()
    return fig, ax
