"""The straight bevel pair's exact 3-D contact (what check, trace and the docs' figures measure):
each gear cut to the teeth near the mesh, the overlap volumes over a tooth pitch, the contact
search, the measured ratio and where along the face the flanks touch.

The contact search: gear 2 is turned from its nominal angle about its own axis until its solid
first overlaps gear 1's (bisection on the exact intersection volume), both ways; each solid is first
cut to the teeth within two pitches of the pitch line (a wedge round its axis), so every test is a
small boolean.
"""

from __future__ import annotations

import math

import numpy as np

from ...checks.contact3d import contact_angles as _contact_angles, measured_ratio as _measured_ratio
from ...checks.contact3d import overlaps_over_pitch
from ...checks.contact_pattern import CONTACT_GAP_MM, Face, contact_pattern, pattern_finding
from ...geometry.helical import sector_prism
from ..solid_pair import SolidPair
from .kit import BevelKit
from .resolve import BevelSpec

__all__ = ["WEDGE_PITCHES", "mesh_overlaps", "designed_backlash", "contact_angles", "measured_ratio",
           "contact_along_face", "PAIR"]

WEDGE_PITCHES = 2  # each gear is cut to ± this many of its pitches round the pitch line (contact ratio < 2)


def _near_mesh(kit: BevelKit, theta: float):
    """(gear 1 cut, its pose, gear 2 cut, its nominal pose) at gear 1's turn ``theta``: each gear cut
    to a wedge of ± two pitches round the direction of the pitch line in its own frame."""
    s = kit.spec
    P = kit.poses(theta)
    out = []
    for name, tooth, angle in (("gear1", s.gear1, float(theta)), ("gear2", s.gear2, float(s.angle2(theta)))):
        R = 2 * s.pair.cone_distance
        wedge = sector_prism(R, -angle, WEDGE_PITCHES * 2 * math.pi / tooth.teeth, R)
        out += [kit.part(name).solid ^ wedge, P[name]]
    return out


def mesh_overlaps(kit: BevelKit, phases: int, nudge: float = 0.0, theta0: float = 0.0) -> np.ndarray:
    """Exact overlap volumes (mm³) of the two gears at ``phases`` turns of gear 1 spread over one
    of its tooth pitches from ``theta0``; ``nudge``: gear 2 turned that far (rad) from its nominal
    angle (``checks.contact3d.overlaps_over_pitch``)."""
    return overlaps_over_pitch(lambda t: _near_mesh(kit, t), kit.spec.gear1.teeth, phases, nudge, theta0)


def designed_backlash(spec: BevelSpec) -> float:
    """Circumferential backlash at the heel pitch circle (mm): the two gears' arc thinnings there."""
    return spec.gear1.backlash + spec.gear2.backlash


def _reach_guess(kit: BevelKit) -> tuple[float, float]:
    """Half a pitch of gear 2 (farther than any backlash) and the designed play at gear 2 (rad)."""
    s = kit.spec
    return math.pi / s.gear2.teeth, designed_backlash(s) / s.gear2.pitch_radius


def contact_angles(kit: BevelKit, thetas, tol: float = 1e-7) -> dict[str, np.ndarray]:
    """At gear 1's turns ``thetas``: how far gear 2 turns from its nominal angle (rad, about its own
    axis) before it touches gear 1, forwards (``ahead`` > 0) and backwards (``behind`` < 0), and the
    overlap (mm³) at the nominal angle (``checks.contact3d.contact_angles``)."""
    return _contact_angles(lambda t: _near_mesh(kit, t), thetas, *_reach_guess(kit), tol)


def measured_ratio(kit: BevelKit, turns: int = 1, tol: float = 1e-8) -> tuple[float, float, float]:
    """(ratio input/output measured, the driven flank's lag at θ = 0 and at θ = 2π·turns, rad)
    (``checks.contact3d.measured_ratio``)."""
    return _measured_ratio(lambda t: _near_mesh(kit, t), kit.spec.angle2, *_reach_guess(kit), turns, tol)


def contact_along_face(kit: BevelKit, thetas, play: dict) -> dict:
    """Where along the face, toe to heel, gear 2's loaded flank comes within ``CONTACT_GAP_MM`` (along its
    heel pitch circle) of gear 1's at gear 1's turns ``thetas``, ``play`` their ``contact_angles``
    (``checks.contact_pattern``). The coordinate: the cone distance in gear 2's frame, s = ρ sin δ_2 − a
    cos δ_2 (ρ from its axis, a along it from the apex), which is R − b on the toe's back cone and R on
    the heel's."""
    s = kit.spec
    d = s.gear2.pitch_angle
    sd, cd = math.sin(d), math.cos(d)

    def cone_distance(points: np.ndarray, Ta: np.ndarray, Tb: np.ndarray) -> np.ndarray:
        local = (points - Tb[:3, 3]) @ Tb[:3, :3]
        return np.hypot(local[:, 0], local[:, 1]) * sd - local[:, 2] * cd

    R, b = s.pair.cone_distance, s.gear2.face_width
    face = Face(cone_distance, R - b, R, ("the toe", "the heel"), "the face (toe to heel)")
    reach, _ = _reach_guess(kit)
    p = contact_pattern(lambda t: _near_mesh(kit, t), thetas, play["ahead"], play["overlap_mm3"],
                        CONTACT_GAP_MM / s.gear2.pitch_radius, [face], reach)[0]
    return {"gap_mm": CONTACT_GAP_MM, "gap_along": "gear 2's heel pitch circle", **p}


def _contact_finding(spec: BevelSpec, contact: dict):
    """The contact along the face, toe to heel, judged (``checks.contact_pattern.pattern_finding``)."""
    return pattern_finding(contact, ("gear1", "gear2"), "gears.teeth",
                           hint="the flanks are not conjugate along the face (the solids or their poses)")


PAIR = SolidPair(contact_angles, measured_ratio, contact_along_face, lambda spec: spec.gear2.pitch_radius,
                 designed_backlash, "gear 2's heel pitch circle", lambda contact: [contact], _contact_finding)
"""The pair as the shared check and trace see it (``mechanisms.solid_pair``): play measured along
gear 2's heel pitch circle, one contact pattern (toe to heel)."""
