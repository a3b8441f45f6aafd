"""Rigid transforms, one module for all: rotations (3, 3), poses (4, 4) world-from-local, mm, rad.

Rotations about z are exact at quarter turns (cos 90° is 0, not 6e-17), so a part turned by 90°
on a build plate keeps its coordinates bit for bit.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["rot2", "rot_z", "rot_x", "rot_axis", "pose", "pose_z", "poses_z", "turn_about", "frame_z", "apply"]


def _cs(angle: float) -> tuple[float, float]:
    c, s = math.cos(angle), math.sin(angle)
    rc, rs = round(c), round(s)
    if abs(c - rc) < 1e-12:  # exact at quarter turns
        c = float(rc)
    if abs(s - rs) < 1e-12:
        s = float(rs)
    return c, s


def rot2(angle: float) -> np.ndarray:
    """(2, 2) rotation by ``angle`` rad (counter-clockwise)."""
    c, s = _cs(angle)
    return np.array([[c, -s], [s, c]])


def rot_z(angle) -> np.ndarray:
    """(3, 3) rotation about z; for an array of n angles, (n, 3, 3)."""
    t = np.asarray(angle, dtype=float)
    if t.ndim == 0:
        c, s = _cs(float(t))
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    c, s, z, o = np.cos(t), np.sin(t), np.zeros_like(t), np.ones_like(t)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def rot_x(angle: float) -> np.ndarray:
    """(3, 3) rotation about x."""
    c, s = _cs(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_axis(axis, angle: float) -> np.ndarray:
    """(3, 3) rotation by ``angle`` about the unit direction of ``axis`` (3,) (Rodrigues)."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    K = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * K @ K


def pose(R=None, t=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(4, 4) pose from a rotation (3, 3) (identity if None) and a translation (3,) mm."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    T[:3, 3] = t
    return T


def pose_z(x: float = 0.0, y: float = 0.0, z: float = 0.0, angle: float = 0.0) -> np.ndarray:
    """(4, 4): turned by ``angle`` about z, then moved to (x, y, z)."""
    c, s = _cs(angle)
    return np.array([[c, -s, 0.0, x], [s, c, 0.0, y], [0.0, 0.0, 1.0, z], [0.0, 0.0, 0.0, 1.0]])


def poses_z(x, y, z, angle) -> np.ndarray:
    """(N, 4, 4): ``pose_z`` for arrays of N values (each argument an (N,) array or a number),
    exact at quarter turns as ``pose_z`` is."""
    t = np.atleast_1d(np.asarray(angle, dtype=float))
    x, y, z = (np.asarray(v, dtype=float) for v in (x, y, z))
    n = max(len(t), *(v.size for v in (x, y, z)))
    c, s = np.cos(t), np.sin(t)
    rc, rs = np.round(c) + 0.0, np.round(s) + 0.0  # + 0.0: no negative zero (as Python's round)
    c = np.where(np.abs(c - rc) < 1e-12, rc, c)
    s = np.where(np.abs(s - rs) < 1e-12, rs, s)
    out = np.zeros((n, 4, 4))
    out[:, 0, 0], out[:, 0, 1], out[:, 1, 0], out[:, 1, 1] = c, -s, s, c
    out[:, 0, 3], out[:, 1, 3], out[:, 2, 3] = x, y, z
    out[:, 2, 2] = out[:, 3, 3] = 1.0
    return out


def turn_about(T: np.ndarray, axis, through, angle: float) -> np.ndarray:
    """(4, 4): the pose ``T`` followed by a turn of ``angle`` about the line along ``axis`` (3,)
    through the point ``through`` (3,) (world)."""
    R = rot_axis(axis, angle)
    p = np.asarray(through, dtype=float)
    out = np.eye(4)
    out[:3, :3] = R @ T[:3, :3]
    out[:3, 3] = R @ (T[:3, 3] - p) + p
    return out


def frame_z(origin, axis) -> np.ndarray:
    """(4, 4) frame at ``origin`` (3,) whose z is the unit direction of ``axis`` (3,); x is
    perpendicular to it and to y (or to x when the axis is near y)."""
    z = np.asarray(axis, dtype=float)
    z = z / np.linalg.norm(z)
    x = np.cross([0.0, 1.0, 0.0] if abs(z[1]) < 0.9 else [1.0, 0.0, 0.0], z)
    x /= np.linalg.norm(x)
    return pose(np.column_stack([x, np.cross(z, x), z]), origin)


def apply(T: np.ndarray, points) -> np.ndarray:
    """Points (n, 3) mm mapped by the pose T (4, 4)."""
    p = np.asarray(points, dtype=float)
    return p @ T[:3, :3].T + T[:3, 3]
