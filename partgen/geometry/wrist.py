"""Solids of a spherical / quasi-ellipsoidal wrist gear pair: pitch bodies of revolution, dome
teeth on gear 1, and gear 2's sockets cut by sweeping gear 1's (grown) teeth over the workspace.

Frames: each gear's centre at its origin, its pole (the centre of its toothed cap) on local +z,
which points at the other gear when the wrist is straight. mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import manifold3d as m3d
import numpy as np

from .outline import segments_for
from .solid import cross_section

__all__ = ["Dome", "revolved_cap", "dome_teeth", "dome_solid", "domes_union", "socket_sweep"]


@dataclass(frozen=True)
class Dome:
    """A dome tooth: sphere centre (3,) mm in the gear's frame and radius mm."""

    centre: tuple[float, float, float]
    radius: float


def revolved_cap(radius_of: Callable[[np.ndarray], np.ndarray], alpha_max: float, base_z: float, shaft_r: float,
                 tol: float, samples: int = 200) -> m3d.Manifold:
    """Solid bounded by the meridian r(α) (α from the pole, 0..alpha_max) revolved about z, closed
    by a cone to a flat base at z = base_z, minus nothing: the caller adds bores.
    radius_of : α (n,) rad → r (n,) mm."""
    a = np.linspace(0.0, alpha_max, samples)
    r = radius_of(a)
    rho, z = r * np.sin(a), r * np.cos(a)
    pts = [(0.0, base_z)] + [(float(max(shaft_r, rho[-1])), base_z)] + list(zip(rho[::-1], z[::-1]))
    poly = np.array(pts)
    poly[:, 0] = np.maximum(poly[:, 0], 0.0)
    # counter-clockwise in (x = radius, y = z)
    area = 0.5 * np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1])
    if area < 0:
        poly = poly[::-1]
    segs = segments_for(float(rho.max()), tol, 64)
    return cross_section(poly).revolve(segs)


def dome_teeth(rows: Sequence[tuple[float, int]], radius_of: Callable[[np.ndarray], np.ndarray], dome_r: float,
               height: float, phase: float = 0.0) -> list[Dome]:
    """Domes on a pitch surface: rows (polar angle α, teeth on the ring); each dome's sphere sits
    on the surface normal so it stands ``height`` proud of the surface."""
    out = []
    h = 1e-6
    for alpha, n in rows:
        r = float(radius_of(np.array([alpha]))[0])
        dr = float((radius_of(np.array([alpha + h])) - radius_of(np.array([max(alpha - h, 0.0)])))[0]) / (
            alpha + h - max(alpha - h, 0.0))
        for m in range(n):
            psi = phase + 2 * math.pi * m / n
            e = np.array([math.cos(psi), math.sin(psi), 0.0])
            z = np.array([0.0, 0.0, 1.0])
            radial = math.sin(alpha) * e + math.cos(alpha) * z
            tangent = dr * radial + r * (math.cos(alpha) * e - math.sin(alpha) * z)
            normal = np.cross(tangent, np.cross(z, e)) if alpha > 1e-12 else z
            normal = normal / np.linalg.norm(normal)
            if np.dot(normal, radial) < 0:
                normal = -normal
            centre = r * radial - (dome_r - height) * normal
            out.append(Dome(tuple(float(c) for c in centre), dome_r))
    return out


def _ball(radius: float, segments: int, turn: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> m3d.Manifold:
    """A tessellated sphere about the origin, its facets turned by ``turn`` (deg about x, y, z)."""
    ball = m3d.Manifold.sphere(radius, segments)
    return ball.rotate(turn) if any(turn) else ball


def dome_solid(domes: Sequence[Dome], grow: float, segments: int, turn=(0.0, 0.0, 0.0)) -> list[m3d.Manifold]:
    return [_ball(d.radius + grow, segments, turn).translate(d.centre) for d in domes]


def domes_union(domes: Sequence[Dome], grow: float = 0.0, segments: int = 32, turn=(0.0, 0.0, 0.0)) -> m3d.Manifold:
    """All domes as one solid (radius + ``grow``); ``turn``: the spheres' facets turned (deg), the
    same domes tessellated differently."""
    return m3d.Manifold.batch_boolean(dome_solid(domes, grow, segments, turn), m3d.OpType.Add)


def socket_sweep(domes: Sequence[Dome], poses: np.ndarray, grow: float, reach: float, segments: int,
                 batch: int = 256, turn=(0.0, 0.0, 0.0)) -> tuple[m3d.Manifold, int]:
    """Union of gear 1's domes (radius + ``grow``) as seen from gear 2 over a grid of poses.

    poses : (a, b, 4, 4) gear-2-from-gear-1 transforms on an (θ, ψ) grid; consecutive θ of one ψ are
    joined by the convex hull of the two instances (a continuous sweep along θ).
    reach : domes whose centre lies farther than this from gear 2's centre cannot touch it and are
    skipped (the clip). Batches of ``batch`` pieces are unioned at a time (the batch), which keeps
    memory bounded. ``turn``: the spheres' facets turned (deg), the same sweep tessellated
    differently. Returns the swept solid and how many pieces went into it."""
    base = [np.array(d.centre) for d in domes]
    rads = [d.radius + grow for d in domes]
    pieces: list[m3d.Manifold] = []
    acc = None
    count = 0

    def flush():
        nonlocal acc, pieces
        if pieces:
            part = m3d.Manifold.batch_boolean(pieces, m3d.OpType.Add)
            acc = part if acc is None else m3d.Manifold.batch_boolean([acc, part], m3d.OpType.Add)
            pieces = []

    for b in range(poses.shape[1]):
        for k, (c, r) in enumerate(zip(base, rads)):
            prev = None
            for a in range(poses.shape[0]):
                T = poses[a, b]
                p = T[:3, :3] @ c + T[:3, 3]
                if np.linalg.norm(p) - r > reach:
                    prev = None
                    continue
                s = _ball(r, segments, turn).translate(tuple(p))
                pieces.append(s if prev is None else m3d.Manifold.batch_hull([prev, s]))
                count += 1
                prev = s
                if len(pieces) >= batch:
                    flush()
    flush()
    return (acc if acc is not None else m3d.Manifold()), count
