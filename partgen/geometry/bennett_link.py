"""Printable links of a Bennett linkage: two joint bosses on skew axes joined by a bar.

Link frame (the DH frame of its proximal joint after Rz(θ)): the proximal joint's axis is z through
the origin; the distal joint's axis passes through (a, 0, 0) in direction Rx(α)·z = (0, −sin α,
cos α) — a common normal of length a along x and a twist α. Each boss sits on its axis at an axial
offset (mm along that axis): stacked bosses of two links on one joint are kept apart by choosing
these offsets.
"""

from __future__ import annotations

import math

import manifold3d as m3d
import numpy as np

__all__ = ["skew_link", "distal_axis"]


def distal_axis(a: float, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """(point (3,), direction (3,)) of the distal joint axis in the link frame."""
    return np.array([a, 0.0, 0.0]), np.array([0.0, -math.sin(alpha), math.cos(alpha)])


def _boss(radius: float, length: float, bore: float, segments: int) -> m3d.Manifold:
    return m3d.Manifold.cylinder(length, radius, -1.0, segments, True)


def _place(solid: m3d.Manifold, point: np.ndarray, direction: np.ndarray, offset: float) -> m3d.Manifold:
    """Move a z-aligned solid so its axis is the line (point, direction), centred ``offset`` along it."""
    d = direction / np.linalg.norm(direction)
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(z, d)
    s, c = np.linalg.norm(axis), float(z @ d)
    if s < 1e-12:
        R = np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    else:
        k = axis / s
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = np.eye(3) + s * K + (1 - c) * K @ K
    T = np.column_stack([R, point + offset * d])
    return solid.transform(T)


def skew_link(a: float, alpha: float, boss_r: float, boss_len: float, bore_r: float, bar_r: float,
              offsets: tuple[float, float], segments: int = 48) -> m3d.Manifold:
    """A link: bosses (radius boss_r, length boss_len, bore bore_r through) on its proximal axis at
    offsets[0] and on its distal axis at offsets[1], joined by a round bar (radius bar_r) between
    the boss centres."""
    p1, d1 = distal_axis(a, alpha)
    b0 = _place(_boss(boss_r, boss_len, bore_r, segments), np.zeros(3), np.array([0.0, 0.0, 1.0]), offsets[0])
    b1 = _place(_boss(boss_r, boss_len, bore_r, segments), p1, d1, offsets[1])
    c0 = np.array([0.0, 0.0, offsets[0]])
    c1 = p1 + offsets[1] * d1 / np.linalg.norm(d1)
    ball = m3d.Manifold.sphere(bar_r, segments)
    bar = m3d.Manifold.batch_hull([ball.translate(tuple(c0)), ball.translate(tuple(c1))])
    long = boss_len * 4
    bores = [_place(m3d.Manifold.cylinder(long, bore_r, -1.0, segments, True), np.zeros(3), np.array([0.0, 0.0, 1.0]),
                    offsets[0]),
             _place(m3d.Manifold.cylinder(long, bore_r, -1.0, segments, True), p1, d1, offsets[1])]
    return m3d.Manifold.batch_boolean([b0, b1, bar], m3d.OpType.Add) - m3d.Manifold.batch_boolean(bores, m3d.OpType.Add)
