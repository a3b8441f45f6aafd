"""Twisted parts in the pairwise motion sweep: a helical gear's slabs are envelopes (the union of its
sections at five heights per slab), so the prism the sweep sees holds the solid at every height —
where the section at each slab's middle (a z-prism, exact only for straight gears) misses the
teeth's turn across the slab, and an obstacle the twisted tooth reaches goes unseen."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
import shapely
from shapely.geometry import Point

from partgen.checks.motion import ENVELOPE_HEIGHTS, prepare, sweep
from partgen.checks.settings import CheckSettings
from partgen.core.parts import Part
from partgen.design.gear_train import twist_over
from partgen.design.gearing import GearSpec, ToothSystem
from partgen.geometry.gear import helical_body
from partgen.geometry.measure import slabs, to_shapely
from partgen.geometry.outline import circle
from partgen.geometry.solid import slab

FACE = 10.0
TOL = 0.3  # mm: the twist's chord tolerance (coarse, so each slab turns far), and what the envelope grows by


@pytest.fixture(scope="module")
def helical():
    """A 40-tooth helical gear, 40° helix, twisted at a coarse chord tolerance: two slabs, its section
    turns 0.105 rad (4.4 mm at the tip) across each."""
    spec = GearSpec(40, ToothSystem(2.0, math.radians(20), 1.0, 1.25, 0.38, 0.1, None, 0.01), 0.0)
    twist = twist_over(FACE, math.radians(40), spec.pitch_radius)
    return helical_body(spec, FACE, circle(5.0, 0.01, hole=True), 0.0, twist, False, TOL)


def _outside(section, shape) -> float:
    """How far (mm) the section's outline (its vertices) reaches outside ``shape`` (0: inside it)."""
    xy = np.asarray(section.exterior.coords)
    out = ~shapely.contains_xy(shape, xy[:, 0], xy[:, 1])
    return float(shapely.distance(shape.boundary, shapely.points(xy[out])).max()) if out.any() else 0.0


def test_the_envelope_holds_every_section_the_middle_one_does_not(helical):
    grown = slabs(helical, ENVELOPE_HEIGHTS, TOL)  # grown by the twist's chord tolerance, as check_train does
    bare = slabs(helical, ENVELOPE_HEIGHTS)
    mid = slabs(helical)
    assert len(grown) == len(mid) == 2
    worst = {"grown": 0.0, "bare": 0.0, "mid": 0.0}
    for slabs_ in zip(grown, bare, mid):
        for z in np.linspace(slabs_[0].z0, slabs_[0].z1, 17):  # both faces and 15 heights between
            cut = to_shapely(helical.slice(float(np.clip(z, 1e-6, FACE - 1e-6))))
            for key, s in zip(worst, slabs_):
                worst[key] = max(worst[key], _outside(cut, s.shape))
    # measured: the middle section leaves the teeth 1.99 mm outside it near the slab's faces; the union
    # of five sections 0.034 mm (the mesh's facets between the sampled heights); grown by the twist's
    # chord tolerance, nothing
    assert worst["grown"] == 0.0
    assert worst["bare"] < 0.05
    assert worst["mid"] > 1.0


def _kit(gear, post):
    parts = (Part("gear", "gear", gear), Part("post", "frame", post))
    still = lambda ts: np.tile(np.eye(4), (len(np.atleast_1d(ts)), 1, 1))  # noqa: E731 (N poses, none moving)
    return SimpleNamespace(parts=parts, contacts=(), poses=lambda theta=0.0: {"gear": np.eye(4), "post": np.eye(4)},
                           poses_over=lambda ts: {"gear": still(ts), "post": still(ts)},
                           params=SimpleNamespace(checks=CheckSettings(1, 0.001, 0.3, 1.2, 2.0, 5.0)))


def test_an_obstacle_the_twisted_tooth_reaches_is_caught(helical):
    """A thin post standing where the tooth is at the bottom face but more than the sweep's reach
    (1 mm) from the slab's middle section: seen as a prism it passes; as an envelope it overlaps,
    and the exact 3-D measure confirms it."""
    bottom = slabs(helical)[0]
    near_face = to_shapely(helical.slice(0.05))
    room = near_face.difference(bottom.shape.buffer(1.3)).buffer(-0.2)
    assert not room.is_empty
    p = room.representative_point()
    post = slab(circle(0.15, 0.005, (p.x, p.y)), 0.0, 0.4)
    kit = _kit(helical, post)
    thetas = np.zeros(1)
    found_prism, _ = sweep(kit, prepare(kit), thetas)
    assert not found_prism  # the z-prism of the middle section misses it
    found, figures = sweep(kit, prepare(kit, {"gear"}, TOL), thetas)
    assert [f.check for f in found] == ["interference"] and found[0].value > 0.001
    assert bottom.shape.distance(Point(p.x, p.y)) > 1.0


def test_pruning_far_pairs_keeps_the_findings_and_still_sees_a_hit():
    """sweep(prune=True) on the planetary set: the same findings and gaps as without; with the sun
    grown into the carrier's pins (a pair that turns about one axis, radii overlapping) both find it."""
    import dataclasses
    from pathlib import Path

    from partgen import pipeline
    from partgen.geometry.solid import slab as prism

    loaded = pipeline.load(Path(__file__).resolve().parents[3] / "configs" / "gear_train_planetary.yaml")
    kit = loaded.mechanism.build(loaded.spec)
    thetas = np.linspace(0.0, loaded.spec.output_turn, 36, endpoint=False)
    plain = sweep(kit, prepare(kit), thetas)
    pruned = sweep(kit, prepare(kit), thetas, prune=True)
    assert plain[0] == pruned[0] and plain[1]["gaps"] == pruned[1]["gaps"]
    s = loaded.spec
    big = prism(circle(s.centre_distance, 0.05), s.gap + 1.0, s.gap + 2.0)  # a disc out to the pins' axes
    bad = dataclasses.replace(kit, parts=tuple(dataclasses.replace(p, solid=big) if p.name == "sun" else p
                                               for p in kit.parts))
    for prune in (False, True):
        found, _ = sweep(bad, prepare(bad), thetas, prune=prune)
        assert any(f.check == "interference" and set(f.parts) == {"sun", "carrier"} for f in found), prune
