"""A gear rack: its outline (the basic rack profile itself, teeth up) and its mesh with a pinion
(pure math: mm, rad).

The rack's reference (pitch) line is y = 0, its teeth point +y: straight flanks at the pressure angle
α, tip flat at y = h_a m, root flat at y = −h_f m with fillets of radius ρ m tangent to flank and
root, tooth thickness at the pitch line π m / 2 less the rack's thinning (its backlash share). A
pinion of shift x meshes it with its centre r_p + x m above the pitch line; turning by θ it moves
the rack r_p θ (the pitch circle rolls on the pitch line).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["rack_outline", "rack_contact_ratio", "rack_tip_width"]


def _arc(centre, radius: float, a0: float, a1: float, tol: float) -> np.ndarray:
    span = abs(a1 - a0)
    n = max(2, math.ceil(span / (2 * math.acos(max(1 - tol / radius, -1.0)))) + 1) if radius > 0 else 2
    t = np.linspace(a0, a1, n)
    return np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)])


def rack_tip_width(m: float, alpha: float, thinning: float = 0.0, ha: float = 1.0) -> float:
    """Width (mm) of a rack tooth's tip flat: π m / 2 − thinning − 2 h_a m tan α."""
    return math.pi * m / 2 - thinning - 2 * ha * m * math.tan(alpha)


def rack_outline(teeth: int, m: float, alpha: float, thinning: float = 0.0, ha: float = 1.0, hf: float = 1.25,
                 rho: float = 0.38, back: float = 6.0, tol: float = 0.01) -> np.ndarray:
    """(n, 2) float, mm, counter-clockwise: a rack of ``teeth`` teeth centred on x = 0 (tooth k at
    (k − (teeth − 1)/2) π m), pitch line y = 0, teeth up, its body ``back`` mm under the root line,
    half a space of root flat beyond each end tooth."""
    p = math.pi * m
    s = p / 2 - thinning
    ta, ca, sa = math.tan(alpha), math.cos(alpha), math.sin(alpha)
    yr, yt = -hf * m, ha * m
    R = rho * m
    # fillet right of tooth 0: tangent to the root line and the flank x cos α + y sin α = (s/2) cos α
    yc = yr + R
    xc = (R + s / 2 * ca - sa * yc) / ca
    if xc > p / 2:  # the two fillets of a space would overlap: the largest that fits
        R = (p / 2 * ca - s / 2 * ca + sa * yr) / (1 - sa)
        yc = yr + R
        xc = p / 2
    fl = (xc - R * ca, yc - R * sa)  # where the fillet meets the flank
    if fl[1] >= yt:
        raise ValueError("the rack's root fillets reach its tip: a smaller cutter_tip_coeff")
    right = np.vstack([[[s / 2 - yt * ta, yt]], [fl], _arc((xc, yc), R, math.pi + alpha, 1.5 * math.pi, tol)[1:]])
    left = (right * [-1, 1])[::-1]
    tooth = np.vstack([left, right])  # root (left) → flank → tip → flank → root (right)
    xs = (np.arange(teeth) - (teeth - 1) / 2) * p
    body = np.vstack([tooth + [x, 0.0] for x in xs])
    x0, x1 = xs[0] - p / 2, xs[-1] + p / 2
    yb = yr - back
    pts = np.vstack([[[x0, yr]], body, [[x1, yr], [x1, yb], [x0, yb]]])
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.hypot(*np.diff(pts, axis=0).T) > 1e-9
    pts = pts[keep]
    # ccw: the walk above runs left to right along the top (clockwise seen from +z): reverse it
    return np.ascontiguousarray(pts[::-1])


def rack_contact_ratio(z: int, m: float, alpha: float, x: float = 0.0, ha_pinion: float = 1.0,
                       ha_rack: float = 1.0) -> float:
    """Transverse contact ratio of a pinion (z, x) with a rack: (√(r_a² − r_b²) − r_p sin α +
    (h_a,rack − x) m / sin α) / (π m cos α)."""
    rp = m * z / 2
    rb = rp * math.cos(alpha)
    ra = rp + (ha_pinion + x) * m
    return (math.sqrt(ra * ra - rb * rb) - rp * math.sin(alpha) + (ha_rack - x) * m / math.sin(alpha)) / (
        math.pi * m * math.cos(alpha))
