"""Bennett linkage in closed form: the paper's numbers, loop closure to 1e-12 over the whole motion,
designs that break the Bennett condition rejected."""

import math

import numpy as np
import pytest

from partgen.design.bennett import bennett_b, check_bennett, dh, joint_angles, joint_frames, loop
from partgen.errors import DesignError


def test_fixture_b():
    assert bennett_b(50.0, math.radians(30), math.radians(60)) == pytest.approx(86.60254, abs=5e-6)


@pytest.mark.parametrize("a,alpha_deg,beta_deg", [(50.0, 30.0, 60.0), (70.0, 40.0, 55.7), (20.0, 80.0, 25.0),
                                                   (35.0, 40.0, 180 - 55.7)])
def test_loop_closes_over_the_whole_motion(a, alpha_deg, beta_deg):
    al, be = math.radians(alpha_deg), math.radians(beta_deg)
    b = bennett_b(a, al, be)
    check_bennett(a, b, al, be)
    theta = np.linspace(-math.pi + 1e-6, math.pi - 1e-6, 721)
    angles = joint_angles(theta, al, be)
    worst = max(np.abs(loop(row, a, b, al, be) - np.eye(4)).max() for row in angles)
    assert worst < 1e-12 * max(a, b) * 10  # mm and unitless entries: ~1e-12 relative
    # one degree of freedom: θ2 moves monotonically with θ1 (away from the fold)
    t2 = np.unwrap(angles[:, 1])
    assert np.all(np.diff(t2) < 0) or np.all(np.diff(t2) > 0)


def test_the_paper_ratio_and_twist():
    """α = 40°, a/b = 7/9: the Bennett condition gives β = 55.7°."""
    al = math.radians(40)
    beta = math.asin(9 / 7 * math.sin(al))
    assert math.degrees(beta) == pytest.approx(55.7, abs=0.05)
    check_bennett(7.0, 9.0, al, beta)


def test_a_non_bennett_design_is_rejected():
    with pytest.raises(DesignError, match="Bennett condition"):
        check_bennett(50.0, 80.0, math.radians(30), math.radians(60), "links")
    # and it really does not move: with the Bennett relation's angles its loop does not close
    al, be = math.radians(30), math.radians(60)
    angles = joint_angles(np.array([1.0]), al, be)[0]
    assert np.abs(loop(angles, 50.0, 80.0, al, be) - np.eye(4)).max() > 1.0


def test_planar_limit_is_a_parallelogram():
    theta = np.linspace(0.1, 3.0, 50)
    for row in joint_angles(theta, 0.0, 0.0):
        assert np.abs(loop(row, 40.0, 25.0, 0.0, 0.0) - np.eye(4)).max() < 1e-12
        f = joint_frames(row, 40.0, 25.0, 0.0, 0.0)
        # opposite sides parallel and equal: joint 3 - joint 4 equals joint 2 - joint 1
        assert np.allclose(f[2][:3, 3] - f[3][:3, 3], f[1][:3, 3] - f[0][:3, 3], atol=1e-12)


def test_joint_axes_are_skew_at_the_right_distance_and_twist():
    a, al, be = 50.0, math.radians(30), math.radians(60)
    b = bennett_b(a, al, be)
    f = joint_frames(joint_angles(np.array([0.7]), al, be)[0], a, b, al, be)
    for i, (length, twist) in enumerate(((a, al), (b, be), (a, al))):
        z0, z1 = f[i][:3, 2], f[i + 1][:3, 2]
        assert math.acos(np.clip(z0 @ z1, -1, 1)) == pytest.approx(abs(twist), abs=1e-12)
        n = np.cross(z0, z1)
        d = abs((f[i + 1][:3, 3] - f[i][:3, 3]) @ n) / np.linalg.norm(n)
        assert d == pytest.approx(length, abs=1e-9)  # common normal = the link length
    assert dh(0.0, 1.0, 0.0)[0, 3] == 1.0
