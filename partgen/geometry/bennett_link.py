"""Printable links of a Bennett linkage: two joint bosses on skew axes joined by a bar.

Link frame (the DH frame of its proximal joint after Rz(θ)): the proximal joint's axis is z through
the origin; the distal joint's axis passes through (a, 0, 0) in direction Rx(α)·z = (0, −sin α,
cos α) — a common normal of length a along x and a twist α. Each boss sits on its axis at an axial
offset (mm along that axis): stacked bosses of two links on one joint are kept apart by choosing
these offsets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import manifold3d as m3d
import numpy as np

from .printing import rotation_between

__all__ = ["skew_link", "distal_axis", "place_on_axis", "Boss", "Bar", "Cup", "Column", "Knee", "bar_paths",
           "polyline_tube", "link_solid", "LINK_PHASES", "base_solid", "capsules", "cylinder_capsules", "tube",
           "pin_solid"]


def distal_axis(a: float, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """(point (3,), direction (3,)) of the distal joint axis in the link frame."""
    return np.array([a, 0.0, 0.0]), np.array([0.0, -math.sin(alpha), math.cos(alpha)])


def place_on_axis(solid: m3d.Manifold, point: np.ndarray, direction: np.ndarray, offset: float) -> m3d.Manifold:
    """Move a z-aligned solid so its axis is the line (point, direction), centred ``offset`` along it."""
    d = direction / np.linalg.norm(direction)
    T = np.column_stack([rotation_between((0.0, 0.0, 1.0), d), point + offset * d])
    return solid.transform(T)


def skew_link(a: float, alpha: float, boss_r: float, boss_len: float, bore_r: float, bar_r: float,
              offsets: tuple[float, float], segments: int = 48) -> m3d.Manifold:
    """A two-joint link of one Bennett loop: bosses (radius boss_r, length boss_len, bore bore_r
    through) on its proximal axis at offsets[0] and on its distal axis at offsets[1], joined by a
    round bar (radius bar_r) between the boss centres."""
    p1, d1 = distal_axis(a, alpha)
    bosses = [Boss((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), offsets[0], boss_r, boss_len, bore_r),
              Boss(tuple(p1), tuple(d1), offsets[1], boss_r, boss_len, bore_r)]
    return link_solid(bosses, [Bar(tuple(bosses[0].centre), tuple(bosses[1].centre), bar_r)], [], segments)


@dataclass(frozen=True)
class Boss:
    """A joint boss: a cylinder (radius, length mm) on the axis through ``point`` along ``axis``,
    centred ``offset`` mm along it, with a bore of ``bore_radius`` through."""

    point: tuple[float, float, float]
    axis: tuple[float, float, float]
    offset: float
    radius: float
    length: float
    bore_radius: float

    @cached_property
    def centre(self) -> np.ndarray:
        d = np.asarray(self.axis, float)
        return np.asarray(self.point, float) + self.offset * d / math.sqrt(float(d @ d))


@dataclass(frozen=True)
class Bar:
    """A round bar (capsule) between two points, radius mm."""

    p0: tuple[float, float, float]
    p1: tuple[float, float, float]
    radius: float


@dataclass(frozen=True)
class Cup:
    """A counterweight pocket: a cylinder (outer radius, height) standing on ``point`` along
    ``axis``, with a blind pocket (radius, depth) open at its far end, to be filled."""

    point: tuple[float, float, float]
    axis: tuple[float, float, float]
    outer_radius: float
    height: float
    pocket_radius: float
    pocket_depth: float

    @property
    def pocket_centre(self) -> np.ndarray:
        d = np.asarray(self.axis, float) / np.linalg.norm(self.axis)
        return np.asarray(self.point, float) + (self.height - self.pocket_depth / 2) * d

    @property
    def pocket_volume(self) -> float:
        return math.pi * self.pocket_radius ** 2 * self.pocket_depth


# How a bent bar is made (the Bennett sweep's bad meshes came from here). Capsules united at a shared
# end are tangent to each other's balls, and two nearly collinear capsules cross at a grazing angle:
# either leaves an edge or a sliver that float32 collapses (5 of 191 sweep designs wrote a link that
# was not one shell). So consecutive bars bending by at most MITRE_MAX_RAD are one swept tube,
# meshed directly with one mitre ring at each corner: no boolean between them at all. At a sharper
# bend the tubes end flat at the corner inside a knuckle ball KNUCKLE_MM fatter than the bar, which
# crosses each tube at acos(r / (r + k)) (~16 deg for an 8 mm bar), never tangent. A bar ending in a
# boss ends flat at the boss centre, inside its bore.
MITRE_MAX_RAD = math.radians(30.0)
KNUCKLE_MM = 0.15


@dataclass(frozen=True)
class Knee:
    """A corner of a bent bar: its point, the radius of the ball that covers it (mm) and the index of
    the bar it belongs to: of the two that meet there, the one that runs into a boss (a knee at a
    boss's exit is part of the bar leaving that boss), else the later one."""

    point: tuple[float, float, float]
    radius: float
    bar: int
    mitred: bool


def bar_paths(bars: list[Bar], ends: list) -> tuple[list[tuple[list[int], np.ndarray]], list[Knee]]:
    """How ``bars`` are built: paths (the bar indices and their (k, 3) points), each one swept tube,
    and the knees where two bars meet outside a boss. ``ends``: points (3,) where bars end inside a
    boss (its centre): a path ends there, flat. Zero-length bars are dropped. Consecutive bars (in
    list order) sharing an end continue one path when they bend by at most MITRE_MAX_RAD and their
    lengths hold the mitres; otherwise they meet in a knuckle."""
    if not bars:
        return [], []
    # points compared to 1e-9 mm (the layout search asks thousands of times: keys made in one pass)
    pts_all = np.array([[b.p0, b.p1] for b in bars], float)
    keys = [(tuple(a), tuple(b)) for a, b in np.round(pts_all, 9).tolist()]
    inside = {tuple(q) for q in np.round(np.asarray(ends, float).reshape(-1, 3), 9).tolist()}
    paths: list[tuple[list[int], list[np.ndarray]]] = []
    knees: list[Knee] = []
    prev = None  # (bar index, direction, length, mitre length used at its start)
    for k, bar in enumerate(bars):
        p0, p1 = pts_all[k]
        length = float(np.linalg.norm(p1 - p0))
        if length < 1e-6:
            continue
        d = (p1 - p0) / length
        joined = False
        if prev is not None and keys[prev[0]][1] == keys[k][0] and keys[k][0] not in inside:
            owner = prev[0] if keys[prev[0]][0] in inside and keys[k][1] not in inside else k
            bend = math.acos(max(-1.0, min(1.0, float(prev[1] @ d))))
            reach = bar.radius * math.tan(bend / 2)  # how far the mitre reaches along each bar
            if (bend <= MITRE_MAX_RAD and bars[prev[0]].radius == bar.radius
                    and prev[3] + reach < prev[2] - 1e-3 and reach < length - 1e-3):
                paths[-1][0].append(k)
                paths[-1][1].append(p1)
                knees.append(Knee(tuple(map(float, p0)), bar.radius / math.cos(bend / 2), owner, True))
                joined = True
            else:
                knees.append(Knee(tuple(map(float, p0)), max(bar.radius, bars[prev[0]].radius) + KNUCKLE_MM, owner, False))
        else:
            reach = 0.0
        if not joined:
            paths.append(([k], [p0, p1]))
            reach = 0.0
        prev = (k, d, length, reach)
    return [(ks, np.array(pts)) for ks, pts in paths], knees


def polyline_tube(points: np.ndarray, radius: float, segments: int = 48, phase: float = 0.0) -> m3d.Manifold:
    """A round tube (radius mm) along a polyline (k, 3), flat at both ends, one mitre ring at each
    corner: one mesh, so its bends hold no boolean. The rings' frames are carried along the path by
    the smallest rotation at each corner, so each mitre ring lies on both cylinders it joins.
    ``phase``: the rings' first vertex, in steps of 2π/segments."""
    pts = np.asarray(points, float)
    d = np.diff(pts, axis=0)
    d /= np.linalg.norm(d, axis=1)[:, None]
    u = np.cross(d[0], [1.0, 0, 0] if abs(d[0][0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    phi = 2 * np.pi * (np.arange(segments) + phase) / segments
    rings = []
    for k in range(len(pts)):
        dk = d[min(k, len(d) - 1)]
        if 0 < k < len(pts) - 1:
            u_prev, d_prev = u, d[k - 1]
            u = rotation_between(d_prev, d[k]) @ u_prev
            v_prev = np.cross(d_prev, u_prev)
            c = radius * (np.cos(phi)[:, None] * u_prev + np.sin(phi)[:, None] * v_prev)
            n = d_prev + d[k]
            t = -(c @ n) / float(d_prev @ n)  # slide along the incoming axis onto the bisecting plane
            rings.append(pts[k] + c + t[:, None] * d_prev)
            continue
        v = np.cross(dk, u)
        rings.append(pts[k] + radius * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v))
    m = len(rings)
    verts = np.concatenate(rings + [pts[:1], pts[-1:]])
    i = np.arange(segments)
    j = (i + 1) % segments
    tris = []
    for k in range(m - 1):
        a, b = k * segments, (k + 1) * segments
        tris += [np.stack([a + i, b + j, a + j], 1), np.stack([a + i, b + i, b + j], 1)]
    s0, s1 = m * segments, m * segments + 1
    last = (m - 1) * segments
    tris += [np.stack([np.full(segments, s0), i, j], 1), np.stack([np.full(segments, s1), last + j, last + i], 1)]
    faces = np.concatenate(tris)
    # outward winding: the tube's signed volume is positive
    a, b, c = (verts[faces[:, q]] for q in range(3))
    if np.einsum("ij,ij->i", a, np.cross(b, c)).sum() < 0:
        faces = faces[:, ::-1]
    out = m3d.Manifold(m3d.Mesh64(vert_properties=np.ascontiguousarray(verts), tri_verts=faces.astype(np.uint64)))
    if out.status() != m3d.Error.NoError:
        raise ValueError(f"a bar along {len(pts)} points is not a manifold tube: {out.status()}")
    return out


def link_solid(bosses: list[Boss], bars: list[Bar], cups: list[Cup] = (), segments: int = 48, phase: float = 0.0
               ) -> m3d.Manifold:
    """A link as one solid: bosses, bars and cups united, then every bore and pocket cut. ``phase``
    (a fraction of one of the ``segments`` steps) turns every round feature's facets about its own
    axis: where two features cross, their facets then meet elsewhere (see ``LINK_PHASES``)."""
    turn = 360.0 * phase / segments

    def round_feature(height, radius, point, axis, offset, center):
        cyl = m3d.Manifold.cylinder(height, radius, -1.0, segments, center).rotate((0.0, 0.0, turn))
        return place_on_axis(cyl, np.asarray(point, float), np.asarray(axis, float), offset)

    add = [round_feature(b.length, b.radius, b.point, b.axis, b.offset, True) for b in bosses]
    paths, knees = bar_paths(bars, [b.centre for b in bosses])
    add += [polyline_tube(pts, bars[ks[0]].radius, segments, phase) for ks, pts in paths]
    add += [m3d.Manifold.sphere(k.radius, segments).rotate((turn, turn, turn)).translate(k.point)
            for k in knees if not k.mitred]
    add += [round_feature(c.height, c.outer_radius, c.point, c.axis, 0.0, False) for c in cups]
    # bores run a little past the faces (bars meeting a boss end within its faces: bar radius ≤ half its length)
    cut = [round_feature(b.length + 0.4, b.bore_radius, b.point, b.axis, b.offset, True) for b in bosses]
    cut += [round_feature(c.pocket_depth + 0.1, c.pocket_radius, c.point, c.axis, c.height - c.pocket_depth, False)
            for c in cups]
    return m3d.Manifold.batch_boolean(add, m3d.OpType.Add) - m3d.Manifold.batch_boolean(cut, m3d.OpType.Add)


# Where curved solids cross, a boolean now and then leaves two vertices ~1e-6 mm apart (a triple
# point of two bars and a knuckle, say), which a float32 STL welds into a non-manifold edge: a
# link is built at the first of these phases whose mesh, as written, stays sound.
LINK_PHASES = (0.0, 0.5, 0.25, 0.75)


def cylinder_capsules(centre: np.ndarray, axis: np.ndarray, radius: float, length: float, spokes: int = 4
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Capsules that together contain a cylinder: ``spokes`` diameters of its mid-plane disc with
    radius √((length/2)² + (radius·sin(π/2k))²) — reaching past the flat faces by far less than
    one capsule along the axis would for a short, fat boss. ((k, 2, 3), (k,))"""
    d = np.asarray(axis, float) / math.sqrt(float(np.dot(axis, axis)))
    # a unit u ⟂ d and v = d × u
    u = np.array([0.0, d[2], -d[1]]) if abs(d[0]) < 0.9 else np.array([-d[2], 0.0, d[0]])
    u /= math.sqrt(float(u @ u))
    v = np.array([d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]])
    t = np.pi * np.arange(spokes) / spokes
    w = radius * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)
    c = np.asarray(centre, float)
    r = math.hypot(length / 2, radius * math.sin(math.pi / (2 * spokes)))
    return np.stack([c - w, c + w], axis=1), np.full(spokes, r)


@dataclass(frozen=True)
class Column:
    """A round post on the z axis from z0 to z1 (mm), radius mm; ``spokes`` for its capsule cover
    when it is a flat disc (a foot), 0 for one capsule along the axis (a post)."""

    z0: float
    z1: float
    radius: float
    spokes: int = 0


def capsules(bosses: list[Boss], bars: list[Bar], cups: list[Cup] = (), columns: list[Column] = ()
             ) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Capsules that contain the features: ((k, 2, 3) segment ends mm, (k,) radii mm, and for each
    capsule the index of its feature in bosses + bars + cups + columns). Bosses, cups and feet are
    covered by ``cylinder_capsules``; a bar by its capsule and the balls of its knees
    (``bar_paths``), and a post's core by one capsule (its caps reach a radius past its ends)."""
    ends, radii, owner = [], [], []
    for n, b in enumerate(bosses):
        e, r = cylinder_capsules(b.centre, np.asarray(b.axis, float), b.radius, b.length)
        ends.append(e)
        radii.append(r)
        owner += [n] * len(r)
    if bars:
        ends.append(np.array([[bar.p0, bar.p1] for bar in bars], float))
        radii.append(np.array([bar.radius for bar in bars], float))
        owner += list(range(len(bosses), len(bosses) + len(bars)))
        # a knee's ball (a knuckle, or what covers a mitre's outer corner), owned by its bar (Knee.bar)
        knees = bar_paths(bars, [b.centre for b in bosses])[1]
        if knees:
            ends.append(np.array([[k.point, k.point] for k in knees], float))
            radii.append(np.array([k.radius for k in knees], float))
            owner += [len(bosses) + k.bar for k in knees]
    for n, c in enumerate(cups):
        d = np.asarray(c.axis, float) / np.linalg.norm(c.axis)
        e, r = cylinder_capsules(np.asarray(c.point, float) + d * c.height / 2, d, c.outer_radius, c.height)
        ends.append(e)
        radii.append(r)
        owner += [len(bosses) + len(bars) + n] * len(r)
    for n, col in enumerate(columns):
        k = len(bosses) + len(bars) + len(cups) + n
        if col.spokes:
            e, r = cylinder_capsules(np.array([0.0, 0.0, (col.z0 + col.z1) / 2]), np.array([0.0, 0, 1]), col.radius,
                                     col.z1 - col.z0, col.spokes)
        else:
            e, r = np.array([[[0.0, 0, col.z0], [0.0, 0, col.z1]]]), np.array([col.radius])
        ends.append(e)
        radii.append(r)
        owner += [k] * len(r)
    if not ends:
        return np.zeros((0, 2, 3)), np.zeros(0), []
    return np.concatenate(ends).reshape(-1, 2, 3), np.concatenate(radii), owner


def base_solid(columns: list[Column], bore: tuple[float, float, float], segments: int = 48) -> m3d.Manifold:
    """A stand on the z axis: round columns (a foot, a post) united, a bore (radius, z0, z1) cut
    from z0 up through the top (open where the pin goes in)."""
    add = [m3d.Manifold.cylinder(c.z1 - c.z0, c.radius, -1.0, max(segments, 4 * c.spokes), False).translate((0, 0, c.z0))
           for c in columns]
    r, z0, z1 = bore
    cut = m3d.Manifold.cylinder(z1 - z0 + 0.4, r, -1.0, segments, False).translate((0, 0, z0))
    return m3d.Manifold.batch_boolean(add, m3d.OpType.Add) - cut


def tube(point, axis, r_in: float, r_out: float, start: float, end: float, segments: int = 48) -> m3d.Manifold:
    """A tube (r_in = 0: a rod) on the line (point, axis) from ``start`` to ``end`` mm along it."""
    pt, ax = np.asarray(point, float), np.asarray(axis, float)
    out = place_on_axis(m3d.Manifold.cylinder(end - start, r_out, -1.0, segments, True), pt, ax, (start + end) / 2)
    if r_in <= 0:
        return out
    return out - place_on_axis(m3d.Manifold.cylinder(end - start + 2, r_in, -1.0, segments, True), pt, ax,
                               (start + end) / 2)


def pin_solid(length: float, radius: float, segments: int = 48) -> m3d.Manifold:
    """A round pin along z, centred on the origin (a bought dowel, modelled for the assembly)."""
    return m3d.Manifold.cylinder(length, radius, -1.0, segments, True)
