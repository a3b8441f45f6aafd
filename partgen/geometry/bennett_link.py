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

__all__ = ["skew_link", "distal_axis", "place_on_axis", "Boss", "Bar", "Cup", "Column", "link_solid", "base_solid", "capsules",
           "cylinder_capsules", "tube", "pin_solid"]


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


# Consecutive bars of a bent bar share an end point, where the capsules are tangent to each
# other's balls: equal balls leave the same sphere patch in both hulls and the union can pinch
# (bodies touching at a vertex: not one shell once written; 3 of the first 23 Bennett sweep
# designs). The first bar to reach a point keeps its ball, a later one ends in a ball
# SHARED_END_INSET_MM smaller, strictly inside it. Its tube then crosses that ball at a shallow
# angle, the smaller the inset the shallower: with 0.02 mm one design of 57 still wrote a sliver.
SHARED_END_INSET_MM = 0.1  # far above float32 resolution at print size (~1e-5 mm), under a print's


def link_solid(bosses: list[Boss], bars: list[Bar], cups: list[Cup] = (), segments: int = 48) -> m3d.Manifold:
    """A link as one solid: bosses, bars and cups united, then every bore and pocket cut."""
    return _link_solid(bosses, bars, cups, segments, SHARED_END_INSET_MM)


def _link_solid(bosses, bars, cups, segments: int, inset: float) -> m3d.Manifold:
    add = [place_on_axis(m3d.Manifold.cylinder(b.length, b.radius, -1.0, segments, True), np.asarray(b.point, float),
                  np.asarray(b.axis, float), b.offset) for b in bosses]
    owned: set[tuple] = set()
    for bar in bars:
        ends = []
        for pt in (bar.p0, bar.p1):
            key = tuple(round(float(x), 9) for x in pt)
            ends.append(m3d.Manifold.sphere(bar.radius - (inset if key in owned else 0.0), segments)
                        .translate(tuple(map(float, pt))))
            owned.add(key)
        add.append(m3d.Manifold.batch_hull(ends))
    for c in cups:
        add.append(place_on_axis(m3d.Manifold.cylinder(c.height, c.outer_radius, -1.0, segments, False), np.asarray(c.point, float),
                          np.asarray(c.axis, float), 0.0))
    # bores run a little past the faces (bars meeting a boss end within its faces: bar radius ≤ half its length)
    cut = [place_on_axis(m3d.Manifold.cylinder(b.length + 0.4, b.bore_radius, -1.0, segments, True), np.asarray(b.point, float),
                  np.asarray(b.axis, float), b.offset) for b in bosses]
    for c in cups:
        start = c.height - c.pocket_depth
        cut.append(place_on_axis(m3d.Manifold.cylinder(c.pocket_depth + 0.1, c.pocket_radius, -1.0, segments, False),
                          np.asarray(c.point, float), np.asarray(c.axis, float), start))
    return m3d.Manifold.batch_boolean(add, m3d.OpType.Add) - m3d.Manifold.batch_boolean(cut, m3d.OpType.Add)


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
    covered by ``cylinder_capsules``; a bar is a capsule exactly, and so is a post's core (its
    caps reach a radius past its ends)."""
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
