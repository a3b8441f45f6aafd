"""Exact 3-D contact of a gear pair on any axes: the overlap of the two posed solids over a tooth
pitch, and how far the driven gear turns about its own axis before it touches the driver (its
backlash either way), by bisection on the exact intersection volume.

A mechanism gives ``near(theta) -> (a, Ta, b, Tb)``: the driver's solid and pose and the driven
gear's solid and nominal pose at the driver's turn ``theta`` (rad), each solid already cut to
where the two can touch (that is the mechanism's own geometry); everything else here knows no
mechanism. Poses are (4, 4) world-from-local, mm; the driven gear turns about its local z.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from .contact import free_turn

from ..core.transforms import pose_z
from ..geometry.measure import intersection

__all__ = ["VOLUME_EPS", "turned", "overlaps_over_pitch", "contact_angles", "measured_ratio"]

VOLUME_EPS = 1e-9  # mm³: below this an intersection is the boolean's rounding, not material


def turned(T: np.ndarray, delta: float) -> np.ndarray:
    """Pose ``T`` (4, 4) turned by ``delta`` rad about its own local z."""
    return T @ pose_z(angle=delta)


def overlaps_over_pitch(near: Callable, teeth1: int, phases: int, nudge: float = 0.0, theta0: float = 0.0
                        ) -> np.ndarray:
    """(phases,) exact overlap volumes (mm³) at ``phases`` turns of the driver spread over one of its
    ``teeth1`` tooth pitches from ``theta0`` (the mesh repeats tooth by tooth); ``nudge``: the driven
    gear turned that far (rad) from its nominal angle."""
    out = np.empty(phases)
    for k in range(phases):
        a, Ta, b, Tb = near(theta0 + 2 * math.pi / teeth1 * k / phases)
        out[k] = intersection(a, Ta, b, turned(Tb, nudge))[0]
    return out


def contact_angles(near: Callable, thetas, reach: float, guess: float, tol: float = 1e-7) -> dict[str, np.ndarray]:
    """At the driver's turns ``thetas`` (rad): how far the driven gear turns from its nominal angle
    (rad, about its own axis) before it touches, forwards (``ahead`` > 0) and backwards (``behind`` <
    0), and the overlap (mm³) at the nominal angle. ``reach``: farther than any backlash (half a
    pitch of the driven gear); ``guess``: the designed play (rad), bracketed at 4× first. Bisection
    on the exact intersection volume to ``tol`` rad; a gap of ``reach`` or more is reported as it."""
    thetas = np.atleast_1d(np.asarray(thetas, dtype=float))
    out = {"ahead": np.empty(len(thetas)), "behind": np.empty(len(thetas)), "overlap_mm3": np.empty(len(thetas))}
    for k, t in enumerate(thetas):
        a, Ta, b, Tb = near(float(t))

        def vol(d: float) -> float:
            return intersection(a, Ta, b, turned(Tb, d))[0]

        out["overlap_mm3"][k] = vol(0.0)
        for key, sign in (("ahead", 1.0), ("behind", -1.0)):
            lo, hi = 0.0, min(reach, 4 * guess) if guess > 0 else reach  # bracket: 4× the designed play first
            if vol(sign * hi) <= VOLUME_EPS:
                lo, hi = hi, reach
                if vol(sign * hi) <= VOLUME_EPS:
                    lo = hi  # no contact within reach: a gap that wide is reported as it
            out[key][k] = sign * free_turn(lambda d: vol(sign * d) > VOLUME_EPS, lo, hi, tol)
    return out


def measured_ratio(near: Callable, angle2: Callable, reach: float, guess: float, turns: int = 1, tol: float = 1e-8
                   ) -> tuple[float, float, float]:
    """(ratio input/output measured, the driven flank's lag at θ = 0 and at θ = 2π·turns, rad): the
    driven gear's loaded angle (``angle2(θ)``, its nominal angle, plus ``ahead``) found at both ends
    of ``turns`` turns of the driver."""
    ends = [0.0, 2 * math.pi * turns]
    c = contact_angles(near, ends, reach, guess, tol)["ahead"]
    loaded = [float(angle2(t)) + d for t, d in zip(ends, c)]
    return abs((ends[1] - ends[0]) / (loaded[1] - loaded[0])), float(c[0]), float(c[1])
