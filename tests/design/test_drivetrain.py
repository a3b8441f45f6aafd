"""Eq 11 ratios, tooth counts (explicit and auto), Eq 12-13, idler placement, mesh clocking."""

import math
from collections import Counter
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import yaml

from partgen.design.drivetrain import Limits, choose_stage, eq11_ratios, idler_centre, make_stage, verify_stage
from partgen.design.gearing import ToothSystem, make_gear
from partgen.design.kinematics import gear_poses, mesh_phase_error
from partgen.errors import DesignError
from partgen.mechanisms.gear_chain.resolve import load

ROOT = Path(__file__).resolve().parents[2]
TABLE3 = yaml.safe_load((Path(__file__).resolve().parents[1] / "data" / "liu2017_table3_manufacturing.yaml").read_text())
PAPER = ToothSystem(module=1.5, pressure_angle=math.radians(20), profile_shift=0.0)


def test_table3_teeth_satisfy_eq11_exactly():
    rows = TABLE3["rows"]
    speeds = [r[1] for r in rows]
    ratios = eq11_ratios(speeds)
    for r, (j, k, name, S, delta, td, tm, tg) in zip(ratios, rows[:-1]):
        w = [0] + speeds
        assert Fraction(td, tg) == r == Fraction(w[j + 1] - w[j], w[j - 1] - w[j])


@pytest.fixture(scope="module")
def default():
    return load(ROOT / "configs" / "butterfly.yaml")


@pytest.fixture(scope="module")
def paper():
    return load(ROOT / "configs" / "butterfly_liu2017.yaml")


def test_auto_teeth_satisfy_eq11_eq12_eq13_with_margin(default):
    mech, params = default.mechanism, default.params
    ratios = eq11_ratios(mech.chain.speeds)
    m = params.system.module
    for s, r in zip(mech.stages, ratios):
        assert Fraction(s.D.teeth, s.G.teeth) == r  # Eq 11 exactly
        # Eq 12 with the config's tip gap, on the real (shifted) tip radii
        assert s.length - s.D.tip_radius - s.G.tip_radius >= 1.5 - 1e-9
        assert m / 2 * (s.D.teeth + s.G.teeth) + 2 * m < s.length  # Eq 12 as the paper writes it
        assert m / 2 * (3 * s.D.teeth + s.G.teeth) >= s.length or m / 2 * (s.D.teeth + 3 * s.G.teeth) >= s.length
        assert s.a_DM + s.a_MG >= s.length + 1.0 - 1e-9  # the idler reaches, with margin
        for g in (s.D, s.M, s.G):
            assert g.module * g.teeth >= params.printer.min_gear - 1e-9
            assert 2 * g.root_radius >= params.min_root_diameter - 1e-9
            assert not g.undercut
    assert not [f for f in mech.findings if f.severity == "warn"]


def test_idler_sits_at_both_centre_distances(default, paper):
    for loaded in (default, paper):
        for s in loaded.mechanism.stages:
            u, v = s.idler
            assert math.hypot(u, v) == pytest.approx(s.a_DM, abs=1e-9)
            assert math.hypot(u - s.length, v) == pytest.approx(s.a_MG, abs=1e-9)


def test_paper_link1_idler_is_in_line():
    """80/80/40 at m = 1.5 on 210 mm: m/2 (80 + 2·80 + 40) = 210 exactly, so the idler stands in
    line with D and G: Eq 13 holds with no margin at all."""
    assert idler_centre(210.0, 120.0, 90.0) == pytest.approx((120.0, 0.0), abs=1e-9)
    assert idler_centre(210.0, 100.0, 90.0) is None


def test_minimax_objective_reproduces_paper_link1():
    """Without margins, the smallest-largest-gear choice on the paper's link 1 is its 80/80/40."""
    limits = Limits(min_pitch_diameter=15.0, min_root_diameter=0.0, tip_gap=0.0, idler_reach=0.0)
    st = choose_stage(1, 210.0, Fraction(2), PAPER, limits)
    assert (st.D.teeth, st.M.teeth, st.G.teeth) == (80, 80, 40)


def test_paper_link10_violates_eq12(paper):
    """21 + 15 teeth at m = 1.5 with a 1.5 mm addendum on a 30 mm link: the tip circles touch."""
    codes = {(f.rule, f.key) for f in paper.mechanism.findings}
    assert ("eq12", "teeth[9]") in codes
    s = paper.mechanism.stages[9]
    assert s.length - s.D.tip_radius - s.G.tip_radius == pytest.approx(0.0, abs=1e-12)


def test_paper_15_tooth_gears_are_reported_undercut(paper):
    undercut = {f.message.split(":")[1].strip().split(" ")[0] + str(f.key) for f in paper.mechanism.findings
                if f.rule == "undercut"}
    assert undercut  # 15- and 16-tooth gears at x = 0
    assert all(f.severity == "info" for f in paper.mechanism.findings if f.rule == "undercut")
    fifteen = [g for _, g in paper.mechanism.gears if g.teeth == 15]
    assert fifteen and all(g.undercut for g in fifteen)


def test_verify_flags_ratio_off_eq11():
    limits = Limits(15.0, 0.0, 0.0, 0.0)
    st = make_stage(1, 60.0, Fraction(2), (36, 18, 19), PAPER)
    assert "eq11" in {f.rule for f in verify_stage(st, limits, "teeth[0]")}
    good = make_stage(1, 60.0, Fraction(2), (36, 18, 18), PAPER)
    assert "eq11" not in {f.rule for f in verify_stage(good, limits, "teeth[0]")}


def test_no_teeth_for_the_ratio_is_a_design_error():
    limits = Limits(15.0, 16.0, 1.5, 1.0)
    with pytest.raises(DesignError, match="Eq 11 ratio 7/5") as e:
        choose_stage(10, 30.0, Fraction(7, 5), ToothSystem(module=2.0, pressure_angle=math.radians(20)), limits)
    assert e.value.key_path == "teeth"


def test_infeasible_idler_is_a_design_error():
    with pytest.raises(DesignError) as e:
        make_stage(1, 210.0, Fraction(2), (40, 15, 20), PAPER)
    assert e.value.key_path == "teeth[0].M"


@pytest.mark.parametrize("speeds,msg", [([1, 1, 3], "same speed"), ([1, 2, 3], "negative")])
def test_eq11_rejects_impossible_speeds(speeds, msg):
    with pytest.raises(DesignError, match=msg):
        eq11_ratios(speeds)


@pytest.mark.parametrize("which", ["default", "paper"])
def test_meshes_interleave_over_the_whole_cycle(which, default, paper):
    """Clocked at θ = 0, every meshing pair stays interleaved over a full crank turn: the idler
    kinematics and Eq 11 agree (a pair off by a tooth fraction would drift)."""
    mech = (default if which == "default" else paper).mechanism
    for theta in np.linspace(0, 2 * np.pi, 97):
        err = mesh_phase_error(mech, float(theta))
        assert max(abs(e) for e in err.values()) < 1e-9, (theta, err)


def test_off_ratio_teeth_drift_out_of_mesh(paper):
    """Seeded fault: change one gear's teeth without re-deriving the motion and the mesh phase
    must drift — proof the check above can fail."""
    from dataclasses import replace
    mech = paper.mechanism
    stages = list(mech.stages)
    stages[1] = replace(stages[1], G=make_gear(stages[1].G.teeth + 1, stages[1].G.system))
    bad = replace(mech, stages=tuple(stages))
    worst = max(max(abs(e) for e in mesh_phase_error(bad, float(t), None).values())
                for t in np.linspace(0, 2 * np.pi, 37))
    assert worst > 0.05


def test_gear_poses_follow_eq11(default):
    """G_{j+1}, driven through the idler, turns with link j+1: its angle is α_{j+1} + clocking."""
    mech = default.mechanism
    p0, p1 = gear_poses(mech, 0.0), gear_poses(mech, 0.3)
    for s, link in zip(mech.stages, mech.chain.links[1:]):
        turned = p1[f"G{s.j + 1}"].angle - p0[f"G{s.j + 1}"].angle
        assert turned == pytest.approx(link.speed * 0.3, abs=1e-12)


def test_the_teeth_search_is_remembered_by_what_it_reads():
    """``teeth: auto``'s search is pure: a second ask of the same link, ratio, tooth system and the
    limits it reads gives the first answer without searching; the limits it does not read (the axle,
    whether a refusal advises) share it, one it reads (the smallest gear) does not; its Counter of the
    rules that turned teeth away is the caller's own to change."""
    from partgen.design import drivetrain as dt
    from partgen.design.rules import GearRules

    sys_ = ToothSystem(module=1.3, pressure_angle=math.radians(20), profile_shift=None)
    lim = Limits(min_pitch_diameter=11.0, min_root_diameter=9.0, tip_gap=1.5, idler_reach=1.0,
                 rules=GearRules(min_contact_ratio=1.2, min_tip_width=0.9), axle_diameter=3.0, min_axle_diameter=2.0)
    dt._searched.cache_clear()
    first = dt._search(60.0, Fraction(3, 2), sys_, lim)
    assert dt._searched.cache_info().misses == 1 and first[0] is not None
    first[2]["tip-width"] += 100
    assert dt._search(60.0, Fraction(3, 2), sys_, replace(lim, axle_diameter=4.0, advise=False)) == \
        (first[0], first[1], first[2] - Counter({"tip-width": 100}))
    assert dt._searched.cache_info().hits == 1
    assert choose_stage(1, 60.0, Fraction(3, 2), sys_, lim) == make_stage(1, 60.0, Fraction(3, 2), first[0], sys_)
    larger = dt._search(60.0, Fraction(3, 2), sys_, replace(lim, min_pitch_diameter=30.0))
    assert dt._searched.cache_info().misses == 2 and larger[1] > first[1] and larger[0] != first[0]
