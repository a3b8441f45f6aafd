"""The spatial balanced butterfly: four similar Bennett linkages (the paper's α = 40°, a/b = 7/9,
scales 1.0/0.8/0.6/0.7) as functions of the two inputs — loops closed, links rigid, the
similarity conditions (Eq 1) met, the planar form as the zero-twist limit, and the common centre
of mass at S with masses from the balance conditions."""

import dataclasses
import math

import numpy as np
import pytest

from partgen.design.balanced import LINKS, positions, solve_masses
from partgen.design.bennett import dh, joint_angles
from partgen.design.bennett_butterfly import (GROUP, JOINTS, BennettButterfly, body_joints, centre_of_mass,
                                              link_frames, pose, solve_point_masses)
from partgen.errors import DesignError

BB = BennettButterfly.from_twist(70.0, 90.0, math.radians(40), 0.8, 0.6, 0.7)
Q1, Q4 = (g.ravel() for g in np.meshgrid(np.linspace(0, 2 * np.pi, 31), np.linspace(0, 2 * np.pi, 29)))
P = pose(BB, Q1, Q4)
# each Bennett as its joints in loop order (copies of S, B2, D2, B3) and its scale
BENNETTS = {1: (("S", "B2", "D2", "B3"), 1.0), 2: (("B8", "D1", "B1", "S"), 0.8),
            3: (("D4", "B7", "S", "B6"), 0.6), 4: (("B5", "S", "B4", "D3"), 0.7)}


def test_the_paper_twist_and_lengths():
    assert math.degrees(BB.beta) == pytest.approx(55.7, abs=0.05)
    assert BB.a / math.sin(BB.alpha) == pytest.approx(BB.b / math.sin(BB.beta), rel=1e-12)


def test_a_non_bennett_design_is_rejected():
    with pytest.raises(DesignError, match="Bennett condition"):
        BennettButterfly(70.0, 90.0, math.radians(40), math.radians(50), 0.8, 0.6, 0.7)
    with pytest.raises(DesignError, match="no Bennett linkage"):
        BennettButterfly.from_twist(70.0, 200.0, math.radians(40), 0.8, 0.6, 0.7)


def _dist(a, b):
    return np.linalg.norm(P.points[a] - P.points[b], axis=1)


def test_every_bennett_is_a_closed_scaled_copy_with_common_normals():
    """Sides s·(a, b, a, b); each joint point is the foot of the common normals of its neighbours'
    axes (ab ⟂ both axes); twists α, β, α, β between consecutive axes."""
    axis_of = {n: JOINTS[n][1] for n in JOINTS}
    for k, (loop, s) in BENNETTS.items():
        joints = [next(n for n, (links, _, at) in JOINTS.items() if at == pt and _in_bennett(links, k)) for pt in loop]
        for j in range(4):
            p, q = loop[j], loop[(j + 1) % 4]
            side = BB.a if j % 2 == 0 else BB.b
            assert np.abs(_dist(p, q) - s * side).max() < 1e-9
            u = (P.points[q] - P.points[p]) / (s * side)
            za, zb = P.axis[axis_of[joints[j]]], P.axis[axis_of[joints[(j + 1) % 4]]]
            assert np.abs(np.einsum("ij,ij->i", u, za)).max() < 1e-12
            assert np.abs(np.einsum("ij,ij->i", u, zb)).max() < 1e-12
            twist = BB.alpha if j % 2 == 0 else BB.beta
            assert np.abs(np.einsum("ij,ij->i", za, zb) - math.cos(twist)).max() < 1e-12


def _in_bennett(links, k):
    members = {1: {1, 2, 3, 4}, 2: {4, 5, 6, 7}, 3: {7, 8, 9, 10}, 4: {10, 11, 12, 1}}[k]
    return set(links) <= members


def test_similarity_conditions_eq1_measured_on_the_poses():
    L = {"l1a": _dist("S", "B2"), "l1b": _dist("S", "B5"), "l2": _dist("B2", "D2"), "l10b": _dist("S", "B4"),
         "l3": _dist("D2", "B3"), "l11": _dist("B4", "D3"), "l4a": _dist("S", "B3"), "l12": _dist("D3", "B5"),
         "l5": _dist("B8", "D1"), "l6": _dist("D1", "B1"), "l7a": _dist("S", "B1"), "l4b": _dist("S", "B8"),
         "l9": _dist("D4", "B7"), "l10a": _dist("S", "B7"), "l7b": _dist("S", "B6"), "l8": _dist("B6", "D4")}
    for row in (("l1a", "l1b"), ("l2", "l10b"), ("l3", "l11"), ("l4a", "l12")), \
               (("l1a", "l5"), ("l2", "l6"), ("l3", "l7a"), ("l4a", "l4b")), \
               (("l1a", "l9"), ("l2", "l10a"), ("l3", "l7b"), ("l4a", "l8")):
        ratios = np.array([L[x] / L[y] for x, y in row])
        assert np.abs(ratios - ratios[0]).max() < 1e-12


def test_links_are_rigid_and_central_links_straight():
    """Body coordinates of every joint reproduce the world poses; B5-S-B2, B3-S-B8, B1-S-B6 and
    B7-S-B4 stay collinear; C1-B2-S-B7 and C2-B4-S-B1 are parallelograms with parallel axes."""
    frames, bj = link_frames(P), body_joints(BB)
    for i, joints in bj.items():
        R, t = frames[i][:, :3, :3], frames[i][:, :3, 3]
        for name, (pt, ax) in joints.items():
            _, g, at = JOINTS[name]
            assert np.abs(R @ pt + t - P.points[at]).max() < 1e-9
            assert np.abs(R @ ax - P.axis[g]).max() < 1e-12
    for a, c in (("B5", "B2"), ("B3", "B8"), ("B1", "B6"), ("B7", "B4")):
        assert np.abs(np.cross(P.points[a], P.points[c])).max() < 1e-9
    assert np.abs(P.points["C1"] - P.points["B2"] - P.points["B7"]).max() < 1e-12
    assert np.abs(P.points["C2"] - P.points["B4"] - P.points["B1"]).max() < 1e-12
    # the four joints at S are four different axes through one point (a spherical four-bar)
    zs = [P.axis[JOINTS[n][1]] for n in ("S14", "S47", "S710", "S101")]
    assert min(np.abs(np.einsum("ij,ij->i", zs[0], z)).max() for z in zs[1:]) < 0.999


def test_inputs_and_rigid_turn():
    """q1 is link 1's angle, q4 the angle of S→B3; q1 and q4 turned together turn the linkage rigidly."""
    p = pose(BB, 0.4, 2.0)
    assert math.atan2(p.points["B2"][0, 1], p.points["B2"][0, 0]) == pytest.approx(0.4)
    assert math.atan2(p.points["B3"][0, 1], p.points["B3"][0, 0]) == pytest.approx(2.0)
    p2 = pose(BB, 0.9, 2.5)
    c, s = math.cos(0.5), math.sin(0.5)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    for n in p.points:
        assert np.abs(p.points[n][0] @ Rz.T - p2.points[n][0]).max() < 1e-9


def test_zero_twist_is_the_planar_butterfly():
    flat = dataclasses.replace(BB, alpha=0.0, beta=0.0)
    p = pose(flat, Q1, Q4)
    checked = 0
    for k in range(0, len(Q1), 7):
        for mode in (1, -1):
            pos = positions(dataclasses.replace(flat.planar, mode=mode), Q1[k], Q4[k])
            if pos is None:
                continue
            err = max(abs(complex(*p.points[n][k, :2]) - v) for n, v in pos.items())
            if err < 1e-9:
                checked += 1
                break
    assert np.abs(np.concatenate([v[:, 2] for v in p.points.values()])).max() == 0.0
    assert checked > 100


def _on_line_coms(offsets):
    """Centres of mass on each link's line, ``offsets`` mm from its reference joint toward the next."""
    bj, coms = body_joints(BB), {}
    for i, (_, ref, toward) in LINKS.items():
        pt = next(p for n, (p, _) in bj[i].items() if JOINTS[n][2] == toward)
        coms[i] = offsets[i] * pt / np.linalg.norm(pt)
    return coms


def test_the_planar_balance_conditions_balance_the_spatial_linkage():
    rng = np.random.default_rng(3)
    L = BB.lengths
    length = {1: L["l1a"], 2: L["l2"], 3: L["l3"], 4: L["l4a"], 5: L["l5"], 6: L["l6"], 7: L["l7a"], 8: L["l8"],
              9: L["l9"], 10: L["l10b"], 11: L["l11"], 12: L["l12"]}
    m = {i: 0.2 * length[i] * float(rng.uniform(0.8, 1.2)) for i in range(1, 13)}  # g: bars of ~0.2 g/mm
    off = {i: length[i] * float(rng.uniform(0.3, 0.7)) for i in range(1, 13)}
    off.update({4: -40.0, 7: -40.0, 9: -40.0})  # counterweights beyond the reference joints
    m = solve_masses(BB.planar, m, off, (4, 7, 9))
    assert all(v > 0 for v in m.values())
    coms = _on_line_coms(off)
    assert np.abs(centre_of_mass(P, m, coms)).max() < 1e-11
    heavy = dict(m)
    heavy[5] *= 1.1
    assert np.linalg.norm(centre_of_mass(P, heavy, coms), axis=1).max() > 0.1
    # the same masses found by least squares on the moment over the poses
    fixed = {i: v for i, v in m.items() if i not in (4, 7, 9)}
    x, worst = solve_point_masses(P, fixed, coms, [(i, coms[i]) for i in (4, 7, 9)])
    assert x == pytest.approx([m[4], m[7], m[9]], rel=1e-9) and worst < 1e-9


def test_one_pin_at_S_cannot_carry_C1():
    """The alternative — links 1, 4, 7, 10 all on S's axis, each Bennett turned so its own joint
    lies on that axis — moves link 9 against link 2 about a wandering axis with no fixed point, so
    no joint at C1 can follow it: why S is a spherical four-bar here."""
    al, be, a, b, s3 = BB.alpha, BB.beta, BB.a, BB.b, BB.s3
    L = lambda l, tw: dh(0.0, l, tw)  # noqa: E731
    Rz = lambda t: dh(t, 0.0, 0.0)  # noqa: E731
    rel = []
    for t in np.linspace(0.3, 2.5, 25):
        t1, t2 = joint_angles(np.array([t]), al, be)[0, :2]
        link2 = L(a, al) @ Rz(t2)  # link 1 frame at S = identity
        link10 = Rz(t2)  # Bennett 4's joint at S (a copy of B2) is θ2
        link9 = link10 @ np.linalg.inv(L(s3 * b, be)) @ Rz(-t2)
        rel.append(np.linalg.inv(link2) @ link9)
    axes = [np.real(np.linalg.eig(M[:3, :3])[1][:, np.argmin(abs(np.linalg.eig(M[:3, :3])[0] - 1))]) for M in rel]
    spread = max(math.degrees(math.acos(min(1.0, abs(float(u @ axes[0]))))) for u in axes)
    A = np.vstack([M[:3, :3] - np.eye(3) for M in rel])
    rhs = -np.concatenate([M[:3, 3] for M in rel])
    fp = np.linalg.lstsq(A, rhs, rcond=None)[0]
    assert spread > 10.0 and np.linalg.norm(A @ fp - rhs) > 10.0


def test_groups_cover_every_link_once():
    assert sorted(GROUP) == list(range(1, 13)) and sorted(LINKS) == list(range(1, 13))
