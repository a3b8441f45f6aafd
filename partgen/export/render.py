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

__all__ = ["view_matrix", "render", "render_cutaway"]

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


# --- depth-buffered pictures, with a cut-away of parts that hide others ------------------------

HIDES_OWN = 0.5  # a part hiding others over at least this share of its own picture ...
HIDES_ONE = 0.9  # ... and at least this share of one other part's ...
AS_LARGE = 0.2  # ... whose picture is at least this share of its own, is drawn translucent
SEE_THROUGH = 0.25  # opacity of a part drawn translucent


def _runs(ordered: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(the distinct values of a sorted 1-D array, the index of each one's first occurrence): what
    ``np.unique(ordered, return_index=True)`` returns, without its sort of an array already sorted
    (numpy 2's ``np.unique`` of integers hashes them, ten times slower here than a sort)."""
    first = np.flatnonzero(np.concatenate(([True], ordered[1:] != ordered[:-1]))) if len(ordered) else \
        np.zeros(0, np.int64)
    return ordered[first], first


def _raster(px: np.ndarray, z: np.ndarray, size: tuple[int, int], chunk: int = 2_000_000
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rasterise triangles px (m, 3, 2) in pixels (x right, y down), depth z (m, 3) (larger is
    nearer) at pixel centres, by scan lines: every (triangle, pixel row) pair gives the row's span
    inside the triangle, every pixel of the span its depth on the triangle's plane. Returns
    (nearest triangle per pixel (H*W,), -1 where none; and every (pixel, triangle) pair covered,
    as two arrays)."""
    W, H = size
    m = len(px)
    y0 = np.clip(np.ceil(px[:, :, 1].min(axis=1) - 0.5), 0, H).astype(np.int64)
    y1 = np.clip(np.floor(px[:, :, 1].max(axis=1) - 0.5), -1, H - 1).astype(np.int64)
    ny = np.maximum(y1 - y0 + 1, 0)
    # depth plane z = a x + b y + c of every triangle
    e1, e2 = px[:, 1] - px[:, 0], px[:, 2] - px[:, 0]
    dz1, dz2 = z[:, 1] - z[:, 0], z[:, 2] - z[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    ok = np.abs(det) > 1e-9
    det = np.where(ok, det, 1.0)
    a = (dz1 * e2[:, 1] - dz2 * e1[:, 1]) / det
    b = (dz2 * e1[:, 0] - dz1 * e2[:, 0]) / det
    c = z[:, 0] - a * px[:, 0, 0] - b * px[:, 0, 1]
    ny[~ok] = 0
    rep = np.repeat(np.arange(m), ny)  # (triangle, row) pairs
    cy = (y0[rep] + np.arange(len(rep)) - np.repeat(np.cumsum(ny) - ny, ny)) + 0.5
    lo, hi = np.full(len(rep), np.inf), np.full(len(rep), -np.inf)
    for k in range(3):
        p, q = px[rep, k], px[rep, (k + 1) % 3]
        dy = q[:, 1] - p[:, 1]
        cross = ((p[:, 1] - cy) * (q[:, 1] - cy) <= 0) & (dy != 0)
        x = p[:, 0] + (cy - p[:, 1]) * (q[:, 0] - p[:, 0]) / np.where(dy != 0, dy, 1.0)
        lo = np.where(cross, np.minimum(lo, x), lo)
        hi = np.where(cross, np.maximum(hi, x), hi)
    x0 = np.clip(np.ceil(lo - 0.5), 0, W).astype(np.int64)
    x1 = np.clip(np.floor(hi - 0.5), -1, W - 1).astype(np.int64)
    nx = np.maximum(x1 - x0 + 1, 0)
    zbuf = np.full(W * H, -np.inf)
    tbuf = np.full(W * H, -1, dtype=np.int64)
    pairs_p, pairs_t = [], []
    ends = np.cumsum(nx)
    start = 0
    while start < len(rep):
        base = ends[start - 1] if start else 0
        stop = max(int(np.searchsorted(ends, base + chunk, side="right")), start + 1)
        n = nx[start:stop]
        r = np.repeat(np.arange(start, stop), n)
        X = x0[r] + np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        tri = rep[r]
        pix = (cy[r] - 0.5).astype(np.int64) * W + X
        zz = a[tri] * (X + 0.5) + b[tri] * cy[r] + c[tri]
        o = np.lexsort((-zz, pix))  # per pixel, nearest first
        pix_o, first = _runs(pix[o])
        zn, tn = zz[o][first], tri[o][first]
        better = zn > zbuf[pix_o]
        zbuf[pix_o[better]], tbuf[pix_o[better]] = zn[better], tn[better]
        pairs_p.append(pix)
        pairs_t.append(tri)
        start = stop
    return tbuf, np.concatenate(pairs_p) if pairs_p else np.zeros(0, np.int64), \
        np.concatenate(pairs_t) if pairs_t else np.zeros(0, np.int64)


def render_cutaway(meshes: list[tuple[np.ndarray, np.ndarray, str]], size_px: tuple[int, int] = (1100, 720),
                   elev: float = 30.0, azim: float = -60.0, cutaway: bool = True,
                   frame: np.ndarray | None = None) -> tuple[bytes, list[int]]:
    """PNG bytes of meshes seen from (elev, azim) with a depth buffer (each pixel shows the nearest
    surface: nothing shows through a part in front of it), and the indices of the meshes drawn
    translucent. With ``cutaway``, a mesh that hides other meshes over at least ``HIDES_OWN`` of its
    own picture, and at least ``HIDES_ONE`` of one other mesh's whose picture is at least
    ``AS_LARGE`` of its own, is drawn translucent
    (``SEE_THROUGH`` opaque) so that what it covers shows (a housing's top over its gears).
    meshes: (vertices (n, 3) mm, faces (m, 3), colour); ``frame``: points (k, 3) mm the picture is
    framed on (default: the meshes' front faces)."""
    import matplotlib.image

    R = view_matrix(elev, azim)
    light = LIGHT / np.linalg.norm(LIGHT)
    tris, rgbs, owner = [], [], []
    for j, (v, f, colour) in enumerate(meshes):
        tri = (np.asarray(v, dtype=float) @ R.T)[np.asarray(f)]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        norm = np.linalg.norm(n, axis=1)
        front = (norm > 1e-12) & (n[:, 2] > 0)
        tri, n = tri[front], n[front] / norm[front, None]
        k = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
        tris.append(tri)
        rgbs.append(np.clip(np.outer(k, to_rgb(colour)), 0, 1))
        owner.append(np.full(len(tri), j))
    tri = np.concatenate(tris) if tris else np.zeros((0, 3, 3))
    rgb = np.concatenate(rgbs) if rgbs else np.zeros((0, 3))
    own = np.concatenate(owner) if owner else np.zeros(0, np.int64)
    W, H = size_px
    img = np.ones((H * W, 3))
    if not len(tri):
        buf = io.BytesIO()
        matplotlib.image.imsave(buf, img.reshape(H, W, 3), format="png")
        return buf.getvalue(), []
    at = tri[:, :, :2].reshape(-1, 2) if frame is None else (np.asarray(frame, dtype=float) @ R.T)[:, :2]
    lo, hi = at.min(axis=0), at.max(axis=0)
    s = min(W / (1.08 * (hi[0] - lo[0]) + 1e-9), H / (1.08 * (hi[1] - lo[1]) + 1e-9))
    mid = (lo + hi) / 2
    px = np.empty(tri.shape[:2] + (2,))
    px[:, :, 0] = W / 2 + (tri[:, :, 0] - mid[0]) * s
    px[:, :, 1] = H / 2 - (tri[:, :, 1] - mid[1]) * s
    near, pp, pt = _raster(px, tri[:, :, 2], (W, H))
    see = []
    if cutaway and len(meshes) > 1:
        m = len(meshes)
        cover = _runs(np.sort(pp * m + own[pt]))[0]  # (pixel, mesh) pairs: each mesh's picture on its own
        pix, mesh = cover // m, cover % m
        area = np.bincount(mesh, minlength=m)
        front = np.where(near[pix] >= 0, own[np.maximum(near[pix], 0)], -1)
        hid = (front != mesh) & (front >= 0)
        hides = np.zeros((m, m))  # hides[a, b]: pixels of b's picture where a is in front
        np.add.at(hides, (front[hid], mesh[hid]), 1)
        shown = np.bincount(own[near[near >= 0]], minlength=m)
        share_one = hides / np.maximum(area, 1)[None, :]
        share_one[area[None, :] < AS_LARGE * area[:, None]] = 0.0  # a gear hiding its own hub is no housing
        see = [a for a in range(m) if hides[a].sum() >= HIDES_OWN * max(shown[a], 1)
               and share_one[a].max() >= HIDES_ONE]
    hit = near >= 0
    img[hit] = rgb[near[hit]]
    if see:
        keep = ~np.isin(own, see)
        back, _, _ = _raster(px[keep], tri[keep][:, :, 2], (W, H))
        base = np.ones((H * W, 3))
        base[back >= 0] = rgb[keep][back[back >= 0]]
        glass = hit & np.isin(own[np.maximum(near, 0)], see)
        img[glass] = SEE_THROUGH * rgb[near[glass]] + (1 - SEE_THROUGH) * base[glass]
    buf = io.BytesIO()
    matplotlib.image.imsave(buf, img.reshape(H, W, 3), format="png")
    return buf.getvalue(), see
