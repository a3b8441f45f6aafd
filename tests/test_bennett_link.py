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


def test_bent_bars_do_not_pinch_where_they_meet(monkeypatch):
    """A link whose bent bars (boss centre → exit → exit → boss centre) met in equal balls came out
    of the union with bodies touching at vertices (a sweep design, kept in tests/data): a later bar
    at a shared point now ends in a ball SHARED_END_INSET_MM smaller, strictly inside the first's."""
    import json
    from pathlib import Path

    import trimesh

    from partgen.export.verify import mesh_report, read_stl
    from partgen.geometry import bennett_link as BL
    from partgen.geometry.solid import mesh_arrays

    d = json.loads((Path(__file__).parent / "data" / "bennett_pinched_link.json").read_text())
    inset = BL.SHARED_END_INSET_MM

    def written(mm: float):
        monkeypatch.setattr(BL, "SHARED_END_INSET_MM", mm)
        solid = BL.link_solid([BL.Boss(**b) for b in d["bosses"]], [BL.Bar(**b) for b in d["bars"]],
                              [BL.Cup(**c) for c in d["cups"]], d["segments"])
        v, f = mesh_arrays(solid)
        return mesh_report(*read_stl(trimesh.exchange.stl.export_stl(trimesh.Trimesh(v, f, process=False))))

    assert written(0.0).pinched_vertices > 0  # equal balls: the data reproduces the pinch
    r = written(inset)
    assert inset >= 0.02 and (r.shells, r.non_manifold_edges, r.pinched_vertices, r.boundary_edges) == (1, 0, 0, 0)
