"""Spherical and quasi-ellipsoidal gear pairs of a 2-DoF wrist (Jiang, Zhou, Li 1998) — pure math,
mm and rad.

Gear 1's pitch surface is the meridian r1(θ) revolved about its axis, gear 2's r2(φ) about its
own; at a bend they touch at polar angles θ on gear 1 and φ on gear 2. The paper's ratio ODE

    di/dθ = i·(√(1 − (i sin θ)²) − cos θ) / sin θ,   i(0) = I,  i′(0) = 0

is what the latitude condition sin φ = i sin θ becomes once φ also keeps equal meridian arcs,
dφ/dθ = i: then dφ/sin φ = dθ/sin θ, which integrates exactly to

    tan(φ/2) = I·tan(θ/2),   i(θ) = dφ/dθ = I / (cos²(θ/2) + I² sin²(θ/2)).

The ODE's root is the positive one, i.e. cos φ ≥ 0: it holds up to φ = π/2, where i sin θ = 1 and
the right-hand side is singular — θ_end = 2·arctan(1/I). Past it the paper's ODE no longer
describes the surfaces; the functions here refuse θ beyond θ_end. I = 1 gives φ = θ, i ≡ 1:
two spheres of radius A/2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from functools import lru_cache

import numpy as np

from ..core.transforms import rot_axis

__all__ = ["WristPair", "valid_end", "ratio", "ratio_ode", "mating_angle_meridian", "mating_angle_latitude",
           "pitch_radii", "gear2_pose", "meridian_arc", "tooth_rows", "RangeError"]


class RangeError(ValueError):
    """A polar angle beyond the end of the valid range (φ would pass π/2)."""


def valid_end(I: float) -> float:
    """θ_end = 2 arctan(1/I), rad: where φ reaches π/2 and i sin θ = 1."""
    if I <= 0:
        raise ValueError(f"nominal ratio I must be > 0, got {I}")
    return 2 * math.atan(1 / I)


def _check(theta, I):
    theta = np.asarray(theta, dtype=float)
    end = valid_end(I)
    if np.any(theta < 0) or np.any(theta > end + 1e-12):
        raise RangeError(f"θ must lie in [0, {end:.9f}] rad for I = {I} (φ reaches π/2 at its end); "
                         f"got up to {float(np.max(theta)):.9f}")
    return theta


def ratio(theta, I: float) -> np.ndarray:
    """i(θ) in closed form; theta : (n,) rad in [0, θ_end]."""
    t = _check(theta, I)
    return I / (np.cos(t / 2) ** 2 + I * I * np.sin(t / 2) ** 2)


def ratio_ode(theta_end: float, I: float, steps: int = 2000) -> tuple[np.ndarray, np.ndarray]:
    """i(θ) by integrating the paper's ODE (classical RK4) from θ = 0 to ``theta_end``.

    The start is singular (0/0): the right-hand side → 0 as θ → 0 (i′(0) = 0), so the integrator
    uses its limit there. At θ_end itself the square root reaches 0 and the step is taken up to
    it, not over it. Returns theta (steps + 1,), i (steps + 1,)."""
    _check(theta_end, I)

    def f(t, i):
        if t < 1e-12:
            return 0.0
        return i * (math.sqrt(max(0.0, 1 - (i * math.sin(t)) ** 2)) - math.cos(t)) / math.sin(t)

    # steps shrink toward θ_end, where √(1 − (i sin θ)²) → 0 and i′ grows without bound
    s = np.linspace(0.0, 1.0, steps + 1)
    ts = theta_end * (1 - (1 - s) ** 2)
    out = np.empty_like(ts)
    i = float(I)
    out[0] = i
    for k in range(steps):
        t, h = ts[k], ts[k + 1] - ts[k]
        k1 = f(t, i)
        k2 = f(t + h / 2, i + h / 2 * k1)
        k3 = f(t + h / 2, i + h / 2 * k2)
        k4 = f(t + h, i + h * k3)
        i += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out[k + 1] = i
    return ts, out


def mating_angle_meridian(theta, I: float, nodes: int = 64) -> np.ndarray:
    """φ = ∫₀^θ i dθ (equal arcs along the meridians), by Gauss–Legendre quadrature of i."""
    t = np.atleast_1d(_check(theta, I))
    x, w = _gauss_legendre(nodes)
    out = np.empty_like(t)
    for k, tk in enumerate(t):
        s = tk / 2 * (x + 1)
        out[k] = tk / 2 * float(np.sum(w * ratio(s, I)))
    return out if np.ndim(theta) else out[0]


def mating_angle_latitude(theta, I: float) -> np.ndarray:
    """φ = arcsin(i sin θ) (equal arcs along the latitudes).

    Near the end of the range i sin θ → 1 and arcsin loses half the digits, so cos φ is taken
    from 1 − i sin θ = (cos(θ/2) − I sin(θ/2))² / (cos²(θ/2) + I² sin²(θ/2)), exact for this i."""
    t = _check(theta, I)
    c, s = np.cos(t / 2), np.sin(t / 2)
    den = c * c + I * I * s * s
    x = ratio(t, I) * np.sin(t)
    one_minus = (c - I * s) ** 2 / den
    return np.arctan2(x, np.sqrt(one_minus * (1 + x)))


def mating_angle(theta, I: float) -> np.ndarray:
    """φ = 2 arctan(I tan(θ/2)), the closed form both of the above equal."""
    t = _check(theta, I)
    return 2 * np.arctan(I * np.tan(t / 2))


def pitch_radii(theta, I: float, A: float) -> tuple[np.ndarray, np.ndarray]:
    """r1(θ) = A i/(1 + i) and r2(φ(θ)) = A/(1 + i), mm: the two meridians at the contact."""
    i = ratio(theta, I)
    return A * i / (1 + i), A / (1 + i)


def gear2_pose(theta: float, psi: float, I: float, A: float) -> np.ndarray:
    """(4, 4) pose of gear 2 for a bend (θ, ψ), gear 1 fixed with its axis on +z at the origin.

    Gear 2's centre lies at distance A in the direction of polar angle θ, azimuth ψ; its axis is
    bent by θ + φ from gear 1's in the plane at azimuth ψ. In its own frame gear 2's pole (its
    cap's centre) is on its −z axis... flipped so that its local +z points at gear 1: local +z
    (the pole direction) maps to −(sin(θ+φ) cos ψ, sin(θ+φ) sin ψ, cos(θ+φ))."""
    phi = float(mating_angle(theta, I))
    u = np.array([math.sin(theta) * math.cos(psi), math.sin(theta) * math.sin(psi), math.cos(theta)])
    n = np.array([-math.sin(psi), math.cos(psi), 0.0])
    flip = np.diag([1.0, -1.0, -1.0])  # half a turn about x: local +z points back at gear 1
    T = np.eye(4)
    T[:3, :3] = rot_axis(n, theta + phi) @ flip
    T[:3, 3] = A * u
    return T


@lru_cache(maxsize=8)
def _gauss_legendre(nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [-1, 1] (an eigenvalue problem: computed once per n)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    x.flags.writeable = w.flags.writeable = False
    return x, w


def meridian_arc(theta, I: float, A: float, gear: int = 1, nodes: int = 64) -> np.ndarray:
    """Arc length (mm) along a meridian from the pole to polar angle θ on gear 1 (gear = 1), or to
    its mate φ(θ) on gear 2 (gear = 2): ∫ √(r² + (dr/dα)²) dα."""
    t = np.atleast_1d(_check(theta, I))
    x, w = _gauss_legendre(nodes)
    out = np.empty_like(t)
    for k, tk in enumerate(t):
        s = tk / 2 * (x + 1)
        h = 1e-6
        r1, r2 = pitch_radii(s, I, A)
        if gear == 1:
            d = (pitch_radii(np.clip(s + h, 0, valid_end(I)), I, A)[0] - pitch_radii(np.clip(s - h, 0, None), I, A)[0]) / (
                np.clip(s + h, 0, valid_end(I)) - np.clip(s - h, 0, None))
            out[k] = tk / 2 * float(np.sum(w * np.hypot(r1, d)))
        else:
            # along gear 2 the variable is φ: dφ = i dθ
            i = ratio(s, I)
            sp, sm = np.clip(s + h, 0, valid_end(I)), np.clip(s - h, 0, None)
            dr2 = (pitch_radii(sp, I, A)[1] - pitch_radii(sm, I, A)[1]) / (mating_angle(sp, I) - mating_angle(sm, I))
            out[k] = tk / 2 * float(np.sum(w * np.hypot(r2, dr2) * i))
    return out if np.ndim(theta) else out[0]


@dataclass(frozen=True)
class Row:
    """One ring of teeth: its index k (0 = the centre tooth), teeth on it, polar angle on gear 1
    and its mate on gear 2 (rad), and the latitudinal pitch on each gear (mm)."""

    k: int
    teeth: int
    theta: float
    phi: float
    lat_pitch_1: float
    lat_pitch_2: float


@dataclass(frozen=True)
class WristPair:
    I: float
    A: float
    rows: tuple[Row, ...]
    long_pitch: float


def tooth_rows(I: float, A: float, long_pitch: float, ring_teeth=(1, 6, 12)) -> WristPair:
    """Rings of teeth at equal meridional arc length ``long_pitch`` apart on both gears (so rows
    meet rows), and the latitudinal pitch each ring then has on each gear."""
    rows = []
    end = valid_end(I)
    for k, n in enumerate(ring_teeth):
        target = k * long_pitch
        lo, hi = 0.0, end
        if target > meridian_arc(end, I, A):
            raise RangeError(f"ring {k} at {target:.3f} mm of arc lies past the valid range ({meridian_arc(end, I, A):.3f} mm)")
        for _ in range(80):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if meridian_arc(mid, I, A) < target else (lo, mid)
        th = (lo + hi) / 2
        ph = float(mating_angle(th, I))
        r1, r2 = pitch_radii(th, I, A)
        lat1 = 2 * math.pi * float(r1) * math.sin(th) / n if k else 0.0
        lat2 = 2 * math.pi * float(r2) * math.sin(ph) / n if k else 0.0
        rows.append(Row(k, n, th, ph, lat1, lat2))
    return WristPair(I, A, tuple(rows), long_pitch)
