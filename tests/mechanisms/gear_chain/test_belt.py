"""The belt variant: pulleys for the Eq 11 ratio, stock belts of whole teeth with tensioners,
parts that build and pass the check, and a curve within 0.5 mm of the gear version's."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import shapely
import pytest

from partgen import pipeline
from partgen.mechanisms.gear_chain.resolve import load as chain_load
from partgen.mechanisms.gear_chain.kit import belt_path_of, build_kit
from partgen.mechanisms.gear_chain.checks import check_kit
from partgen.design.belt import BeltProfile, belt_path, design_belt_stage, open_length
from partgen.design.synthesis import trace
from partgen.design.trace import built_chain
from partgen.export.kit import printed
from partgen.testing import mesh_problems, section_outline

ROOT = Path(__file__).resolve().parents[3]
GT2 = BeltProfile()


@pytest.fixture(scope="module")
def belt(kit_of):
    """(ChainSpec, kit) of the shipped belt design: the session's `partgen build` of it (``kit_of``)."""
    b = kit_of("butterfly_belt")
    # the config as `build` loads it (its backlash: auto, resolved once per process)
    assert b.loaded.spec == pipeline.load(ROOT / "configs" / "butterfly_belt.yaml").spec
    assert b.loaded.auto is not None and b.loaded.auto["backlash_per_gear_mm"] > 0
    return b.loaded.spec, b.kit


def test_belt_path_matches_the_open_belt_formula_and_its_own_polyline():
    length, pts = belt_path([((0.0, 0.0), 12.0, 1), ((80.0, 0.0), 7.0, 1)])
    assert length == pytest.approx(open_length(12.0, 7.0, 80.0), abs=1e-9)
    # equal pulleys: two straight spans and one full circle
    assert belt_path([((0, 0), 5.0, 1), ((30, 0), 5.0, 1)])[0] == pytest.approx(60 + 10 * math.pi)
    # the polyline it draws is that long too (chords a hair shorter than the arcs)
    poly = float(np.sum(np.hypot(*np.diff(np.vstack([pts, pts[:1]]), axis=0).T)))
    assert poly == pytest.approx(length, rel=2e-4)


def test_a_backside_idler_lengthens_the_path_by_the_geometry():
    """Idler of effective radius r on the lower span at depth v: the path is longer than the open
    belt; pushed further in, longer still."""
    base = open_length(10.0, 10.0, 60.0)
    lens = [belt_path([((0, 0), 10.0, 1), ((30, v), 4.0, -1), ((60, 0), 10.0, 1)])[0] for v in (-13.0, -10.0, -7.0)]
    assert base < lens[0] < lens[1] < lens[2]


@pytest.mark.parametrize("S,ratio", [(210.0, Fraction(2)), (60.0, Fraction(2)), (37.5, Fraction(9, 8)),
                                     (34.5, Fraction(5, 3)), (30.0, Fraction(7, 5))])
def test_stage_meets_eq11_with_a_whole_belt(S, ratio):
    stock = list(range(56, 131)) + [140, 150, 160, 175, 200, 250, 300]
    st = design_belt_stage(1, S, ratio, GT2, stock, 24, 1.5, 7.0, 0.5, -1)
    assert Fraction(st.D.teeth, st.G.teeth) == ratio
    assert st.belt_teeth in stock
    assert st.path_length == pytest.approx(st.belt_teeth * GT2.pitch, abs=1e-6)
    if st.tensioner is not None:
        assert st.link_change == 0.0 and st.length == S
        for centre, p in (((0.0, 0.0), st.D), ((S, 0.0), st.G)):  # the roller clears both flanges
            assert math.dist(st.tensioner, centre) >= st.tensioner_radius + p.outside_radius + 1.5 + 0.5 - 1e-9
    else:
        assert abs(st.link_change) < 1.0
        assert open_length(st.D.pitch_radius, st.G.pitch_radius, st.length) == pytest.approx(st.path_length, abs=1e-6)


def test_pulleys_measure_as_designed(belt):
    L, kit = belt
    s = L.mechanism.belt_stages[3]
    part = kit.part(f"D{s.j}")
    mesh = printed(part).mesh
    assert mesh_problems(mesh) == []
    sec = section_outline(mesh, L.params.face_width / 2)
    r = np.hypot(*np.asarray(sec.exterior.coords).T)
    assert 2 * r.max() == pytest.approx(2 * s.D.outside_radius, abs=0.02)
    assert 2 * r.min() == pytest.approx(2 * s.D.root_radius, abs=0.02)
    # one groove per tooth: a circle between root and tip crosses the material once per tooth
    from shapely.geometry import Point
    ring = Point(0, 0).buffer(s.D.outside_radius - 0.3, 2048).exterior
    pieces = shapely.line_merge(ring.intersection(sec))  # join the piece split at the ring's seam
    assert len(getattr(pieces, "geoms", [pieces])) == s.D.teeth


def test_belt_kit_builds_and_passes_its_check(belt, kit_of):
    L, kit = belt
    roles = {p.role for p in kit.parts}
    assert {"pulley", "idler", "belt"} <= roles and "gear" in roles  # G1 and the drive stay gears
    assert sum(p.role == "pulley" for p in kit.parts) == 2 * len(L.mechanism.belt_stages)
    for s in L.mechanism.belt_stages:
        length, _ = belt_path_of(s, s.D.profile)
        assert length == pytest.approx(s.belt_teeth * s.D.profile.pitch, abs=1e-6)
    result = check_kit(kit, 36)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    assert all(r[k] >= 6 for r in result.figures["belts"] for k in r if k.startswith("teeth_in_mesh"))
    man = kit_of("butterfly_belt").manifest  # the kit folder `build` wrote
    assert not any(p["role"] == "belt" for p in man["parts"])  # bought, not printed
    assert [b["teeth"] for b in man["purchased"]] == [s.belt_teeth for s in L.mechanism.belt_stages]
    assert {p["role"] for p in man["parts"]} >= {"pulley", "idler"}


def test_a_belt_through_a_part_is_caught(belt):
    """Both sides: move a tensioner 3 mm into its belt's far span — the sweep must see the belt
    hit something it must not."""
    from dataclasses import replace
    L, kit = belt
    st = L.mechanism.belt_stages[4]
    bad_stage = replace(st, tensioner=(st.tensioner[0], st.tensioner[1] - np.sign(st.tensioner[1]) * 9.0))
    stages = list(L.mechanism.belt_stages)
    stages[4] = bad_stage
    bad = build_kit(replace(L.mechanism, belt_stages=tuple(stages)), L.params)
    result = check_kit(bad, 12)
    assert not result.ok


def test_belt_curve_stays_within_half_a_millimetre_of_the_gear_version(belt):
    L, _ = belt
    gear = chain_load(ROOT / "configs" / "butterfly.yaml").mechanism
    theta = np.linspace(0, 2 * np.pi, 7200, endpoint=False)
    d = np.abs(trace(built_chain(L.mechanism), theta) - trace(built_chain(gear), theta)).max()
    assert d < 0.5
    assert d == pytest.approx(sum(abs(s.link_change) for s in L.mechanism.belt_stages), rel=0.2)
