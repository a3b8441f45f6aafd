"""The crossed helical pair's exact 3-D contact (what check, trace and the docs' figures measure):
each gear cut to the teeth near the mesh, the overlap volumes over a tooth pitch, the contact
search, the measured ratio and where along the faces the flanks touch.

The contact search: gear 2 is turned from its nominal angle about its own axis until its solid
first overlaps gear 1's (bisection on the exact intersection volume), both ways; each solid is first
cut to the few teeth that can reach the mesh at that phase (a sector of ± the face's twist and
three pitches round the pitch point), so every test is a small boolean.
"""

from __future__ import annotations

import math

import numpy as np

from ...checks.contact3d import contact_angles as _contact_angles, measured_ratio as _measured_ratio
from ...checks.contact3d import overlaps_over_pitch
from ...checks.contact_pattern import CONTACT_GAP_MM, Face, contact_pattern, pattern_finding
from ...geometry.helical import cylinder_along
from ..solid_pair import SolidPair
from .kit import CrossedKit
from .resolve import CrossedSpec, is_worm

__all__ = ["mesh_overlaps", "designed_backlash", "contact_angles", "measured_ratio", "contact_along_face", "PAIR"]


def _near_mesh(kit: CrossedKit, theta: float):
    """(gear 1 cut, its pose, gear 2 cut, its nominal pose) at gear 1's turn ``theta``: each gear
    cut to the other's tip cylinder (0.5 mm larger, 1 mm longer), the only place they can touch."""
    s = kit.spec
    P = kit.poses(theta)
    out = []
    for i, (name, other) in enumerate((("gear1", "gear2"), ("gear2", "gear1"))):
        j = 1 - i
        g = (s.gear1, s.gear2)[j]
        local = np.linalg.inv(P[name]) @ P[other]
        cut = kit.part(name).solid ^ cylinder_along(g.tip_radius + 0.5, s.face_width[j] + 1.0, 0.05, local)
        out += [cut, P[name]]
    return out


def mesh_overlaps(kit: CrossedKit, phases: int, nudge: float = 0.0, theta0: float = 0.0) -> np.ndarray:
    """Exact overlap volumes (mm³) of the two gears at ``phases`` turns of gear 1 spread over one
    of its tooth pitches from ``theta0``; ``nudge``: gear 2 turned that far (rad) from its nominal
    angle (``checks.contact3d.overlaps_over_pitch``)."""
    return overlaps_over_pitch(lambda t: _near_mesh(kit, t), kit.spec.gear1.teeth, phases, nudge, theta0)


def designed_backlash(spec: CrossedSpec) -> float:
    """Circumferential backlash along gear 2's reference pitch circle (mm): each gear's transverse
    thinning is j cos β_i in the normal plane, and a turn of gear 2 moves its flank 1/cos β_2 as
    far along its pitch circle as along the normal: (j_1 cos β_1 + j_2 cos β_2) / cos β_2."""
    b1, b2 = spec.pair.helix
    j1, j2 = spec.gear1.system.backlash_per_gear, spec.gear2.system.backlash_per_gear
    return (j1 * math.cos(b1) + j2 * math.cos(b2)) / math.cos(b2)


def _reach_guess(kit: CrossedKit) -> tuple[float, float]:
    """Half a pitch of gear 2 (farther than any backlash) and the designed play at gear 2 (rad)."""
    s = kit.spec
    return math.pi / s.gear2.teeth, designed_backlash(s) / s.pair.pitch_radius(1)


def contact_angles(kit: CrossedKit, thetas, tol: float = 1e-7) -> dict[str, np.ndarray]:
    """At gear 1's turns ``thetas``: how far gear 2 turns from its nominal angle (rad, about its own
    axis) before it touches gear 1, forwards (``ahead`` > 0) and backwards (``behind`` < 0), and the
    overlap (mm³) at the nominal angle (``checks.contact3d.contact_angles``)."""
    return _contact_angles(lambda t: _near_mesh(kit, t), thetas, *_reach_guess(kit), tol)


def measured_ratio(kit: CrossedKit, turns: int = 1, tol: float = 1e-8) -> tuple[float, float, float]:
    """(ratio input/output measured, the driven flank's lag at θ = 0 and at θ = 2π·turns, rad)
    (``checks.contact3d.measured_ratio``)."""
    return _measured_ratio(lambda t: _near_mesh(kit, t), kit.spec.angle2, *_reach_guess(kit), turns, tol)


def _along_axis(which: int):
    """A face coordinate: the points along gear ``which``'s axis (0: gear 1, 1: gear 2) from its mid-plane, mm."""
    def coord(points: np.ndarray, Ta: np.ndarray, Tb: np.ndarray) -> np.ndarray:
        T = (Ta, Tb)[which]
        return (points - T[:3, 3]) @ T[:3, 2]
    return coord


def contact_along_face(kit: CrossedKit, thetas, play: dict) -> dict:
    """Where along the faces gear 2's loaded flank comes within ``CONTACT_GAP_MM`` (along its pitch
    circle) of gear 1's at gear 1's turns ``thetas``, ``play`` their ``contact_angles``
    (``checks.contact_pattern``): along gear 2's face (its axis, from the block1 end to the block2 end:
    the figure the finding judges) and along gear 1's (its axis, bottom to top: a worm's length), as
    ``{"gear2": ..., "gear1": ...}``."""
    s = kit.spec
    b1, b2 = s.face_width
    worm = is_worm(s.pair)
    faces = [Face(_along_axis(1), -b2 / 2, b2 / 2, ("the block1 end", "the block2 end"),
                  "the wheel's face" if worm else "gear 2's face"),
             Face(_along_axis(0), -b1 / 2, b1 / 2, ("the bottom", "the top"),
                  "the worm's length" if worm else "gear 1's face")]
    reach, _ = _reach_guess(kit)
    p2, p1 = contact_pattern(lambda t: _near_mesh(kit, t), thetas, play["ahead"], play["overlap_mm3"],
                             CONTACT_GAP_MM / s.pair.pitch_radius(1), faces, reach)
    return {"gap_mm": CONTACT_GAP_MM, "gap_along": "gear 2's pitch circle", "gear2": p2, "gear1": p1}


def _point_contact(spec: CrossedSpec) -> str:
    """What a short contact pattern means here (the finding's hint)."""
    if spec.throated:
        return "a throated wheel should bear across its face: its cut or the poses are off"
    if is_worm(spec.pair):
        return ("a plain helical wheel touches the worm at a point, which crosses little of the wheel's face "
                "over a turn (a throated wheel wraps round the worm)")
    return "crossed helical gears touch at a point: their path of contact crosses only part of the face"


def _contact_finding(spec: CrossedSpec, contact: dict):
    """The contact along gear 2's face judged (``checks.contact_pattern.pattern_finding``)."""
    return pattern_finding(contact["gear2"], ("gear1", "gear2"), "gears.face_width_mm[1]", hint=_point_contact(spec))


PAIR = SolidPair(contact_angles, measured_ratio, contact_along_face, lambda spec: spec.pair.pitch_radius(1),
                 designed_backlash, "gear 2's pitch circle", lambda contact: [contact["gear2"], contact["gear1"]],
                 _contact_finding, lambda spec: {"centre_distance_mm": round(spec.centre_distance, 6)})
"""The pair as the shared check and trace see it (``mechanisms.solid_pair``): play measured along
gear 2's reference pitch circle, two contact patterns (along gear 2's face, the one judged, and
gear 1's), and the centre distance among the check's figures."""
