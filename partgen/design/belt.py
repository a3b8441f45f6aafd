"""Timing-belt stages: pulley teeth for the Eq 11 ratio, a stock closed belt (whole teeth), and
a backside tensioner that takes up the difference so the link keeps its designed length (pure
math, mm and rad).

Belt path: a closed loop around circles, each wrapped counter-clockwise (``wrap`` +1: the circle
lies left of the belt's travel, a pulley inside the loop) or clockwise (-1: a backside idler
outside it), in travel order. A straight span leaves circle i and meets circle i+1 tangentially.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

import numpy as np

from ..errors import DesignError
from .drivetrain import ratio_multiples

__all__ = ["BeltProfile", "Pulley", "BeltStage", "pitch_diameter", "open_length", "centre_distance_for", "belt_path",
           "design_belt_stage"]


@dataclass(frozen=True)
class BeltProfile:
    """A timing belt: pitch, the pulley's pitch-line offset (pitch radius − outside radius), the
    groove depth and radius of a pulley tooth space, the belt's height from its pitch line to
    its back, and its width (mm)."""

    name: str = "GT2"
    pitch: float = 2.0
    pitch_line_offset: float = 0.254
    groove_depth: float = 0.75
    groove_radius: float = 0.555
    back_height: float = 0.63
    width: float = 6.0


@dataclass(frozen=True)
class Pulley:
    teeth: int
    profile: BeltProfile

    @property
    def pitch_radius(self) -> float:
        return pitch_diameter(self.teeth, self.profile.pitch) / 2

    @property
    def outside_radius(self) -> float:
        return self.pitch_radius - self.profile.pitch_line_offset

    @property
    def root_radius(self) -> float:
        return self.outside_radius - self.profile.groove_depth


@dataclass(frozen=True)
class BeltStage:
    """Link j's belt stage in its frame (proximal joint at 0, distal at (length, 0))."""

    j: int
    length: float  # the link's centre distance as built (changed only when there is no tensioner)
    ratio: Fraction
    D: Pulley
    G: Pulley
    belt_teeth: int
    open_length: float  # belt over the two pulleys alone at ``length``
    tensioner: tuple[float, float] | None
    tensioner_radius: float
    path_length: float  # the belt's pitch path as assembled: belt_teeth × pitch
    link_change: float  # length − the design's S (0 with a tensioner)
    link_change_without_tensioner: float
    settings: object = None  # the BeltSettings it was designed with (flanges, tensioner)

    @property
    def slack(self) -> float:
        """Belt length the tensioner takes up, mm."""
        return self.belt_teeth * self.D.profile.pitch - self.open_length


def pitch_diameter(teeth: int, pitch: float) -> float:
    return teeth * pitch / math.pi


def open_length(r1: float, r2: float, c: float) -> float:
    """Length of a belt over two pulleys of pitch radii r1, r2 at centre distance c (no idler)."""
    beta = math.asin((r1 - r2) / c)
    return 2 * c * math.cos(beta) + math.pi * (r1 + r2) + 2 * beta * (r1 - r2)


def centre_distance_for(belt: float, r1: float, r2: float, lo: float) -> float:
    """Centre distance (mm, above ``lo``) at which a belt of length ``belt`` fits two pulleys of
    pitch radii r1, r2 with no idler (``open_length`` grows with the distance: bisection)."""
    hi = max(lo, belt)
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if open_length(r1, r2, mid) < belt else (lo, mid)
    return (lo + hi) / 2


def _left(t: np.ndarray) -> np.ndarray:
    return np.array([-t[1], t[0]])


def belt_path(circles: Sequence[tuple[tuple[float, float], float, int]], arc_step: float = 0.5
              ) -> tuple[float, np.ndarray]:
    """Length (mm) and pitch-line polyline ((n, 2) mm, closed, travel order) of a belt around
    ``circles`` = [(centre, radius, wrap ±1), …] in travel order."""
    n = len(circles)
    spans = []
    for i in range(n):
        (c1, r1, w1), (c2, r2, w2) = circles[i], circles[(i + 1) % n]
        c1, c2 = np.asarray(c1, float), np.asarray(c2, float)
        rho1, rho2 = w1 * r1, w2 * r2
        d = c2 - c1
        D = float(np.hypot(*d))
        cos_psi = (rho2 - rho1) / D
        if abs(cos_psi) > 1:
            raise ValueError("circles overlap: no tangent between them")
        psi = math.acos(cos_psi)
        phi = math.atan2(d[1], d[0]) + psi
        N = np.array([math.cos(phi), math.sin(phi)])
        spans.append((c1 - rho1 * N, c2 - rho2 * N))
    length, pts = 0.0, []
    for i in range(n):
        c, r, w = circles[i]
        c = np.asarray(c, float)
        arrive, leave = spans[i - 1][1], spans[i][0]
        a0 = math.atan2(*(arrive - c)[::-1])
        a1 = math.atan2(*(leave - c)[::-1])
        sweep = (a1 - a0) % (2 * math.pi) if w > 0 else -((a0 - a1) % (2 * math.pi))
        length += abs(sweep) * r
        k = max(2, int(math.ceil(abs(sweep) * r / arc_step)) + 1)
        t = a0 + sweep * np.linspace(0, 1, k)
        pts.append(np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)]))
        length += float(np.hypot(*(spans[i][1] - spans[i][0])))
    return length, np.vstack(pts)


def _tensioner(length: float, rd: float, rg: float, r_e: float, target: float, side: int, gap: float,
               clear: tuple[float, float], r_roller: float | None = None) -> tuple[float, float] | None:
    """Centre of a backside idler (effective radius r_e) on the span on ``side`` (-1 below the
    link, +1 above) at mid-link, pushed in until the belt path is ``target`` long. None if it
    cannot take up that much without its flanges (radius ``r_roller``, default r_e) coming within
    ``gap`` of a pulley's flange (radii ``clear``): they turn in the same layers."""
    u = length / 2

    def path_len(v):
        circles = [((0.0, 0.0), rd, 1), ((u, v), r_e, -1), ((length, 0.0), rg, 1)]
        if side > 0:
            circles = [((length, 0.0), rg, 1), ((u, v), r_e, -1), ((0.0, 0.0), rd, 1)]
        try:
            return belt_path(circles)[0]
        except ValueError:  # pushed through a pulley
            return math.inf

    r_span = (rd + rg) / 2
    v_out = side * (r_span + r_e + 1e-6)  # just touching the straight span
    v_in = side * (r_e - r_span) * 0.0  # pushed to the link's centre line
    if path_len(v_out) > target:
        return None
    lo, hi = v_out, v_in
    if path_len(hi) < target:
        return None
    for _ in range(80):
        mid = (lo + hi) / 2
        if path_len(mid) < target:
            lo = mid
        else:
            hi = mid
    v = (lo + hi) / 2
    r_idler = r_e if r_roller is None else r_roller
    for (cx, r_fl) in ((0.0, clear[0]), (length, clear[1])):
        if math.hypot(u - cx, v) < r_idler + r_fl + gap:
            return None
    return (u, v)


def design_belt_stage(j: int, length: float, ratio: Fraction, profile: BeltProfile, stock_teeth: Sequence[int],
                      min_teeth: int, flange: float, idler_radius: float, gap: float, side: int) -> BeltStage:
    """Pulleys giving ``ratio`` exactly, the shortest stock belt that is long enough, and the
    tensioner that takes up its slack. Among pulley sizes, the smallest that work.
    Raises DesignError when nothing fits the link."""
    stock = sorted(set(int(t) for t in stock_teeth))
    r_e = idler_radius + profile.back_height
    tried = []
    for zd, zg in ratio_multiples(ratio, min_teeth):
        D, G = Pulley(zd, profile), Pulley(zg, profile)
        fd, fg = D.outside_radius + flange, G.outside_radius + flange
        if fd + fg + gap > length:
            break
        lo = open_length(D.pitch_radius, G.pitch_radius, length)
        for teeth in stock:
            L = teeth * profile.pitch
            if L < lo:
                continue
            pos = _tensioner(length, D.pitch_radius, G.pitch_radius, r_e, L, side, gap, (fd, fg),
                             max(r_e, idler_radius + flange))
            tried.append((zd, zg, teeth, pos is not None))
            if pos is None:
                break  # a longer belt needs a deeper push: no better
            # without a tensioner the link would have to change to the belt's centre distance
            c_free = centre_distance_for(L, D.pitch_radius, G.pitch_radius, length)
            circles = [((0.0, 0.0), D.pitch_radius, 1), (pos, r_e, -1), ((length, 0.0), G.pitch_radius, 1)]
            if side > 0:
                circles = [circles[2], circles[1], circles[0]]
            try:
                path = belt_path(circles)[0]
            except ValueError as e:
                raise DesignError(f"link {j} (S = {length:.3f} mm): the belt cannot be routed round its pulleys and "
                                  f"tensioner ({e}): check the belt profile", "belts") from None
            return BeltStage(j, length, ratio, D, G, teeth, lo, pos, idler_radius, path, 0.0, c_free - length)
    # no tensioner fits: change the link to the centre distance of the stock belt that needs the
    # smallest change
    best = None
    for zd, zg in ratio_multiples(ratio, min_teeth):
        D, G = Pulley(zd, profile), Pulley(zg, profile)
        fd, fg = D.outside_radius + flange, G.outside_radius + flange
        if fd + fg + gap > 1.5 * length:
            break
        for teeth in stock:
            L = teeth * profile.pitch
            c_min = max(fd + fg + gap, abs(D.pitch_radius - G.pitch_radius) + 1e-6)
            if open_length(D.pitch_radius, G.pitch_radius, c_min) > L:
                continue
            c = centre_distance_for(L, D.pitch_radius, G.pitch_radius, c_min)
            if best is None or abs(c - length) < abs(best[0] - length):
                best = (c, D, G, teeth)
    if best is not None:
        c, D, G, teeth = best
        return BeltStage(j, c, ratio, D, G, teeth, open_length(D.pitch_radius, G.pitch_radius, c), None, idler_radius,
                         teeth * profile.pitch, c - length, c - length)
    raise DesignError(f"link {j} (S = {length:.3f} mm): no {profile.name} pulleys ≥ {min_teeth} teeth for the ratio "
                      f"{ratio} with a stock belt and tensioner fit (tried {len(tried)} combinations)", "belts")
