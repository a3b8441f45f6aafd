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
from ..core.findings import Finding, Result
from ..geometry.measure import intersection, min_gap

__all__ = ["VOLUME_EPS", "turned", "overlaps_over_pitch", "contact_angles", "measured_ratio", "pair_check"]

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


def pair_check(res: Result, kit, thetas: np.ndarray, play: dict, r2: float, running_mm: float, designed_mm: float,
               contact: dict, contact_finding, extra: dict | None = None) -> None:
    """The findings and figures of a pair of solid gears checked exactly in 3-D (``gear1``, ``gear2``
    in a frame of ``base`` and ``pin2``), added to ``res`` in this order: the teeth overlapping at a
    phase, no backlash left, the gears against the frame over a turn of gear 1 (4 angles: overlap,
    closest gap), the bores gripping their shafts (``running_mm``: the diametral running clearance),
    the contact along the face (``contact_finding``, the mechanism's), the bed and the bores.
    ``play``: ``contact_angles`` at ``thetas`` (rad of gear 2); ``r2``: the radius (mm) its play is
    measured along; ``designed_mm``: the backlash designed there; ``extra``: figures of the
    mechanism's own, placed after the phases."""
    from .bed import add_bed_and_bores

    n = len(thetas)
    bad = np.flatnonzero(play["overlap_mm3"] > VOLUME_EPS)
    if len(bad):
        k = bad[np.argmax(play["overlap_mm3"][bad])]
        res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {play['overlap_mm3'][k]:.4f} mm³ at "
                        f"{len(bad)} of {n} phases", ("gear1", "gear2"), float(thetas[k]),
                        float(play["overlap_mm3"][k]), "mm3", key="gears.backlash_per_gear_mm"))
    backlash = (play["ahead"] - play["behind"]) * r2
    if backlash.min() <= 0:
        res.add(Finding("mesh", "fail", "the teeth jam: no backlash left", ("gear1", "gear2"),
                        float(thetas[np.argmin(backlash)]), float(backlash.min()), "mm",
                        key="gears.backlash_per_gear_mm"))
    # the frame: the gears against the base and the pin, exact 3-D, over a turn of gear 1
    closest = {}
    for t in np.linspace(0.0, 2 * math.pi, 4, endpoint=False):
        P = kit.poses(float(t))
        for g in ("gear1", "gear2"):
            for other in ("base", "pin2"):
                v = intersection(kit.part(g).solid, P[g], kit.part(other).solid, P[other])[0]
                if v > VOLUME_EPS:
                    res.add(Finding("interference", "fail", f"{g} and {other} overlap by {v:.4f} mm³",
                                    (g, other), float(t), v, "mm3", key="frame"))
                gap = min_gap(kit.part(g).solid, P[g], kit.part(other).solid, P[other], 5.0)
                closest[f"{g}-{other}"] = min(closest.get(f"{g}-{other}", math.inf), gap)
    radial = running_mm / 2
    if radial <= 0:
        res.add(Finding("fit", "fail", f"the bores grip their shafts ({radial:.3f} mm radial gap)", ("gear1", "base"),
                        value=radial, unit="mm", key="shafts.running_clearance_diametral_mm"))
    res.add(contact_finding)
    te = play["ahead"] * r2
    res.figures.update(samples=n, phases_over="one tooth pitch of gear 1", **(extra or {}),
                       max_overlap_mm3=float(play["overlap_mm3"].max()), contact_along_face=contact,
                       backlash_mm={"min": float(backlash.min()), "max": float(backlash.max()),
                                    "designed": designed_mm},
                       transmission_error_mm={"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                       closest_mm={k: float(round(v, 4)) for k, v in closest.items()}, radial_gap_mm=float(radial))
    add_bed_and_bores(res, kit.parts, kit.printer)

