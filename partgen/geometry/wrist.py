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


def _rz(deg: float) -> np.ndarray:
    t = math.radians(deg)
    return np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0], [0.0, 0.0, 1.0]])


def _copy_of(centres: np.ndarray, base: np.ndarray, step_deg: float) -> float | None:
    """The turn β (deg) about z with Rz(−β)·base[:, b] = centres[:, b + s] for every pose (s = β / step,
    the ψ columns shifted cyclically), or None: then the dome's sweep is the base dome's turned
    by −β. Tested on the numbers, so it holds for any pose grid that has the symmetry."""
    c0, b0 = centres[0, 0], base[0, 0]
    if abs(np.hypot(*c0[:2]) - np.hypot(*b0[:2])) > 1e-9 or abs(c0[2] - b0[2]) > 1e-9 or np.hypot(*c0[:2]) < 1e-9:
        return None
    for s in range(1, centres.shape[1]):
        beta = s * step_deg
        moved = base @ _rz(-beta).T
        if np.allclose(np.roll(centres, -s, axis=1), moved, atol=1e-9, rtol=0.0):
            return beta
    return None


def socket_sweep(domes: Sequence[Dome], poses: np.ndarray, grow: float, reach: float, segments: int,
                 batch: int = 256, turn=(0.0, 0.0, 0.0)) -> tuple[m3d.Manifold, int]:
    """Union of gear 1's domes (radius + ``grow``) as seen from gear 2 over a grid of poses.

    poses : (a, b, 4, 4) gear-2-from-gear-1 transforms on an (θ, ψ) grid, ψ evenly spaced over a
    turn; consecutive θ of one ψ are joined by the convex hull of the two instances (a continuous
    sweep along θ).
    reach : domes whose centre lies farther than this from gear 2's centre cannot touch it and are
    skipped (the clip). Each dome's pieces are unioned on their own (they lie together, so the
    union is cheap), then the domes' sweeps are unioned. A dome whose path over the grid is another
    dome's turned about z (a ring's teeth on a ψ grid that steps through their spacing: tested on
    the numbers, ``_copy_of``) takes that dome's sweep turned instead of being swept again.
    ``batch``: kept for callers; the grouping is per dome. ``turn``: the spheres' facets turned
    (deg), the same sweep tessellated differently. Returns the swept solid and how many pieces
    went into it (copies counted as their pieces)."""
    del batch
    A, B = poses.shape[:2]
    step_deg = 360.0 / B
    sweeps: list[m3d.Manifold] = []
    done: list[tuple[np.ndarray, m3d.Manifold, int]] = []  # (centres, sweep, pieces) of domes swept
    count = 0
    for d in domes:
        r = d.radius + grow
        c = np.asarray(d.centre, dtype=float)
        centres = np.einsum("abij,j->abi", poses[:, :, :3, :3], c) + poses[:, :, :3, 3]  # (A, B, 3)
        copied = None
        for base, sweep, n in done:
            beta = _copy_of(centres, base, step_deg)
            if beta is not None:
                copied = (sweep.rotate((0.0, 0.0, -beta)), n)
                break
        if copied is not None:
            sweeps.append(copied[0])
            count += copied[1]
            continue
        pieces = []
        ball = _ball(r, segments, turn)
        for b in range(B):
            prev = None
            for a in range(A):
                p = centres[a, b]
                if np.linalg.norm(p) - r > reach:
                    prev = None
                    continue
                s = ball.translate(tuple(p))
                pieces.append(s if prev is None else m3d.Manifold.batch_hull([prev, s]))
                prev = s
        count += len(pieces)
        sweep = m3d.Manifold.batch_boolean(pieces, m3d.OpType.Add) if pieces else m3d.Manifold()
        done.append((centres, sweep, len(pieces)))
        sweeps.append(sweep)
    sweeps = [s for s in sweeps if not s.is_empty()]
    return (m3d.Manifold.batch_boolean(sweeps, m3d.OpType.Add) if sweeps else m3d.Manifold()), count
