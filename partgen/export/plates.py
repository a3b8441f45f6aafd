"""Lay a kit's printed parts out on build plates; one 3MF and a picture per plate.

Every part already lies in its print orientation on z >= 0, so laying it out is a 2-D problem: its
*footprint* is the convex hull of its vertices projected on xy, grown by ``margin / 2``, so two
footprints that touch hold their parts ``margin`` apart.

**Which turns a part tries.** A part may turn freely about z. Each part tries ``angles`` evenly
spaced turns of the pose it was designed in, the four quarter turns of its minimum-area rectangle
(long side along x), and, when none of those fits the plate, the turn that leaves it the most room
(a long part on the diagonal) with its quarter turns. Whether a part fits the plate at all is
decided exactly: its footprint's extents at turn t are those of the rotated hull plus the margin,
and :func:`best_turn` finds the turn with the most room by a branch and bound over t in [0, π)
whose bound is certified (the extents are Lipschitz in t with the hull's diameter), so "does not
fit" means no turn of the part fits the plate, not that none of a few tried turns does.

**Packing.** The packer places every copy, largest footprint first, at the bottom-left-most free
spot of the first plate it fits on (over the part's turns), and opens a new plate when it fits on
none: first-fit decreasing, bottom-left. Internally it packs a polygon with ``_K`` fixed edge
directions drawn around each footprint at the exact support distances, so it contains the true
(unapproximated) hull grown by margin/2 and parts end up at least ``margin`` apart; its extents
along x and y are exact, so a part that fits the plate also fits as packed. Because all these
polygons share their edge directions, the no-fit polygon of two of them (where one's origin must
not go) is again one of them with summed support distances, and the free region for a part is one
shapely difference: the plate rectangle minus the union of the no-fit polygons; its bottom-left
point is one of its vertices. Nothing is random: the same input gives the same layout.

The 3MF of a plate (:func:`plate_3mf`) holds each distinct part once, as a named mesh object, and
each copy as a build item placing it (see :mod:`partgen.export.threemf`).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon, box

from ..core.quantise import RESOLUTION_MM
from ..core.transforms import rot2
from .stl import Mesh
from .threemf import Object3MF, write_3mf

__all__ = ["Placement", "Layout", "DoesNotFit", "footprint", "best_turn", "layout", "plate_meshes",
           "placement_matrix", "instance_name", "plate_3mf", "plate_picture"]

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


def _hull(mesh: Mesh):
    """Convex hull (shapely) of the mesh's vertices projected on xy."""
    v = np.asarray(mesh.vertices, dtype=float)
    if len(v) < 3:
        raise ValueError("a mesh with fewer than 3 vertices has no footprint")
    # quantised to RESOLUTION_MM first: a part's top and bottom vertices project onto one point, and
    # without it the last bits decide whether the hull keeps a 1e-14 mm edge there, whose round join
    # changes the footprint's area by 1e-3 mm² and can reorder the packing on another machine
    xy = np.round(v[:, :2] / RESOLUTION_MM) * RESOLUTION_MM
    # one coordinate sequence (a LineString) is far cheaper to build than a MultiPoint
    return shapely.linestrings(xy).convex_hull


def footprint(mesh: Mesh, margin: float) -> Polygon:
    """The part's footprint on the plate: convex hull of its vertices on xy, grown by margin/2
    (round joins as 8 chords per quarter circle, which lie at most 0.5 % of margin/2 inside)."""
    return _hull(mesh).buffer(margin / 2.0, quad_segs=8)


def fits_plate(mesh: Mesh, plate_xy: tuple[float, float], margin: float = 5.0) -> bool:
    """Whether a part, its mesh as it prints, fits a ``plate_xy`` = (W, H) mm plate at some turn about
    z with ``margin / 2`` mm to the edge — as ``layout`` would place it (``best_turn``: certified)."""
    hull = np.asarray(_hull(mesh).exterior.coords)
    return best_turn(hull, plate_xy, margin / 2.0)[1] >= -_FIT_TOL


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


# --- does a part fit the plate, and turned how --------------------------------------------------

_GRID = 720  # first sampling of the turn t over [0, π)
_LIVE = 1 << 15  # most intervals the branch and bound keeps per level (see best_turn)
_FIT_TOL = 1e-9  # mm: a part fits when its footprint sticks out by no more than this


class DoesNotFit(ValueError):
    """A part fits the plate in no turn about z; ``part`` names it, ``overhang`` is by how much it
    sticks out at best (mm), at turn ``angle`` (rad)."""

    def __init__(self, message: str, part: str, overhang: float, angle: float):
        super().__init__(message)
        self.part, self.overhang, self.angle = part, overhang, angle

    @property
    def parts(self) -> tuple[str, ...]:
        return (self.part,)


def _room(pts: np.ndarray, W: float, H: float, t: np.ndarray, half: float
          ) -> tuple[np.ndarray, np.ndarray]:
    """Room left, mm, by the tighter axis, when conv(pts) turned by t (m,) rad lies in W × H:
    min(W - x extent, H - y extent); and an upper bound of the room over [t - half, t + half].

    pts : (n, 2) float, mm. Returns (room (m,), bound (m,)). The bound: if p, q are the extreme
    points along x at t, X the x extent and d the offset of p - q across it (along y), then at a
    turn within h of t the x extent is at least (p - q)·u >= X cos h - |d| sin h (likewise for y).
    It is tight for round parts (d ~ 0), where a bound by the diameter D alone (X - D h) is not.
    """
    c, s = np.cos(t), np.sin(t)
    x = np.outer(pts[:, 0], c) - np.outer(pts[:, 1], s)  # (n, m) turned x
    y = np.outer(pts[:, 0], s) + np.outer(pts[:, 1], c)
    cols = np.arange(len(t))
    ext = []
    for u, v in ((x, y), (y, x)):
        hi, lo = u.argmax(axis=0), u.argmin(axis=0)
        e = u[hi, cols] - u[lo, cols]
        d = np.abs(v[hi, cols] - v[lo, cols])
        ext.append((e, np.maximum(e * math.cos(half) - d * math.sin(half), 0.0)))
    (X, Xlo), (Y, Ylo) = ext
    return np.minimum(W - X, H - Y), np.minimum(W - Xlo, H - Ylo)


def best_turn(points: np.ndarray, plate_xy: tuple[float, float], grow: float = 0.0,
              tol: float = 1e-3) -> tuple[float, float]:
    """The turn about z that leaves the convex hull of ``points`` grown by ``grow`` the most room on
    a ``plate_xy`` = (W, H) plate, and that room.

    points : (n, 2) float, mm. Returns (t, room): t in [0, π) rad (t + π gives the same extents),
    room in mm = min(W - x extent, H - y extent) at t; room >= 0 iff the part fits turned by t.

    A branch and bound over t in [0, π): every interval carries an upper bound of the room
    anywhere in it (see ``_room``), and is halved while that bound could beat the best room found
    by ``tol`` mm (and, while no turn that fits is found, while the bound is >= 0). So a negative
    result means that no turn fits (it is certified by the bound, not sampled), and either result
    is within ``tol`` of the best room. At most ``_LIVE`` intervals are kept per level (those with
    the highest bound), which only a part whose room stays within about ``tol`` of the best over
    a wide range of turns could reach.
    """
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) == 0 or not np.all(np.isfinite(pts)):
        raise ValueError("points must be a non-empty finite (n, 2) array")
    pts = shapely.get_coordinates(shapely.multipoints(pts).convex_hull)
    pts = pts - pts.mean(axis=0)
    W, H = float(plate_xy[0]) - 2 * grow, float(plate_xy[1]) - 2 * grow
    half = math.pi / (2 * _GRID)
    t = (2 * np.arange(_GRID) + 1) * half
    room, bound = _room(pts, W, H, t, half)
    i = int(np.argmax(room))
    best_t, best = float(t[i]), float(room[i])
    while half > 1e-12:
        keep = bound > best + tol  # could beat the best room found by tol
        if best < -_FIT_TOL:  # no fit found yet: keep every interval that might hold one
            keep |= bound >= -_FIT_TOL
        t, bound = t[keep], bound[keep]
        if not len(t):
            break
        if len(t) > _LIVE:
            t = t[np.sort(np.argsort(-bound, kind="stable")[:_LIVE])]
        half /= 2
        t = np.concatenate([t - half, t + half])
        room, bound = _room(pts, W, H, t, half)
        i = int(np.argmax(room))
        if room[i] > best:
            best_t, best = float(t[i]), float(room[i])
    return best_t % math.pi, best


def _turns(hull: np.ndarray, W: float, H: float, grow: float, angles: int, free: bool) -> list[float]:
    """The turns (rad) a part tries, in order: its own pose's ``angles`` even turns, then, if
    ``free``, the quarter turns of its minimum-area rectangle (long side along x) and, if none of
    those fits, the quarter turns of the turn with the most room, preceded by those of the
    nearest turn that puts the rectangle's long side along one of the ``_K`` packing directions
    (its packing polygon then hugs its long sides: see the module), if that one fits too."""
    out = [2 * math.pi * m / angles for m in range(angles)]
    if not free:
        return out
    env = shapely.oriented_envelope(shapely.linestrings(hull))
    rect = np.asarray(env.exterior.coords) if env.geom_type == "Polygon" else np.empty((0, 2))
    base = 0.0
    if len(rect) >= 4:
        e = np.diff(rect[:3], axis=0)
        d = e[int(np.argmax(np.hypot(e[:, 0], e[:, 1])))]
        base = -math.atan2(d[1], d[0])
        out += [(base + k * math.pi / 2) % (2 * math.pi) for k in range(4)]

    def fits(a: float) -> bool:
        w, h = np.ptp(hull @ rot2(a).T, axis=0) + 2 * grow
        return w <= W + _FIT_TOL and h <= H + _FIT_TOL

    if not any(fits(a) for a in out):
        t, room = best_turn(hull, (W, H), grow)
        if room >= -_FIT_TOL:
            snap = base + round((t - base) / _DELTA) * _DELTA
            for a in ([snap] if fits(snap) else []) + [t]:
                out += [(a + k * math.pi / 2) % (2 * math.pi) for k in range(4)]
    return out


def layout(items: list[tuple[str, Mesh, int]], plate_xy: tuple[float, float],
           margin: float = 5.0, angles: int = 4, free: bool = True) -> Layout:
    """Pack ``count`` copies of every ``(name, mesh, count)`` onto as few plates as it can.

    Largest footprint first, each copy goes to the first plate where it fits, at the
    bottom-left-most spot (lowest top edge, then leftmost) over the part's turns (``angles`` even
    turns of its pose, its minimum-area rectangle's quarter turns, and the turn with the most
    room when it needs one: see the module). Each footprint stays inside [0, W]×[0, H] and clear
    of the others, so parts are at least ``margin`` apart and ``margin / 2`` from the plate edge.
    Raises :class:`DoesNotFit` (a ValueError) naming a part that fits the plate in no turn.
    ``free=False`` tries only the ``angles`` even turns (the packer before free turns; a
    benchmark's baseline), and then "does not fit" means: in none of those turns.
    """
    W, H = float(plate_xy[0]), float(plate_xy[1])
    if not (math.isfinite(W) and math.isfinite(H) and W > 0 and H > 0):
        raise ValueError(f"plate size must be positive, got {plate_xy!r}")
    if not (math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin must be >= 0, got {margin!r}")
    if int(angles) < 1:
        raise ValueError(f"angles must be >= 1, got {angles!r}")
    angles = int(angles)
    dup = [n for n, c in Counter(name for name, _, _ in items).items() if c > 1]
    if dup:
        raise ValueError(f"part names must be distinct, repeated: {dup}")
    grow = margin / 2.0
    # every part's distinct turns (near-identical packing polygons are tried once)
    parts = []
    for idx, (name, mesh, count) in enumerate(items):
        if count <= 0:
            continue
        hull_poly = _hull(mesh)
        hull = shapely.get_coordinates(hull_poly)
        shapes: list[_Shape] = []
        for a in _turns(hull, W, H, grow, angles, free):
            h = _support(hull @ rot2(a).T, grow)
            if any(np.max(np.abs(h - s.h)) < 0.05 for s in shapes):
                continue
            shapes.append(_Shape(a, h))
        fits = [s for s in shapes if s.width <= W + _FIT_TOL and s.height <= H + _FIT_TOL]
        if not fits and not free:
            w, d = min((s.width, s.height) for s in shapes)
            raise DoesNotFit(f"part {name!r} does not fit on a {W:g} x {H:g} mm plate in any of "
                             f"{angles} turn(s): footprint {w:.1f} x {d:.1f} mm with {margin:g} mm "
                             "margin", name, float("nan"), float("nan"))
        if not fits:
            t, room = best_turn(hull, (W, H), grow)
            ext = np.ptp(hull @ rot2(t).T, axis=0) + margin
            raise DoesNotFit(
                f"part {name!r} does not fit on a {W:g} x {H:g} mm plate in any turn about z: "
                f"with the {margin:g} mm margin it sticks out {-room:.1f} mm at best "
                f"({ext[0]:.1f} x {ext[1]:.1f} mm turned {math.degrees(t):.1f}°)", name, -room, t)
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


def placement_matrix(p: Placement) -> np.ndarray:
    """(4, 4) the placement of a copy: turn by ``p.angle`` about z, then move by (x, y, 0) mm."""
    m = np.eye(4)
    m[:2, :2] = rot2(p.angle)
    m[:2, 3] = p.x, p.y
    return m


def _place(mesh: Mesh, p: Placement) -> Mesh:
    r = rot2(p.angle)
    v = np.asarray(mesh.vertices, dtype=float)
    out = np.empty_like(v)
    out[:, :2] = v[:, :2] @ r.T + (p.x, p.y)
    out[:, 2] = v[:, 2]
    return Mesh(out, mesh.faces)


def plate_meshes(lay: Layout, meshes: dict[str, Mesh]
                 ) -> list[list[tuple[str, Mesh]]]:
    """Every plate's parts moved into place (rotation about z, then translation), named ``M4#2``."""
    return [[(instance_name(p), _place(meshes[p.name], p)) for p in plate] for plate in lay.plates]


def plate_3mf(plate: tuple[Placement, ...], meshes: dict[str, Mesh], design: str = "",
              material: str = "", description: str = "") -> bytes:
    """The 3MF of one plate: each distinct part on it once, as a mesh object named after the part
    (in its print orientation, as its STL holds it), and each copy as a build item placing that
    object (item partnumber ``M4#2``). Metadata: Title (the design), Application, Description,
    and per object its part, design, material and copies on this plate."""
    order: dict[str, list[Placement]] = {}
    for p in plate:
        order.setdefault(p.name, []).append(p)
    objects = []
    for name, ps in order.items():
        meta = {"part": name}
        if design:
            meta["design"] = design
        if material:
            meta["material"] = material
        meta["copies"] = str(len(ps))
        m = meshes[name]
        objects.append(Object3MF(name, np.asarray(m.vertices), np.asarray(m.faces),
                                 tuple(placement_matrix(p) for p in ps), meta,
                                 tuple(instance_name(p) for p in ps)))
    md = {}
    if design:
        md["Title"] = design
    md["Application"] = "partgen"
    if description:
        md["Description"] = description
    return write_3mf(objects, md)


# --- picture -----------------------------------------------------------------------------------

_LABEL_PT = (10.0, 6.0)  # largest and smallest label size, points: 6 pt is still legible at 100 dpi


def _overlap(a, b, pad: float = 1.0) -> bool:
    """Whether two display-space boxes (x0, y0, x1, y1) come closer than ``pad`` pixels."""
    return a[0] < b[2] + pad and b[0] < a[2] + pad and a[1] < b[3] + pad and b[1] < a[3] + pad


def _box(text, renderer) -> tuple[float, float, float, float]:
    from matplotlib.text import Text

    e = Text.get_window_extent(text, renderer)
    return float(e.x0), float(e.y0), float(e.x1), float(e.y1)


def _label_footprints(ax, shapes: list[tuple[str, np.ndarray]], pt_per_mm: float) -> None:
    """Write every label (name, its placed footprint outline (n, 2) mm) so that no two labels' text
    boxes overlap (measured with the figure's renderer): each tries, in order, its footprint's
    centre and then points further inside it, at the size that fits across it and then smaller
    down to 6 pt, level and then (for a footprint taller than wide) turned upright; keeping inside
    its footprint first, then anywhere on the plate; and when no spot is free it goes beside the
    plate's parts on the nearest free spot with a leader line to its footprint. Smaller footprints
    choose first (a large one has room to move its label)."""
    renderer = ax.figure.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    inside_ax = lambda b: (b[0] >= frame.x0 and b[2] <= frame.x1 and b[1] >= frame.y0  # noqa: E731
                           and b[3] <= frame.y1)
    to_px = ax.transData.transform
    taken: list[tuple[float, float, float, float]] = []
    order = sorted(range(len(shapes)), key=lambda k: (Polygon(shapes[k][1]).area, k))
    for k in order:
        label, xy = shapes[k]
        poly = Polygon(xy)
        c = np.asarray(poly.centroid.coords[0]) if poly.contains(poly.centroid) else \
            np.asarray(poly.representative_point().coords[0])
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        gx, gy = np.meshgrid(np.linspace(lo[0], hi[0], 9)[1:-1], np.linspace(lo[1], hi[1], 9)[1:-1])
        grid = np.column_stack([gx.ravel(), gy.ravel()])
        grid = grid[shapely.contains_xy(poly, grid[:, 0], grid[:, 1])]
        grid = grid[np.argsort(np.hypot(*(grid - c).T), kind="stable")]
        spots = np.vstack([c[None], grid])
        px_poly = Polygon(to_px(xy))
        fit = float(np.clip(np.ptp(xy[:, 0]) * pt_per_mm / (0.65 * len(label)), *_LABEL_PT[::-1]))
        sizes = [fit] + [s for s in np.arange(fit - 1.0, _LABEL_PT[1] - 1e-9, -1.0)]
        turns = (0, 90) if np.ptp(xy[:, 1]) > 1.3 * np.ptp(xy[:, 0]) else (0,)
        t = ax.text(c[0], c[1], label, ha="center", va="center", fontsize=fit, clip_on=False)

        def free(b) -> bool:
            return inside_ax(b) and not any(_overlap(b, o) for o in taken)

        placed = None
        for within in (True, False):
            for size in sizes:
                for rot in turns:
                    t.set_fontsize(size)
                    t.set_rotation(rot)
                    for s in spots:
                        t.set_position(s)
                        b = _box(t, renderer)
                        if free(b) and (not within or px_poly.contains(box(*b))):
                            placed = b
                            break
                    if placed:
                        break
                if placed:
                    break
            if placed:
                break
        if placed is None:  # beside it, on rings around its centre, with a leader line
            t.set_fontsize(_LABEL_PT[1])
            t.set_rotation(0)
            span = float(max(np.ptp(xy, axis=0)))
            xl, yl = ax.get_xlim(), ax.get_ylim()
            for r in span * np.array([0.6, 0.9, 1.3, 1.8, 2.5, 3.5, 5.0, 7.0]):
                for a in np.arange(16) * (math.pi / 8) + math.pi / 2:
                    s = c + r * np.array([math.cos(a), math.sin(a)])
                    if not (xl[0] <= s[0] <= xl[1] and yl[0] <= s[1] <= yl[1]):
                        continue
                    t.set_position(s)
                    b = _box(t, renderer)
                    if free(b):
                        placed = b
                        ax.plot([c[0], s[0]], [c[1], s[1]], color="0.25", lw=0.6)
                        break
                if placed:
                    break
        if placed is None:  # nowhere free on the plate: drop the label rather than cover another
            t.remove()
            continue
        taken.append(placed)


def _draw_plate(ax, lay: Layout, i: int, footprints: dict[str, Polygon], colour: dict) -> list:
    """Plate ``i`` of ``lay`` on ``ax``: the plate, its footprints, its title. Returns the labels to
    write, (copy name, placed footprint outline (n, 2) mm)."""
    from matplotlib.patches import Polygon as MplPolygon, Rectangle

    W, H = lay.size
    ax.add_patch(Rectangle((0, 0), W, H, fill=False, lw=1.5, ec="black"))
    plate = lay.plates[i] if i < len(lay.plates) else ()
    area = 0.0
    shapes = []
    for p in plate:
        xy = np.asarray(footprints[p.name].exterior.coords) @ rot2(p.angle).T + (p.x, p.y)
        area += footprints[p.name].area
        ax.add_patch(MplPolygon(xy, closed=True, fc=colour[p.name], ec="0.2", lw=0.6, alpha=0.85))
        shapes.append((instance_name(p), xy[:-1]))
    ax.set_xlim(-0.02 * W, 1.02 * W)
    ax.set_ylim(-0.02 * H, 1.02 * H)
    ax.set_aspect("equal")
    ax.set_title(f"plate {i + 1}: {len(plate)} parts, {100 * area / (W * H):.0f} % covered", fontsize=9)
    ax.tick_params(labelsize=7)
    return shapes


def _write_labels(ax, shapes: list) -> None:
    """The labels of a laid-out plate's axes, sized by its scale on the page."""
    ax.apply_aspect()
    W = ax.get_xlim()[1] - ax.get_xlim()[0]
    _label_footprints(ax, shapes, ax.get_window_extent().width * 72 / ax.figure.dpi / W)


def _colours(lay: Layout) -> dict:
    import matplotlib

    names = sorted({p.name for plate in lay.plates for p in plate})
    cmap = matplotlib.colormaps["tab20"]
    return {nm: cmap(i % 20) for i, nm in enumerate(names)}


PLATE_PX = 1100  # width of one plate's picture in the report, pixels (the page's column is 1168)


def plate_figure(lay: Layout, i: int, footprints: dict[str, Polygon], title: str = "",
                 width_px: int = PLATE_PX):
    """A matplotlib Figure (Agg canvas, laid out) of plate ``i`` alone, ``width_px`` wide at 100 dpi,
    labels placed as :func:`_label_footprints` says."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    W, H = lay.size
    w_in = width_px / 100
    fig = Figure(figsize=(w_in, w_in * 0.94 * H / W + 0.7), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_axes([0.05, 0.04, 0.94, 0.94 * (w_in * 0.94 * H / W) / (w_in * 0.94 * H / W + 0.7)])
    if title:
        fig.suptitle(title, fontsize=11, y=0.995)
    _write_labels(ax, _draw_plate(ax, lay, i, footprints, _colours(lay)))
    return fig


def plate_pictures(lay: Layout, footprints: dict[str, Polygon], title: str = "",
                   width_px: int = PLATE_PX) -> list[bytes]:
    """One PNG per plate, each ``width_px`` wide (see :func:`plate_figure`)."""
    import io

    out = []
    for i in range(len(lay.plates)):
        fig = plate_figure(lay, i, footprints, title, width_px)
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        out.append(buf.getvalue())
    return out


def plate_picture(lay: Layout, footprints: dict[str, Polygon], path: str | Path,
                  title: str = "") -> Path:
    """A PNG with one panel per plate: the plate rectangle and every placed footprint, filled and
    labelled with its copy name. ``footprints`` maps part name -> footprint (local frame)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # Agg canvas directly: no pyplot, no display
    from matplotlib.figure import Figure

    W, H = lay.size
    n = max(1, len(lay.plates))
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    panel = 8.0
    fig = Figure(figsize=(panel * cols, panel * H / W * rows + 0.8), dpi=100)
    FigureCanvasAgg(fig)
    axes = [fig.add_subplot(rows, cols, i + 1) for i in range(n)]
    if title:
        fig.suptitle(title, fontsize=11)
    colour = _colours(lay)
    shapes = [_draw_plate(ax, lay, i, footprints, colour) for i, ax in enumerate(axes)]
    fig.tight_layout()  # laid out before the labels are placed: they are measured where they end up
    for ax, sh in zip(axes, shapes):
        _write_labels(ax, sh)
    path = Path(path)
    fig.savefig(path, format="png")
    return path
