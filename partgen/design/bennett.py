"""A Bennett linkage in closed form (pure math, mm and rad) — the building block of the balanced
butterfly linkage (van der Wijk 2020).

Standard DH, ``T_i = Rz(θ_i)·Tx(a_i)·Rx(α_i)``, links (a, α), (b, β), (a, α), (b, β) around the
loop. The Bennett condition ``a / sin α = b / sin β`` makes the spatial 4R loop movable with one
degree of freedom, and then

    θ3 = −θ1,  θ4 = −θ2  (mod 2π),   tan(θ1/2)·tan(θ2/2) = sin((β + α)/2) / sin((β − α)/2).

(Verified here by loop closure: T1·T2·T3·T4 = I to ~1e-13.) With all twists zero it is the planar
parallelogram: θ2 = π − θ1, θ3 = θ1, θ4 = θ2.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import DesignError

__all__ = ["dh", "bennett_b", "check_bennett", "joint_angles", "loop", "joint_frames"]


def dh(theta: float, a: float, alpha: float) -> np.ndarray:
    """(4, 4) Rz(θ)·Tx(a)·Rx(α)."""
    c, s, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[c, -s * ca, s * sa, a * c], [s, c * ca, -c * sa, a * s], [0, sa, ca, 0], [0, 0, 0, 1.0]])


def bennett_b(a: float, alpha: float, beta: float) -> float:
    """The b that makes (a, α, b, β) a Bennett linkage: b = a sin β / sin α."""
    if abs(math.sin(alpha)) < 1e-12:
        raise DesignError("a Bennett linkage needs a non-zero twist α (all twists zero is the planar case)")
    return a * math.sin(beta) / math.sin(alpha)


def check_bennett(a: float, b: float, alpha: float, beta: float, key: str = "", tol: float = 1e-9) -> None:
    """Raise DesignError unless (a, b, α, β) meets a/sin α = b/sin β (or is planar: α = β = 0)."""
    if a <= 0 or b <= 0:
        raise DesignError(f"link lengths must be positive, got a = {a}, b = {b}", key)
    if abs(alpha) < 1e-15 and abs(beta) < 1e-15:
        return
    if abs(math.sin(alpha)) < 1e-12 or abs(math.sin(beta)) < 1e-12:
        raise DesignError("one twist is zero and the other is not: no Bennett linkage", key)
    lhs, rhs = a / math.sin(alpha), b / math.sin(beta)
    if abs(lhs - rhs) > tol * max(abs(lhs), 1.0):
        raise DesignError(f"breaks the Bennett condition a/sin α = b/sin β: {lhs:.9g} ≠ {rhs:.9g} "
                          f"(for these twists b must be {a * math.sin(beta) / math.sin(alpha):.6g} mm)", key)
    if abs(math.sin((beta - alpha) / 2)) < 1e-12:
        raise DesignError("α = β: the Bennett relation degenerates (the links fold)", key)


def joint_angles(theta1: np.ndarray, alpha: float, beta: float) -> np.ndarray:
    """(n, 4) joint angles for input angles θ1 : (n,) rad."""
    t1 = np.atleast_1d(np.asarray(theta1, dtype=float))
    if abs(alpha) < 1e-15 and abs(beta) < 1e-15:
        t2 = np.pi - t1
        return np.column_stack([t1, t2, t1, t2])
    k = math.sin((beta + alpha) / 2) / math.sin((beta - alpha) / 2)
    t2 = 2 * np.arctan2(k * np.cos(t1 / 2), np.sin(t1 / 2))  # tan(θ2/2) = k / tan(θ1/2), quadrant kept
    return np.column_stack([t1, t2, -t1, -t2])


def loop(angles: np.ndarray, a: float, b: float, alpha: float, beta: float) -> np.ndarray:
    """(4, 4) T1·T2·T3·T4 for one row of joint angles (the identity when the loop closes)."""
    M = np.eye(4)
    for th, (l, tw) in zip(angles, ((a, alpha), (b, beta), (a, alpha), (b, beta))):
        M = M @ dh(float(th), l, tw)
    return M


def joint_frames(angles: np.ndarray, a: float, b: float, alpha: float, beta: float) -> list[np.ndarray]:
    """(4, 4) frames of the four joint axes (z) for one row of joint angles, joint 1 at the origin."""
    out, M = [np.eye(4)], np.eye(4)
    for th, (l, tw) in list(zip(angles, ((a, alpha), (b, beta), (a, alpha), (b, beta))))[:3]:
        M = M @ dh(float(th), l, tw)
        out.append(M.copy())
    return out
