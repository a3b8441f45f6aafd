"""Spherical / quasi-ellipsoidal wrist gears: the ratio ODE against its closed form, the mating
angle both ways, pitch radii, the pose of gear 2, and tooth rows at equal arcs."""

import math

import numpy as np
import pytest

from partgen.design.spherical import (RangeError, gear2_pose, mating_angle, mating_angle_latitude,
                                      mating_angle_meridian, meridian_arc, pitch_radii, ratio, ratio_ode, tooth_rows,
                                      valid_end)

RATIOS = [1.0, 2 / 3, 0.4, 1.5, 3.0]


@pytest.mark.parametrize("I", RATIOS)
def test_ode_integrates_to_the_closed_form_over_the_whole_range(I):
    end = valid_end(I)
    theta, i = ratio_ode(end, I, 4000)
    assert theta[0] == 0 and theta[-1] == end
    assert np.abs(i - ratio(theta, I)).max() < 1e-9
    # the ODE itself holds for the closed form: finite differences of i vs its right-hand side
    t = np.linspace(0.05, end - 0.05, 200)
    h = 1e-6
    di = (ratio(t + h, I) - ratio(t - h, I)) / (2 * h)
    r = ratio(t, I)
    rhs = r * (np.sqrt(1 - (r * np.sin(t)) ** 2) - np.cos(t)) / np.sin(t)
    assert np.abs(di - rhs).max() < 1e-7
    assert ratio(0.0, I) == pytest.approx(I, abs=1e-15)
    assert (ratio(1e-4, I) - I) / 1e-4 == pytest.approx(0.0, abs=1e-3)  # i'(0) = 0


@pytest.mark.parametrize("I", RATIOS)
def test_the_end_of_the_range_is_detected_not_overrun(I):
    end = valid_end(I)
    assert ratio(end, I) * math.sin(end) == pytest.approx(1.0, abs=1e-12)  # the ODE's root hits 0
    assert mating_angle(end, I) == pytest.approx(math.pi / 2, abs=1e-12)
    for f in (lambda t: ratio(t, I), lambda t: mating_angle_latitude(t, I), lambda t: ratio_ode(t, I, 10)):
        with pytest.raises(RangeError, match="φ reaches π/2"):
            f(end + 1e-6)


@pytest.mark.parametrize("I", RATIOS)
def test_mating_angle_both_ways_agree(I):
    t = np.linspace(0, valid_end(I), 301)
    merid, lat = mating_angle_meridian(t, I), mating_angle_latitude(t, I)
    assert np.abs(merid - lat).max() < 1e-9
    assert np.abs(merid - mating_angle(t, I)).max() < 1e-9


def test_unit_ratio_gives_two_spheres():
    t = np.linspace(0, valid_end(1.0), 101)
    assert np.abs(ratio(t, 1.0) - 1).max() < 1e-15
    r1, r2 = pitch_radii(t, 1.0, 40.0)
    assert np.abs(r1 - 20).max() < 1e-12 and np.abs(r2 - 20).max() < 1e-12
    assert np.abs(mating_angle(t, 1.0) - t).max() < 1e-15


@pytest.mark.parametrize("I", [1.0, 2 / 3])
@pytest.mark.parametrize("theta_frac,psi", [(0.2, 0.0), (0.5, 1.1), (0.8, -2.5)])
def test_gear2_pose_puts_the_pitch_surfaces_tangent_at_the_contact(I, theta_frac, psi):
    A = 40.0
    theta = theta_frac * valid_end(I)
    T = gear2_pose(theta, psi, I, A)
    r1, r2 = (float(x) for x in pitch_radii(theta, I, A))
    u = np.array([math.sin(theta) * math.cos(psi), math.sin(theta) * math.sin(psi), math.cos(theta)])
    P = r1 * u  # the contact point on gear 1
    c2, pole2 = T[:3, 3], T[:3, :3] @ np.array([0, 0, 1.0])
    assert np.linalg.norm(P - c2) == pytest.approx(r2, abs=1e-9)
    phi = float(mating_angle(theta, I))
    assert math.acos(np.clip(np.dot((P - c2) / r2, pole2), -1, 1)) == pytest.approx(phi, abs=1e-9)

    def normal(radius_fn, alpha, axis_frame, centre):
        """Outward normal of a surface of revolution at polar angle alpha in the meridian plane."""
        h = 1e-6
        R, z_axis, e = axis_frame
        p = lambda a: centre + radius_fn(a) * (math.sin(a) * e + math.cos(a) * z_axis)  # noqa: E731
        tangent = (p(alpha + h) - p(alpha - h)) / (2 * h)
        binormal = np.cross(z_axis, e)
        n = np.cross(tangent, binormal)
        return n / np.linalg.norm(n)

    e1 = np.array([math.cos(psi), math.sin(psi), 0.0])
    n1 = normal(lambda a: float(pitch_radii(a, I, A)[0]), theta, (None, np.array([0, 0, 1.0]), e1), np.zeros(3))
    # gear 2: its meridian plane holds its pole and the contact; r2 as a function of its own angle
    e2 = (P - c2) / r2 - math.cos(phi) * pole2
    e2 /= np.linalg.norm(e2)
    th_of = lambda ph: 2 * math.atan(math.tan(ph / 2) / I)  # noqa: E731
    n2 = normal(lambda a: float(pitch_radii(th_of(a), I, A)[1]), phi, (None, pole2, e2), c2)
    assert abs(abs(np.dot(n1, n2)) - 1) < 1e-8  # same tangent plane: they touch, not cross


@pytest.mark.parametrize("I", [1.0, 2 / 3])
def test_rows_meet_rows_and_the_latitude_pitch_is_reported(I):
    A, p = 40.0, 5.0
    pair = tooth_rows(I, A, p)
    assert [r.teeth for r in pair.rows] == [1, 6, 12]
    for r in pair.rows:
        assert meridian_arc(r.theta, I, A) == pytest.approx(r.k * p, abs=1e-9)
        assert meridian_arc(r.theta, I, A, gear=2) == pytest.approx(r.k * p, abs=1e-8)  # rows meet rows
    # equal arcs cannot also keep the latitudinal pitch at p: ring k has 6k teeth on a circle of
    # circumference 2π ρ, ρ < k p (for spheres, 2π r sin(kp/r) / 6k)
    for r in pair.rows[1:]:
        if I == 1.0:
            assert r.lat_pitch_1 == pytest.approx(2 * math.pi * 20 * math.sin(r.k * p / 20) / r.teeth, rel=1e-9)
        assert r.lat_pitch_1 == pytest.approx(r.lat_pitch_2, rel=1e-9)
        assert abs(r.lat_pitch_1 / p - 1) > 1e-4
