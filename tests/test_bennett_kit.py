"""The printed Bennett butterfly kit: bores on the joint axes (measured with pins on the meshes), the
capsule model containing every part, the common centre of mass at S from the meshes themselves,
the FDM mass model meeting the solid one at 100 % infill, seeded faults that must show, and the
interference sampling bound."""

import dataclasses
import math

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

from partgen.assembly import bennett as A
from partgen.checks.bennett import check_bennett
from partgen.config.bennett import resolve_bennett
from partgen.config.loader import load_design
from partgen.design import bennett_butterfly as bbf
from partgen.geometry.bennett_link import _place
from partgen.geometry.capsules import segment_distance
from partgen.geometry.measure import intersection
from partgen.geometry.solid import mesh_arrays

CFG = "tests/designs/bennett_fixed.yaml"


@pytest.fixture(scope="module")
def kit():
    return A.build_bennett(resolve_bennett(load_design(CFG)))


@pytest.fixture(scope="module")
def result(kit):
    return check_bennett(kit)


def _solid(kit, i):
    return next(p.solid for p in kit.parts if p.name == f"link{i:02d}")


def test_bores_lie_on_the_joint_axes(kit):
    """A pin a hair thinner than the bore, on the joint's axis, misses the link; one as thick as the
    boss's wall is thin hits it; a pin tilted 3° off the axis hits it too."""
    p = kit.params
    bore = p.pin_radius + p.pin_clearance / 2
    for i in (1, 2, 7, 12):
        solid = _solid(kit, i)
        for j, (pt, ax) in kit.bodies[i].items():
            off = kit.layout.offset(j, i, p.pitch)
            def pin(r, direction=ax):
                return _place(m3d.Manifold.cylinder(p.boss_length + 4, r, -1.0, 64, True), pt, direction, off)
            assert intersection(solid, np.eye(4), pin(bore - 0.05), np.eye(4))[0] == 0.0, (i, j)
            assert intersection(solid, np.eye(4), pin(bore + 0.5), np.eye(4))[0] > 1.0, (i, j)
            tilt = ax + math.tan(math.radians(3)) * np.cross(ax, [0.3, 0.4, 0.5]) / np.linalg.norm(np.cross(ax, [0.3, 0.4, 0.5]))
            assert intersection(solid, np.eye(4), pin(bore - 0.05, tilt), np.eye(4))[0] > 0.1, (i, j)


def test_capsules_contain_every_part(kit):
    """The sweep's capsules are conservative: every mesh vertex lies inside one of its part's capsules."""
    caps = A.link_capsules(kit.params, kit.layout, kit.bodies, kit.delta)
    for i in range(1, 13):
        v, _ = mesh_arrays(_solid(kit, i))
        ends, radii, _ = caps[i]
        d = segment_distance(v[:, None, :], v[:, None, :], ends[None, :, 0], ends[None, :, 1]) - radii[None]
        assert d.min(axis=1).max() < 1e-6, i


def test_centre_of_mass_from_the_meshes_stays_at_S(kit):
    """Solid model, independently: trimesh's mass properties of every link mesh, placed at a pose,
    plus pins and fills; agrees with the kit's own balance figure and is at S as printed."""
    p = kit.params
    rng = np.random.default_rng(5)
    for _ in range(4):
        q1 = rng.uniform(0, 2 * np.pi)
        q4 = q1 - rng.uniform(*p.workspace)
        place = kit.placements(q1, q4)
        total, moment = 0.0, np.zeros(3)
        for i in range(1, 13):
            v, f = mesh_arrays(_solid(kit, i))
            tm = trimesh.Trimesh(v, f, process=False)
            m = tm.volume * p.density
            T = place[f"link{i:02d}"]
            total += m
            moment += m * (T[:3, :3] @ tm.center_mass + T[:3, 3])
            for mp, pp in kit.pins[i]:
                total += mp
                moment += mp * (T[:3, :3] @ pp + T[:3, 3])
            if i in kit.fill["solid"]:
                f_ = kit.fill["fdm"][i]
                total += f_
                moment += f_ * (T[:3, :3] @ kit.cups[i].pocket_centre + T[:3, 3])
        ours = A.com_deviation(kit, "solid", np.array([q1]), np.array([q4]), fill=kit.fill["fdm"])[0]
        assert np.linalg.norm(moment / total) == pytest.approx(ours, abs=1e-6)
    q1, q4 = A.grid(p)
    assert A.com_deviation(kit, "fdm", q1, q4).max() < 1e-3


def test_fdm_model_at_full_infill_is_the_solid_model(kit):
    q1, q4 = A.grid(kit.params)
    a = A.com_deviation(kit, "fdm", q1, q4, infill=1.0)
    b = A.com_deviation(kit, "solid", q1, q4, fill=kit.fill["fdm"])
    assert np.abs(a - b).max() < 1e-9
    for i, lm in kit.masses.items():
        assert lm.fdm_mass < lm.solid_mass
        if i not in kit.cups:  # a bar link is about a third interior; a thin-walled cup is nearly all shell
            assert lm.fdm_mass < 0.8 * lm.solid_mass


def test_check_figures(kit, result):
    f = result.figures
    assert result.ok, [x.message for x in result.findings if x.severity == "fail"]
    b = f["balance_mm"]
    assert b["fdm"] < 1e-3 < b["fdm_infill_error"] < b["solid_weights_printed_fdm"]
    assert f["least_clearance_mm"] > 0 and f["joint_stack_overlap_mm3"] == 0.0
    lo, hi = (math.degrees(x) for x in kit.params.workspace)
    assert f["free_range_deg"][0] <= lo and f["free_range_deg"][1] >= hi


def test_ten_percent_heavier_link_shows(kit):
    heavy = dataclasses.replace(kit, params=dataclasses.replace(kit.params, mass_scale=((5, 1.1),)))
    r = check_bennett(heavy)
    assert not r.ok
    assert r.figures["balance_mm"]["what_if_mass_scale"] > kit.params.tolerance
    assert any(x.check == "balance" and x.severity == "fail" for x in r.findings)


def test_stacks_without_a_gap_are_caught(kit):
    """Seeded fault: bosses on a pin closer than a boss is long overlap, and the
    exact stack measurement finds it."""
    p = dataclasses.replace(kit.params, axial_gap=-5.0)  # pitch 3 mm: two layers apart is 6 mm < an 8 mm boss
    bad = A.build_bennett(p, lay=kit.layout)
    r = check_bennett(bad)
    assert r.figures["joint_stack_overlap_mm3"] > 1.0 and not r.ok


def test_sampling_step_bounds_the_clearance(kit):
    """The speed bound holds for every capsule end of every part (finite differences on a grid four
    times finer than the check's), and a sweep at a quarter of the step finds no clearance smaller
    than the check's by more than a bar's diameter."""
    p = kit.params
    reach = A.part_reach(p, kit.layout, kit.bodies, kit.delta)
    speed = A.point_speed(p, *p.workspace, reach)
    coarse, step = A.shape_samples(p, *p.workspace, speed)
    fine = np.linspace(*p.workspace, 4 * (len(coarse) - 1) + 1)
    sweep = A.Sweep(p, fine, kit.bodies, kit.delta)
    for i, (ends, _, _, _) in sweep.capsules(kit.layout).items():
        if i == A.BASE:
            continue
        v = np.linalg.norm(np.diff(ends, axis=0), axis=-1) / np.diff(fine)[:, None, None]
        assert v.max() <= speed, i
    c = A.Sweep(p, coarse, kit.bodies, kit.delta).profile(kit.layout)
    f = sweep.profile(kit.layout)
    assert f.min() >= c.min() - 2 * p.bar_radius
    assert f.min() <= c.min() + 1e-9  # the fine sweep includes every coarse sample
    assert step * speed <= p.bar_radius + 1e-9


def test_the_search_improves_on_the_default_layout(kit):
    p = dataclasses.replace(kit.params, offset_max=12.0, offset_step=12.0)
    angles = np.linspace(*p.workspace, 5)
    before = min(v for v, _ in A.sweep_clearance(p, A.default_layout(), angles, kit.bodies).values())
    lay, after = A.choose_offsets(p, angles, kit.bodies, layers=6, rounds=1)
    assert after > before
    for j in bbf.JOINTS:
        members = lay.members(j)
        assert len({lay.layer[i] for i in members}) == len(members)
