"""A printable Bennett link: its two bores lie on skew axes a apart and twisted by α."""

import math

import manifold3d as m3d
import numpy as np
import pytest

from partgen.export.kit import printed
from partgen.geometry.bennett_link import place_on_axis, distal_axis, skew_link
from partgen.geometry.measure import intersection
from partgen.geometry.parts import Part
from partgen.testing import mesh_problems

A, ALPHA = 50.0, math.radians(30)


def pin(point, direction, radius, length=40.0):
    return place_on_axis(m3d.Manifold.cylinder(length, radius, -1.0, 48, True), np.asarray(point, float),
                  np.asarray(direction, float), 0.0)


def test_link_is_a_printable_solid_with_two_bores():
    link = skew_link(A, ALPHA, 6.0, 8.0, 2.55, 3.0, (4.25, -4.25))
    assert link.genus() == 2
    assert mesh_problems(printed(Part("L", "link", link)).mesh) == []


@pytest.mark.parametrize("alpha_deg", [30.0, 55.7, 80.0])
def test_bores_lie_on_the_skew_axes(alpha_deg):
    alpha = math.radians(alpha_deg)
    link = skew_link(A, alpha, 6.0, 8.0, 2.55, 3.0, (4.25, -4.25))
    p1, d1 = distal_axis(A, alpha)
    eye = np.eye(4)
    # a pin a hair thinner than the bore passes along each true joint axis...
    for point, direction in (((0, 0, 0), (0, 0, 1)), (p1, d1)):
        assert intersection(link, eye, pin(point, direction, 2.5), eye)[0] < 1e-6
    # ...and jams along the untwisted axis (the check can fail)
    assert intersection(link, eye, pin(p1, (0, 0, 1), 2.5), eye)[0] > 1.0
    # the two axes: common normal a long, at angle α
    assert abs(np.cross((0, 0, 1), d1) @ (p1 - 0)) / np.linalg.norm(np.cross((0, 0, 1), d1)) == pytest.approx(A)
    assert math.acos(d1 @ (0, 0, 1)) == pytest.approx(alpha)


def _written(solid, rotation=None):
    """The mesh report of a solid written as a float32 STL (turned by ``rotation`` (3, 3) first)."""
    import trimesh

    from partgen.export.verify import mesh_report, read_stl
    from partgen.geometry.solid import mesh_arrays

    v, f = mesh_arrays(solid)
    if rotation is not None:
        v = v @ np.asarray(rotation).T
    return mesh_report(*read_stl(trimesh.exchange.stl.export_stl(trimesh.Trimesh(v, f, process=False))))


def _data_link(name):
    import json
    from pathlib import Path

    from partgen.geometry import bennett_link as BL

    d = json.loads((Path(__file__).resolve().parents[2] / "data" / name).read_text())
    return ([BL.Boss(**b) for b in d["bosses"]], [BL.Bar(**b) for b in d["bars"]], [BL.Cup(**c) for c in d["cups"]],
            d["segments"])


def _capsule_link(bosses, bars, cups, segments, inset):
    """The construction the sweep found wanting: bars as capsules (hulls of two balls) united with the
    bosses and cups, a later bar's ball at a shared end ``inset`` mm smaller; then the bores cut."""
    from partgen.geometry.bennett_link import place_on_axis

    cyl = lambda h, r, pt, ax, off, c: place_on_axis(m3d.Manifold.cylinder(h, r, -1.0, segments, c),  # noqa: E731
                                                     np.asarray(pt, float), np.asarray(ax, float), off)
    add = [cyl(b.length, b.radius, b.point, b.axis, b.offset, True) for b in bosses]
    add += [cyl(c.height, c.outer_radius, c.point, c.axis, 0.0, False) for c in cups]
    seen = set()
    for b in bars:
        balls = []
        for pt in (b.p0, b.p1):
            key = tuple(round(float(x), 9) for x in pt)
            balls.append(m3d.Manifold.sphere(b.radius - (inset if key in seen else 0.0), segments).translate(pt))
            seen.add(key)
        add.append(m3d.Manifold.batch_hull(balls))
    cut = [cyl(b.length + 0.4, b.bore_radius, b.point, b.axis, b.offset, True) for b in bosses]
    cut += [cyl(c.pocket_depth + 0.1, c.pocket_radius, c.point, c.axis, c.height - c.pocket_depth, False) for c in cups]
    return m3d.Manifold.batch_boolean(add, m3d.OpType.Add) - m3d.Manifold.batch_boolean(cut, m3d.OpType.Add)


@pytest.mark.parametrize("name, inset", [("bennett_pinched_link.json", 0.0), ("bennett_collinear_link.json", 0.1)])
def test_bent_bars_write_one_shell(name, inset):
    """Two sweep links (kept in tests/data) whose bent bars, built as capsules united at their shared
    ends, wrote STLs that are not one shell: equal balls pinching at a bend, and (with the later
    ball 0.1 mm smaller) bars bending by under 4° crossing at a grazing angle. As one mitred tube per
    run of gentle bends, they write one clean shell."""
    from partgen.geometry import bennett_link as BL

    bosses, bars, cups, segments = _data_link(name)
    old = _written(_capsule_link(bosses, bars, cups, segments, inset))
    assert old.non_manifold_edges + old.pinched_vertices > 0  # the data reproduces the bad mesh
    r = _written(BL.link_solid(bosses, bars, cups, segments))
    assert (r.shells, r.non_manifold_edges, r.pinched_vertices, r.boundary_edges, r.zero_area_faces) == (1, 0, 0, 0, 0)
    assert r.volume_mm3 == pytest.approx(BL.link_solid(bosses, bars, cups, segments).volume(), rel=1e-6)


def _polyline(rng, r, bends_rad):
    """A bent bar as a Bennett link draws one: out of a boss centre radially in its mid-plane (z), then
    runs of random length each turned by the next bend about a random axis."""
    d = np.array([*rng.normal(size=2), 0.0])
    d /= np.linalg.norm(d)
    pts = [np.zeros(3), d * (3.6 * r + rng.uniform(0, 2))]
    for bend in bends_rad:
        w = rng.normal(size=3)
        w -= (w @ d) * d
        w /= np.linalg.norm(w)
        d = math.cos(bend) * d + math.sin(bend) * w
        pts.append(pts[-1] + d * rng.uniform(8, 60))
    return np.array(pts)


def test_bar_paths_mitre_gentle_bends_and_knuckle_sharp_ones():
    from partgen.geometry.bennett_link import KNUCKLE_MM, MITRE_MAX_RAD, Bar, bar_paths

    rng = np.random.default_rng(3)
    r = 3.9
    bends = [math.radians(x) for x in (0.0, 2.0, 29.0, 31.0, 80.0)]
    pts = _polyline(rng, r, bends)
    bars = [Bar(tuple(a), tuple(b), r) for a, b in zip(pts, pts[1:])]
    bars.insert(2, Bar(bars[1].p1, bars[1].p1, r))  # a zero-length bar is dropped
    paths, knees = bar_paths(bars, [pts[0]])
    # 0°, 2° and 29° continue one path; 31° and 80° start new ones, each with a knuckle
    assert [ks for ks, _ in paths] == [[0, 1, 3, 4], [5], [6]]
    assert [k.mitred for k in knees] == [True, True, True, False, False]
    # the knee at the boss's exit belongs to the bar leaving the boss (the checks exempt it with that
    # bar from the parts stacked on its pin), every other one to the later bar
    assert [k.bar for k in knees] == [0, 3, 4, 5, 6]
    for k, b in zip(knees, (0.0, 2.0, 29.0)):
        assert k.radius == pytest.approx(r / math.cos(math.radians(b) / 2))  # covers the mitre's outer corner
    assert all(k.radius == pytest.approx(r + KNUCKLE_MM) for k in knees[3:])
    assert MITRE_MAX_RAD == pytest.approx(math.radians(30))
    # a path through a boss centre ends there, without a knee
    paths, knees = bar_paths(bars[:2], [pts[1]])
    assert [ks for ks, _ in paths] == [[0], [1]] and knees == []


def test_mitred_tube_lies_on_its_cylinders_and_holds_their_volume():
    from partgen.geometry.bennett_link import polyline_tube
    from partgen.geometry.solid import mesh_arrays

    rng = np.random.default_rng(5)
    r, n = 4.0, 48
    pts = _polyline(rng, r, [math.radians(x) for x in (5.0, 25.0, 12.0)])
    tube = polyline_tube(pts, r, n, phase=0.3)
    v, _ = mesh_arrays(tube)
    # every vertex but the two cap centres lies at r from the axis of a segment it belongs to, and
    # a mitre ring's vertices at r from both of its segments' axes
    a, b = pts[:-1], pts[1:]
    ab = b - a
    t = np.einsum("vkj,kj->vk", v[:, None] - a[None], ab) / np.einsum("kj,kj->k", ab, ab)
    dist = np.linalg.norm(v[:, None] - (a[None] + t[..., None] * ab[None]), axis=2)  # to each axis line
    on = np.abs(dist - r) < 1e-9
    caps = np.linalg.norm(v[:, None] - pts[[0, -1]][None], axis=2).min(1) < 1e-9
    assert np.all(on.any(axis=1) | caps) and caps.sum() == 2
    assert np.sum(on.sum(axis=1) >= 2) == n * (len(pts) - 2)  # the mitre rings
    # the mitres' wedges cancel: the volume is the polygon's area times the path's length
    area = 0.5 * n * r * r * math.sin(2 * math.pi / n)
    assert tube.volume() == pytest.approx(area * np.linalg.norm(ab, axis=1).sum(), rel=1e-9)


def test_random_bent_bars_write_one_shell_inside_their_capsules():
    """Sixty random bent bars (gentle and sharp bends, radius 3-5 mm, a boss at the start) at random
    print poses: each link, built at the first of LINK_PHASES whose float32 mesh stays sound (as the
    Bennett kit does), writes one closed shell, and lies inside the capsules the checks use."""
    from scipy.spatial.transform import Rotation

    from partgen.geometry import bennett_link as BL
    from partgen.geometry.capsules import segment_distance
    from partgen.geometry.solid import float32_sound, mesh_arrays

    rng = np.random.default_rng(11)
    for trial in range(60):
        r = rng.uniform(3, 5)
        bends = [rng.choice([rng.uniform(0, 1e-3), rng.uniform(0, 0.1), rng.uniform(0, 0.7), rng.uniform(0, 2.1)])
                 for _ in range(rng.integers(1, 4))]
        pts = _polyline(rng, r, bends) + rng.uniform(-150, 150, 3)
        bars = [BL.Bar(tuple(a), tuple(b), r) for a, b in zip(pts, pts[1:])]
        boss = BL.Boss(tuple(pts[0]), (0.0, 0.0, 1.0), 0.0, 2.6 * r, 2.2 * r, 1.3 * r)
        R = Rotation.random(random_state=int(rng.integers(1 << 31))).as_matrix()
        for phase in BL.LINK_PHASES:
            solid = BL.link_solid([boss], bars, [], 48, phase)
            v, f = mesh_arrays(solid)
            if float32_sound(v @ R.T, f):
                break
        rep = _written(solid, R)
        assert (rep.shells, rep.non_manifold_edges, rep.pinched_vertices, rep.boundary_edges) == (1, 0, 0, 0), trial
        ends, radii, _ = BL.capsules([boss], bars)
        gap = segment_distance(ends[None, :, 0], ends[None, :, 1], v[:, None], v[:, None]) - radii[None]  # (V, K)
        assert gap.min(axis=1).max() < 1e-6, trial


def test_segment_distance_to_a_point_is_the_same_both_ways():
    """A knee's ball is a zero-length capsule; the distance from a segment to it was its distance to
    the segment's first end when the point came second (a capsule sweep then missed a closer pair)."""
    from partgen.geometry.capsules import segment_distance

    rng = np.random.default_rng(2)
    p0, p1, q = rng.normal(size=(3, 200, 3))
    s = np.linspace(0, 1, 2001)
    brute = np.linalg.norm(p0[:, None] + s[None, :, None] * (p1 - p0)[:, None] - q[:, None], axis=2).min(axis=1)
    for got in (segment_distance(p0, p1, q, q), segment_distance(q, q, p0, p1)):
        assert np.allclose(got, brute, atol=1e-6)
