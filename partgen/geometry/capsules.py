"""Distances between capsules (segments with radii) — the fast, conservative stand-in for slender
parts in a motion sweep. Pure numpy; mm."""

from __future__ import annotations

import numpy as np

__all__ = ["segment_distance", "capsule_clearance"]


def segment_distance(p0: np.ndarray, p1: np.ndarray, q0: np.ndarray, q1: np.ndarray) -> np.ndarray:
    """(...,) closest distance between segments p0–p1 and q0–q1 (arrays (..., 3), broadcast)."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = np.einsum("...i,...i->...", d1, d1)
    e = np.einsum("...i,...i->...", d2, d2)
    f = np.einsum("...i,...i->...", d2, r)
    c = np.einsum("...i,...i->...", d1, r)
    b = np.einsum("...i,...i->...", d1, d2)
    denom = a * e - b * b
    tiny = 1e-12
    s = np.where(denom > tiny * np.maximum(a * e, tiny), np.clip((b * f - c * e) / np.where(denom > 0, denom, 1), 0, 1), 0.0)
    t = (b * s + f) / np.where(e > tiny, e, 1)
    # clamp t and recompute s where needed
    s = np.where(t < 0, np.clip(-c / np.where(a > tiny, a, 1), 0, 1), np.where(t > 1, np.clip((b - c) / np.where(a > tiny, a, 1), 0, 1), s))
    t = np.clip(t, 0, 1)
    # q a point (a zero-length capsule: a ball): the nearest point of p to it (t is 0 already)
    s = np.where((e <= tiny) & (a > tiny), np.clip(-c / np.where(a > tiny, a, 1), 0, 1), s)
    gap = p0 + d1 * s[..., None] - (q0 + d2 * t[..., None])
    return np.linalg.norm(gap, axis=-1)


def capsule_clearance(a_ends: np.ndarray, a_r: np.ndarray, b_ends: np.ndarray, b_r: np.ndarray) -> np.ndarray:
    """(n, ka, kb) clearance (mm, negative = overlap) between capsule sets a (n, ka, 2, 3) and b (n, kb, 2, 3)."""
    A, B = a_ends[:, :, None], b_ends[:, None, :]
    d = segment_distance(A[..., 0, :], A[..., 1, :], B[..., 0, :], B[..., 1, :])
    return d - a_r[None, :, None] - b_r[None, None, :]
