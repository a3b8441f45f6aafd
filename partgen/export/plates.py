"""Lay a kit's printed parts out on build plates; one multi-object 3MF and a picture per plate.

Every part already lies in its print orientation on z >= 0, so laying it out is a 2-D problem: its
*footprint* is the convex hull of its vertices projected on xy, grown by ``margin / 2``, so two
footprints that touch hold their parts ``margin`` apart.

The packer places every copy, largest footprint first, at the bottom-left-most free spot of the
first plate it fits on (trying ``angles`` rotations about z), and opens a new plate when it fits on
none. Internally it packs a polygon with ``_K`` fixed edge directions drawn around each footprint
at the exact support distances, so it contains the true (unapproximated) hull grown by margin/2
and parts end up at least ``margin`` apart (round parts lose at most 0.12 % of width to it).
Because all these polygons share their edge directions, the no-fit polygon of two of them (where
one's origin must not go) is again one of them with summed support distances, and the free region
for a part is one shapely difference: the plate rectangle minus the union of the no-fit polygons;
its bottom-left point is one of its vertices. Nothing is random: the same input gives the same
layout.

The 3MF is written here (zip + the core-spec XML) rather than by trimesh's exporter, which needs
lxml and stamps random UUIDs on every object, so its files are never byte-identical run to run.
"""

from __future__ import annotations

import io
import math
import zipfile
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import shapely
import trimesh
from shapely.geometry import Polygon, box

__all__ = ["Placement", "Layout", "footprint", "layout", "plate_meshes", "instance_name",
           "write_plate_3mf", "plate_picture"]

_K = 64  # edge directions of the packing polygons (a multiple of 4: the axes are among them)
_DIRS = np.arange(_K) * (2 * math.pi / _K)
_N = np.column_stack([np.cos(_DIRS), np.sin(_DIRS)])  # (K, 2) outward edge normals
_DELTA = 2 * math.pi / _K
_EPS = 1e-7  # mm; numerical slack when checking a candidate position


@dataclass(frozen=True)
class Placement:
    """Copy ``copy`` (1-based) of part ``name`` on plate ``plate`` (0-based): rotated by ``angle``
    (rad, about z, about the part's local origin), then its local origin moved to (x, y)."""

    name: str
    copy: int
    plate: int
    x: float
    y: float
    angle: float


@dataclass(frozen=True)
class Layout:
    """Placements per plate (plate i holds ``plates[i]``) on plates of ``size`` = (W, H) mm."""

    plates: tuple[tuple[Placement, ...], ...]
    size: tuple[float, float]


def instance_name(p: Placement) -> str:
    """The name of a placed copy: ``M4#2`` for copy 2 of M4."""
    return f"{p.name}#{p.copy}"


def _hull(mesh: trimesh.Trimesh):
    """Convex hull (shapely) of the mesh's vertices projected on xy."""
    v = np.asarray(mesh.vertices, dtype=float)
    if len(v) < 3:
        raise ValueError("a mesh with fewer than 3 vertices has no footprint")
    # one coordinate sequence (a LineString) is far cheaper to build than a MultiPoint
    return shapely.linestrings(v[:, :2]).convex_hull


def footprint(mesh: trimesh.Trimesh, margin: float) -> Polygon:
    """The part's footprint on the plate: convex hull of its vertices on xy, grown by margin/2
    (round joins as 8 chords per quarter circle, which lie at most 0.5 % of margin/2 inside)."""
    return _hull(mesh).buffer(margin / 2.0, quad_segs=8)


def _rot2(angle: float) -> np.ndarray:
    """2×2 rotation matrix, exact at multiples of 90° (a quarter turn leaves no 1e-16 noise)."""
    c, s = math.cos(angle), math.sin(angle)
    c, s = (float(round(t)) if abs(t - round(t)) < 1e-12 else t for t in (c, s))
    return np.array([[c, -s], [s, c]])


def _support(pts: np.ndarray, grow: float) -> np.ndarray:
    """Support distances (K,) of conv(pts) grown by ``grow`` in the _K fixed directions."""
    return (pts @ _N.T).max(axis=0) + grow


_S0, _C0 = np.sin(_DIRS) / math.sin(_DELTA), np.cos(_DIRS) / math.sin(_DELTA)
_S1, _C1 = np.roll(_S0, -1), np.roll(_C0, -1)


def _kgon(h: np.ndarray) -> np.ndarray:
    """Vertices (..., K, 2) of {p : n_k·p <= h_k for all k} for supports h (..., K): edge k meets
    edge k+1 at vertex k."""
    h1 = np.roll(h, -1, axis=-1)
    return np.stack([h * _S1 - h1 * _S0, h1 * _C0 - h * _C1], axis=-1)


def _kgon_area(h: np.ndarray) -> float:
    v = _kgon(h)
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


# support indices of the axis directions: +x, +y, -x, -y
_PX, _PY, _MX, _MY = 0, _K // 4, _K // 2, 3 * _K // 4
_OPP = (np.arange(_K) + _K // 2) % _K  # h_{-P}(n_k) = h_P(-n_k) = h_P[_OPP[k]]


@dataclass
class _Shape:
    """One rotation of one part's packing polygon, relative to its local origin."""

    angle: float
    h: np.ndarray  # (K,) support distances

    @property
    def width(self) -> float:
        return float(self.h[_PX] + self.h[_MX])

    @property
    def height(self) -> float:
        return float(self.h[_PY] + self.h[_MY])


@dataclass
class _Plate:
    placed: list  # of (Placement, h (K,) translated support)
    used: float  # packing-polygon area on it


def _spot(shape: _Shape, plate: _Plate, W: float, H: float) -> tuple[float, float] | None:
    """Bottom-left-most origin position of ``shape`` on ``plate`` (or None if it does not fit)."""
    h = shape.h
    x0, x1 = float(h[_MX]), W - float(h[_PX])  # the inner-fit rectangle of the origin
    y0, y1 = float(h[_MY]), H - float(h[_PY])
    if x1 < x0 - 1e-9 or y1 < y0 - 1e-9:
        return None
    x1, y1 = max(x1, x0), max(y1, y0)
    if not plate.placed:
        return x0, y0
    hn = np.array([hq for _, hq in plate.placed]) + h[_OPP]  # (n, K) no-fit polygons
    # keep the no-fit polygons whose bounding box meets the inner-fit rectangle
    near = ((-hn[:, _MX] < x1) & (hn[:, _PX] > x0) & (-hn[:, _MY] < y1) & (hn[:, _PY] > y0))
    hn = hn[near]
    if len(hn) == 0:
        return x0, y0
    nfps = shapely.polygons(_kgon(hn))
    free = box(x0, y0, x1, y1).difference(shapely.union_all(nfps))
    pts = shapely.get_coordinates(free)
    if len(pts) == 0:
        return None
    order = np.lexsort((pts[:, 0], np.round(pts[:, 1], 6)))
    for i in order:  # first candidate that truly lies outside every no-fit polygon's interior
        t = np.clip(pts[i], (x0, y0), (x1, y1))
        gap = (_N @ t)[None, :] - hn  # > 0 on the outside of edge k
        if np.all(gap.max(axis=1) >= -_EPS):
            return float(t[0]), float(t[1])
    return None


def layout(items: list[tuple[str, trimesh.Trimesh, int]], plate_xy: tuple[float, float],
           margin: float = 5.0, angles: int = 4) -> Layout:
    """Pack ``count`` copies of every ``(name, mesh, count)`` onto as few plates as it can.

    Largest footprint first, each copy goes to the first plate where it fits, at the
    bottom-left-most spot (lowest top edge, then leftmost) over ``angles`` rotations
    k·360°/angles. Each footprint stays inside [0, W]×[0, H] and clear of the others, so parts
    are at least ``margin`` apart and ``margin / 2`` from the plate edge. Raises ValueError naming
    a part that fits on an empty plate in none of the rotations.
    """
    W, H = float(plate_xy[0]), float(plate_xy[1])
    if not (W > 0 and H > 0):
        raise ValueError(f"plate size must be positive, got {plate_xy!r}")
    if int(angles) < 1:
        raise ValueError(f"angles must be >= 1, got {angles!r}")
    angles = int(angles)
    dup = [n for n, c in Counter(name for name, _, _ in items).items() if c > 1]
    if dup:
        raise ValueError(f"part names must be distinct, repeated: {dup}")
    grow = margin / 2.0
    # every part's distinct rotations (near-identical packing polygons are tried once)
    parts = []
    for idx, (name, mesh, count) in enumerate(items):
        if count <= 0:
            continue
        hull_poly = _hull(mesh)
        hull = shapely.get_coordinates(hull_poly)
        shapes: list[_Shape] = []
        for m in range(angles):
            a = 2 * math.pi * m / angles
            h = _support(hull @ _rot2(a).T, grow)
            if any(np.max(np.abs(h - s.h)) < 0.05 for s in shapes):
                continue
            shapes.append(_Shape(a, h))
        fits = [s for s in shapes if s.width <= W + 1e-9 and s.height <= H + 1e-9]
        if not fits:
            w, d = min((s.width, s.height) for s in shapes)
            raise ValueError(
                f"part {name!r} does not fit on a {W:g} x {H:g} mm plate in any of {angles} "
                f"rotation(s): footprint {w:.1f} x {d:.1f} mm with {margin:g} mm margin")
        area = float(hull_poly.buffer(grow, quad_segs=8).area)  # == footprint(mesh, margin).area
        parts.append((-round(area, 6), idx, name, int(count), fits,
                      min(_kgon_area(f.h) for f in fits)))
    parts.sort(key=lambda p: (p[0], p[1]))

    plates: list[_Plate] = []
    for _, _, name, count, shapes, area in parts:
        for copy in range(1, count + 1):
            for pi in range(len(plates) + 1):
                if pi == len(plates):
                    plates.append(_Plate([], 0.0))
                plate = plates[pi]
                if plate.used + area > W * H + 1e-6:
                    continue
                best = None
                for s in shapes:
                    t = _spot(s, plate, W, H)
                    if t is None:
                        continue
                    key = (round(t[1] + s.h[_PY], 6), round(t[0] - s.h[_MX], 6))
                    if best is None or key < best[0]:
                        best = (key, s, t)
                if best is None:
                    if not plate.placed:  # cannot happen: every shape in `fits` fits alone
                        raise ValueError(f"part {name!r} does not fit on an empty plate")
                    continue
                _, s, (x, y) = best
                p = Placement(name, copy, pi, x, y, s.angle)
                plate.placed.append((p, s.h + _N @ np.array([x, y])))
                plate.used += area
                break
    return Layout(tuple(tuple(p for p, _ in pl.placed) for pl in plates if pl.placed), (W, H))


def _place(mesh: trimesh.Trimesh, p: Placement) -> trimesh.Trimesh:
    r = _rot2(p.angle)
    v = np.asarray(mesh.vertices, dtype=float)
    out = np.empty_like(v)
    out[:, :2] = v[:, :2] @ r.T + (p.x, p.y)
    out[:, 2] = v[:, 2]
    return trimesh.Trimesh(out, np.asarray(mesh.faces), process=False)


def plate_meshes(lay: Layout, meshes: dict[str, trimesh.Trimesh]
                 ) -> list[list[tuple[str, trimesh.Trimesh]]]:
    """Every plate's parts moved into place (rotation about z, then translation), named ``M4#2``."""
    return [[(instance_name(p), _place(meshes[p.name], p)) for p in plate] for plate in lay.plates]


# --- 3MF ---------------------------------------------------------------------------------------

_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" '
    'ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" '
    'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    '</Types>\n')
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    '</Relationships>\n')


def _model_xml(parts: list[tuple[str, trimesh.Trimesh]]) -> bytes:
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n'
           '<model unit="millimeter" xml:lang="en-US" '
           'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n<resources>\n']
    for i, (name, mesh) in enumerate(parts, start=1):
        v = np.asarray(mesh.vertices, dtype=float)
        f = np.asarray(mesh.faces, dtype=np.int64)
        out.append(f'<object id="{i}" name={quoteattr(str(name))} type="model"><mesh><vertices>\n')
        # shortest repr that reads back to the same double: exact and platform independent
        out.append(('<vertex x="%s" y="%s" z="%s"/>\n' * len(v))
                   % tuple(map(repr, v.ravel().tolist())))
        out.append("</vertices><triangles>\n")
        out.append(('<triangle v1="%d" v2="%d" v3="%d"/>\n' * len(f)) % tuple(f.ravel().tolist()))
        out.append("</triangles></mesh></object>\n")
    out.append("</resources>\n<build>\n")
    out.extend(f'<item objectid="{i}"/>\n' for i in range(1, len(parts) + 1))
    out.append("</build>\n</model>\n")
    return "".join(out).encode("utf-8")


def write_plate_3mf(parts: list[tuple[str, trimesh.Trimesh]]) -> bytes:
    """One 3MF (core spec, millimetres) with every ``(name, mesh)`` as its own named object.

    Written with the standard library rather than trimesh's exporter, which needs lxml and stamps
    random UUIDs into every file: the same parts give the same bytes (fixed zip dates, no UUIDs).
    """
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for name, text in (("[Content_Types].xml", _CONTENT_TYPES.encode()),
                           ("_rels/.rels", _RELS.encode()),
                           ("3D/3dmodel.model", _model_xml(parts))):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.create_system = 0
            info.external_attr = 0o644 << 16
            z.writestr(info, text, compresslevel=6)
    return buf.getvalue()


# --- picture -----------------------------------------------------------------------------------

def plate_picture(lay: Layout, footprints: dict[str, Polygon], path: str | Path,
                  title: str = "") -> Path:
    """A PNG with one panel per plate: the plate rectangle and every placed footprint, filled and
    labelled with its copy name. ``footprints`` maps part name -> footprint (local frame)."""
    import matplotlib
    from matplotlib.figure import Figure  # Agg canvas directly: no pyplot, no display
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.patches import Polygon as MplPolygon, Rectangle

    W, H = lay.size
    n = max(1, len(lay.plates))
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    panel = 8.0
    fig = Figure(figsize=(panel * cols, panel * H / W * rows + 0.8), dpi=100)
    FigureCanvasAgg(fig)
    names = sorted({p.name for plate in lay.plates for p in plate})
    cmap = matplotlib.colormaps["tab20"]
    colour = {nm: cmap(i % 20) for i, nm in enumerate(names)}
    pt_per_mm = 0.85 * panel * 72 / max(W, H)
    for i in range(n):
        ax = fig.add_subplot(rows, cols, i + 1)
        ax.add_patch(Rectangle((0, 0), W, H, fill=False, lw=1.5, ec="black"))
        plate = lay.plates[i] if i < len(lay.plates) else ()
        area = 0.0
        for p in plate:
            r = _rot2(p.angle)
            xy = np.asarray(footprints[p.name].exterior.coords) @ r.T + (p.x, p.y)
            area += footprints[p.name].area
            ax.add_patch(MplPolygon(xy, closed=True, fc=colour[p.name], ec="0.2", lw=0.6,
                                    alpha=0.85))
            c = xy[:-1].mean(axis=0)
            label = instance_name(p)
            width_pt = np.ptp(xy[:, 0]) * pt_per_mm  # fit the label across the footprint
            ax.text(c[0], c[1], label, ha="center", va="center",
                    fontsize=float(np.clip(width_pt / (0.65 * len(label)), 4.0, 10.0)))
        ax.set_xlim(-0.02 * W, 1.02 * W)
        ax.set_ylim(-0.02 * H, 1.02 * H)
        ax.set_aspect("equal")
        ax.set_title(f"plate {i + 1}: {len(plate)} parts, {100 * area / (W * H):.0f} % covered",
                     fontsize=9)
        ax.tick_params(labelsize=7)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, format="png")
    return path
