"""Contact along the face (``checks.contact_pattern``): the kernel against a wedge whose contact
length has a closed form; the shipped bevel mitre pair bears from toe to heel, a mis-set pair (gear 2
moved 0.2 mm sideways, the shafts no longer meeting) only at the heel or the toe, where the closed form
says; the crossed helical pair and
the plain-wheel worm touch at a point whose pattern crosses part of the face (the worm's wheel: a
warning)."""

from __future__ import annotations

import math

import manifold3d as m3d
import numpy as np
import pytest

from partgen.checks.contact3d import turned
from partgen.checks.contact_pattern import Face, contact_pattern, pattern_finding
from partgen.geometry.solid import cross_section
from partgen.mechanisms.bevel.kit import BevelKit
from partgen.mechanisms.bevel.contact import contact_along_face as bevel_contact, contact_angles as bevel_angles

PHASES = 4


def _wedge_near(slope: float, arm: float):
    """A block (world x 0–10, y −3–0) and a driven block above it whose lower face rises ``slope`` per mm
    of x from touching at x = 0, turning about the z axis through (``arm``, 0): a turn δ brings its face
    down (arm − x) δ."""
    a = m3d.Manifold.extrude(cross_section(np.array([[0.0, -3.0], [10.0, -3.0], [10.0, 0.0], [0.0, 0.0]])), 2.0)
    b_world = np.array([[0.0, 0.0], [10.0, 10.0 * slope], [10.0, 3.0], [0.0, 3.0]])
    b = m3d.Manifold.extrude(cross_section(b_world - [arm, 0.0]), 2.0)
    Tb = np.eye(4)
    Tb[0, 3] = arm
    return lambda theta: (a, np.eye(4), b, Tb)


@pytest.mark.parametrize("slope,gap_rad", [(0.004, 2e-4), (0.002, 1.5e-4), (1e-4, 2e-4)])
def test_the_kernel_measures_a_wedges_contact_length(slope, gap_rad):
    """The driven face, turned the gap past touching, cuts into the block where (arm − x) δ > slope x:
    x < arm δ / (slope + δ) — the contact length in closed form, toward the end where they touch (the
    whole face when that is beyond it)."""
    arm = 100.0
    near = _wedge_near(slope, arm)
    face = Face(lambda p, Ta, Tb: p[:, 0], 0.0, 10.0, ("the left", "the right"), "the face")
    p = contact_pattern(near, [0.0], [0.0], [0.0], gap_rad, [face])[0]
    expected = min(arm * gap_rad / (slope + gap_rad), 10.0) / 10.0
    assert p["from"] == pytest.approx(0.0, abs=1e-6)
    assert p["fraction"] == pytest.approx(expected, rel=0.02, abs=1e-3)
    assert p["sits"] == ("centred" if expected > 0.8 else "toward the left")
    assert pattern_finding(p, ("a", "b"), "k").severity == ("info" if expected >= 0.5 else "warn")
    # a phase that already overlaps, or has no loaded flank within reach, is left out
    assert contact_pattern(near, [0.0], [0.0], [1.0], gap_rad, [face])[0]["fraction"] is None
    assert contact_pattern(near, [0.0], [0.5], [0.0], gap_rad, [face], reach=0.5)[0]["fraction"] is None


def _phases(spec) -> np.ndarray:
    return 2 * math.pi / spec.gear1.teeth * np.arange(PHASES) / PHASES


@pytest.fixture(scope="module")
def mitre(kit_of):
    built = kit_of("bevel_mitre")
    thetas = _phases(built.loaded.spec)
    return built, thetas, bevel_angles(built.kit, thetas, 1e-5)


def test_the_mitre_pair_bears_from_toe_to_heel(mitre):
    """Exact spherical involutes on a common apex touch along a line through it: at every phase the
    loaded flanks are within 0.02 mm from the toe's back cone to the heel's, the pattern centred."""
    built, thetas, play = mitre
    c = bevel_contact(built.kit, thetas, play)
    assert c["gap_mm"] == 0.02 and c["phases"] == PHASES and c["face_width_mm"] == pytest.approx(9.0)
    assert c["fraction"] >= 0.97 and c["from"] <= 0.01 and c["to"] >= 0.99, c
    assert c["instantaneous"]["min"] >= 0.95 and c["sits"] == "centred"
    assert pattern_finding(c, ("gear1", "gear2"), "gears").severity == "info"


class _Offset(BevelKit):
    """The shipped kit with gear 2 moved ``offset`` mm along world y — square to both shafts, so the axes
    no longer meet (a mounting error) — and turned back by the angle that move is at mid-face, so the
    pair stays clear."""

    offset = 0.0

    def poses(self, theta: float = 0.0):
        s = self.spec
        P = super().poses(theta)
        T = P["gear2"].copy()
        T[1, 3] += self.offset
        v = np.cross(s.pair.axis2, (s.pair.cone_distance - s.gear2.face_width / 2) * s.pair.pitch_line)
        return {**P, "gear2": turned(T, -self.offset * v[1] / (v @ v))}


@pytest.mark.parametrize("offset", [0.2, -0.2])
def test_a_mis_set_bevel_pair_bears_only_at_one_end(mitre, offset):
    """Gear 2 moved e = ±0.2 mm off the plane of the shafts: a move along its pitch circle's tangent there
    is an angle e / ρ, ρ = s sin δ growing from toe to heel, so the flanks turn against each other
    along the face. They touch at the heel (e > 0) or the toe (e < 0) and are within the gap g = 0.02 mm
    (at the heel pitch radius R sin δ, an angle g / (R sin δ)) from there to where
    |e| (1/s − 1/s_end) / sin δ = g / (R sin δ): s = R / (1 + g/e) at the heel, 1 / (1/(R − b) − g/(|e| R))
    at the toe. The measured pattern ends there (to 0.01 of the face), a warning at that end."""
    built, thetas, _ = mitre
    kit = type("Offset", (_Offset,), {"offset": offset})(built.kit.spec, built.kit.parts)
    play = bevel_angles(kit, thetas[:2], 1e-5)
    assert (play["overlap_mm3"] == 0.0).all()
    c = bevel_contact(kit, thetas[:2], play)
    R, b, g = built.loaded.spec.pair.cone_distance, built.loaded.spec.gear2.face_width, 0.02
    if offset > 0:
        s = R / (1 + g / offset)
        assert c["to"] >= 0.99 and c["from"] == pytest.approx((s - (R - b)) / b, abs=0.01), c
        assert c["sits"] == "toward the heel"
    else:
        s = 1 / (1 / (R - b) - g / (-offset * R))
        assert c["from"] <= 0.01 and c["to"] == pytest.approx((s - (R - b)) / b, abs=0.01), c
        assert c["sits"] == "toward the toe"
    assert c["fraction"] < 1 / 3 and c["instantaneous"]["max"] < 1 / 3
    f = pattern_finding(c, ("gear1", "gear2"), "gears")
    assert f.severity == "warn" and c["sits"] in f.message


@pytest.fixture(scope="module")
def worm(kit_of):
    built = kit_of("gear_train_worm")
    return built.loaded.mechanism.check(built.loaded.spec, built.kit, PHASES)


def test_the_plain_worm_wheel_touches_at_a_point_near_its_middle(worm):
    """A ZI worm and a plain helical wheel touch at a point: at 5° lead the contact path crosses the
    wheel's face at sin 5° of its speed, so the pattern is the contact ellipse (flanks within 0.02 mm
    over about a quarter of the 10 mm face), centred — the check's warning names the throated wheel;
    along the worm the path runs almost axially (a tooth's worth at each phase, a few % of its 30 mm)."""
    c = worm.figures["contact_along_face"]
    wheel, worm_len = c["gear2"], c["gear1"]
    assert c["gap_mm"] == 0.02 and wheel["phases"] == PHASES
    assert 0.2 <= wheel["fraction"] <= 0.4 and wheel["sits"] == "centred", wheel
    assert 0.2 <= wheel["instantaneous"]["min"] <= wheel["instantaneous"]["max"] <= 0.35
    assert worm_len["instantaneous"]["max"] < 0.06 and worm_len["fraction"] > 2 * worm_len["instantaneous"]["max"]
    found = [x for x in worm.findings if x.check == "contact"]
    assert len(found) == 1 and found[0].severity == "warn" and "throated" in found[0].message
    assert found[0].value == pytest.approx(wheel["fraction"]) and worm.ok


def test_the_crossed_pair_pattern_crosses_most_of_the_face(kit_of):
    """At 45° + 45° the contact path crosses gear 2's face at sin 45° of its speed: the ellipses over a
    tooth pitch cover most of the face, centred; at any one phase about a third."""
    built = kit_of("gear_train_crossed_helical")
    result = built.loaded.mechanism.check(built.loaded.spec, built.kit, PHASES)
    c = result.figures["contact_along_face"]["gear2"]
    assert 0.6 <= c["fraction"] <= 0.9 and c["sits"] == "centred", c
    assert 0.2 <= c["instantaneous"]["min"] <= c["instantaneous"]["max"] <= 0.5
    assert [x.severity for x in result.findings if x.check == "contact"] == ["info"]
