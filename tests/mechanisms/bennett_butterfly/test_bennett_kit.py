"""The printed Bennett butterfly kit: bores on the joint axes (measured with pins on the meshes), the
capsule model containing every part, the common centre of mass at S from the meshes themselves,
the FDM mass model meeting the solid one at 100 % infill, stock pins held along their length, whole
slugs filling their pockets, the base, the print orientations, seeded faults that must show, and
the interference sampling bound; the layout's capsule sweep against brute force."""

import dataclasses
import itertools
import math

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

from partgen.mechanisms.bennett_butterfly import kit as A
from partgen.mechanisms.bennett_butterfly import layout as L
from partgen.mechanisms.bennett_butterfly.checks import check_bennett
from partgen.mechanisms.bennett_butterfly.resolve import resolve_bennett
from partgen.mechanisms import load_design
from partgen.design import bennett_butterfly as bbf
from partgen.geometry.bennett_link import place_on_axis
from partgen.geometry.capsules import capsule_clearance, segment_distance
from partgen.geometry.measure import intersection
from partgen.geometry.printing import bed_contact_area, flat_faces, overhang_area, shells
from partgen.geometry.solid import mesh_arrays

CFG = "configs/bennett_butterfly.yaml"


@pytest.fixture(scope="module")
def kit(kit_of):
    """The kit of the shipped design (CFG) as `build` makes it, the session's (tests/mechanisms/bennett_butterfly/test_bennett_cli.py
    and the manifest schema test share it)."""
    b = kit_of("bennett_butterfly")
    assert b.loaded.spec == resolve_bennett(load_design(CFG))
    return b.kit


@pytest.fixture(scope="module")
def result(kit):
    return check_bennett(kit)


def test_bores_lie_on_the_joint_axes(kit):
    """A pin a hair thinner than the bore, on the joint's axis over the boss's span, misses the link;
    one as thick as the boss's wall is thin hits it; a pin tilted 3° off the axis hits it too."""
    p = kit.params
    bore = p.pin_radius + p.pin_clearance / 2
    for i in (1, 2, 7, 12):
        solid = kit.solids[i]
        for j, (pt, ax) in kit.bodies[i].items():
            lo, hi = A.stack(p, kit.layout, j).spans[i]

            def pin(r, direction=ax):
                return place_on_axis(m3d.Manifold.cylinder(hi - lo + 4, r, -1.0, 64, True), pt, direction, (lo + hi) / 2)
            assert intersection(solid, np.eye(4), pin(bore - 0.05), np.eye(4))[0] == 0.0, (i, j)
            assert intersection(solid, np.eye(4), pin(bore + 0.5), np.eye(4))[0] > 1.0, (i, j)
            tilt = ax + math.tan(math.radians(3)) * np.cross(ax, [0.3, 0.4, 0.5]) / np.linalg.norm(np.cross(ax, [0.3, 0.4, 0.5]))
            assert intersection(solid, np.eye(4), pin(bore - 0.05, tilt), np.eye(4))[0] > 0.1, (i, j)


def test_capsules_contain_every_part(kit):
    """The sweep's capsules are conservative: every mesh vertex lies inside one of its part's capsules."""
    caps = A.link_capsules(kit.params, kit.layout, kit.bodies, kit.pockets)
    for i in range(0, 13):
        v, _ = mesh_arrays(kit.solids[i])
        ends, radii, _ = caps[i]
        d = segment_distance(v[:, None, :], v[:, None, :], ends[None, :, 0], ends[None, :, 1]) - radii[None]
        assert d.min(axis=1).max() < 1e-6, i


def test_centre_of_mass_from_the_meshes_stays_at_S(kit):
    """Solid model, independently: trimesh's mass properties of every link mesh, placed at a pose,
    plus pins and the fills (slugs and binder at their pocket's centre); agrees with the kit's own
    figure, and the kit as printed (FDM) balances."""
    p = kit.params
    rng = np.random.default_rng(5)
    for _ in range(4):
        q1 = rng.uniform(0, 2 * np.pi)
        q4 = q1 - rng.uniform(*p.workspace)
        frames = kit.frames(q1, q4)
        total, moment = 0.0, np.zeros(3)
        for i in range(1, 13):
            v, f = mesh_arrays(kit.solids[i])
            tm = trimesh.Trimesh(v, f, process=False)
            T = frames[i][0]
            pts = [(tm.volume * p.density, tm.center_mass)] + kit.pins[i]
            if i in kit.fills:
                pts.append((kit.fills[i].mass, kit.cups[i].pocket_centre))
            for m, c in pts:
                total += m
                moment += m * (T[:3, :3] @ c + T[:3, 3])
        ours = A.com_deviation(kit, "solid", np.array([q1]), np.array([q4]))[0]
        assert np.linalg.norm(moment / total) == pytest.approx(ours, abs=1e-6)
    q1, q4 = A.grid(p)
    assert A.com_deviation(kit, "fdm", q1, q4).max() < 1e-3


def test_fdm_model_at_full_infill_is_the_solid_model(kit):
    q1, q4 = A.grid(kit.params)
    a = A.com_deviation(kit, "fdm", q1, q4, infill=1.0)
    b = A.com_deviation(kit, "solid", q1, q4)
    assert np.abs(a - b).max() < 1e-9
    for i, lm in kit.masses.items():
        assert lm.fdm_mass < lm.solid_mass
        if i not in kit.cups:  # a bar link is about a third interior; a thin-walled cup is nearly all shell
            assert lm.fdm_mass < 0.8 * lm.solid_mass


def test_pins_are_stock_and_held_over_their_length(kit, result):
    """Every pin a stock length spanning its stack from the bottom boss's outer face to the top one's,
    measured on the solids: a ring just outside the bore is full of each member's material over its
    span, and short of the pin's ends there is nothing (the pin does not stand proud)."""
    p = kit.params
    for j in bbf.JOINTS:
        st = A.stack(p, kit.layout, j)
        assert st.length in p.pin_stock and st.pin[1] - st.pin[0] == pytest.approx(st.length)
        assert st.pin == (min(a for a, _ in st.spans.values()), max(b for _, b in st.spans.values()))
        for i, (a, b) in st.spans.items():
            pt, ax = (np.zeros(3), np.array([0.0, 0, 1])) if i == A.BASE else kit.bodies[i][j]
            ring = (place_on_axis(m3d.Manifold.cylinder(b - a - 0.2, p.bore_radius + 1.0, -1.0, 48, True), pt, ax, (a + b) / 2)
                    - place_on_axis(m3d.Manifold.cylinder(b - a + 2, p.bore_radius + 0.05, -1.0, 48, True), pt, ax, (a + b) / 2))
            assert (kit.solids[i] ^ ring).volume() == pytest.approx(ring.volume(), rel=0.01), (j, i)
        # beyond the ends: the end members' material stops at the pin's ends
        for i, z in ((st.members[0], st.pin[0] - 0.6), (st.members[-1], st.pin[1] + 0.6)):
            pt, ax = (np.zeros(3), np.array([0.0, 0, 1])) if i == A.BASE else kit.bodies[i][j]
            if i == A.BASE and z < st.pin[0]:
                continue  # the base's post goes on below its bore
            disc = place_on_axis(m3d.Manifold.cylinder(1.0, p.bore_radius + 1.0, -1.0, 48, True), pt, ax, z) - \
                place_on_axis(m3d.Manifold.cylinder(2.0, p.bore_radius + 0.05, -1.0, 48, True), pt, ax, z)
            assert (kit.solids[i] ^ disc).volume() < 0.05 * disc.volume(), (j, i)
    assert not [x for x in result.findings if x.check == "pins" and x.severity == "fail"]
    assert set(result.figures["pins"]["lengths_mm"].values()) <= set(p.pin_stock)


def test_pockets_hold_whole_slugs_exactly(kit):
    """Each pocket is a bore exactly as deep as its slugs stacked (measured: a probe a hair narrower
    than the bore fits to that depth and no further) and the fill's mass is steel plus the binder in
    the radial clearance."""
    p = kit.params
    for i, f in kit.fills.items():
        cup = kit.cups[i]
        assert f.length in p.slug_lengths and f.count >= 1
        axis = np.asarray(cup.axis, float) / np.linalg.norm(cup.axis)
        mouth = np.asarray(cup.point, float) + axis * cup.height

        def probe(depth):
            return place_on_axis(m3d.Manifold.cylinder(depth + 1, f.bore_radius - 0.05, -1.0, 64, False),
                                 mouth + axis, -axis, 0.0)
        assert intersection(kit.solids[i], np.eye(4), probe(f.depth - 0.05), np.eye(4))[0] < 1e-6
        assert intersection(kit.solids[i], np.eye(4), probe(f.depth + 0.3), np.eye(4))[0] > 1.0
        steel = f.count * p.slug_density * math.pi * (p.slug_diameter / 2) ** 2 * f.length
        binder = p.binder_density * math.pi * f.depth * (f.bore_radius ** 2 - (p.slug_diameter / 2) ** 2)
        assert f.mass == pytest.approx(steel + binder, rel=1e-12)


def test_fill_sensitivity_by_arithmetic(kit, result):
    """One slug short in a pocket: the kit's moment changes by the slug's mass at the top slug's
    centre; the binder left out: by the binder's mass at each pocket's centre — computed here from
    the pose directly and compared with the check's figures; leaving the binder out stays inside
    the tolerance here, a missing slug does not."""
    p = kit.params
    b = result.figures["balance_mm"]
    q1, q4 = A.grid(p)
    P = bbf.pose(p.bb, q1, q4)
    frames = bbf.link_frames(P)
    total = sum(lm.fdm_mass for lm in kit.masses.values()) + sum(m for i in kit.pins if i for m, _ in kit.pins[i])
    total += sum(f.mass for f in kit.fills.values())
    for i, f in kit.fills.items():
        cup = kit.cups[i]
        axis = np.asarray(cup.axis, float) / np.linalg.norm(cup.axis)
        top = cup.pocket_centre + axis * (f.depth - f.length) / 2
        T = frames[i]
        moved = f.slug_mass * (T[:, :3, :3] @ top + T[:, :3, 3])
        dev = np.linalg.norm(moved, axis=1) / (total - f.slug_mass)  # the kit as built balances: its moment is ~0
        assert b[f"one_slug_short_link{i:02d}"] == pytest.approx(dev.max(), abs=2e-3)
    binder = sum(f.binder_mass * (frames[i][:, :3, :3] @ kit.cups[i].pocket_centre + frames[i][:, :3, 3])
                 for i, f in kit.fills.items())
    total_b = total - sum(f.binder_mass for f in kit.fills.values())
    assert b["no_binder"] == pytest.approx((np.linalg.norm(binder, axis=1) / total_b).max(), abs=2e-3)
    assert b["no_binder"] < p.tolerance < min(v for k, v in b.items() if k.startswith("one_slug_short"))


def test_links_print_in_their_least_support_orientation(kit):
    """Each link's STL (its solid as laid on the bed) rests on the face the kit says, and no other
    flat face with the required contact needs less support (brute force over its flat faces)."""
    p = kit.params
    angle = math.degrees(p.overhang_angle)
    for part in kit.parts:
        if not part.printed:
            continue
        v, f = mesh_arrays(part.solid)
        assert v[:, 2].min() == pytest.approx(0.0, abs=1e-9)
        pose = kit.printing[part.name]
        assert overhang_area(v, f, (0, 0, -1.0), angle) == pytest.approx(pose.overhang_mm2, abs=1e-6)
        assert bed_contact_area(v, f) == pytest.approx(pose.contact_mm2, abs=1e-6)
        faces = flat_faces(v, f)
        ok = [d for d, a in faces if a >= p.min_contact] or [d for d, _ in faces]
        if ok:
            assert pose.overhang_mm2 <= min(overhang_area(v, f, d, angle) for d in ok) + 1e-6, part.name
        assert len(shells(v, f)) == 1, part.name


def test_base_stands_on_a_flat_foot_with_the_bore_open(kit, result):
    """The base as printed: one shell, a flat disc on the bed (section just above the bed = the
    foot's area), the S bore open from the top down to the pin's end (a rod slides in from above,
    and one 0.5 mm wider does not), and the centre of mass well inside the foot in every pose."""
    p = kit.params
    base = next(x for x in kit.parts if x.name == "base")
    v, f = mesh_arrays(base.solid)
    mesh = trimesh.Trimesh(v, f, process=False)
    assert len(shells(v, f)) == 1
    section = mesh.section(plane_origin=(0, 0, 0.01), plane_normal=(0, 0, 1)).to_2D()[0]
    assert section.area == pytest.approx(math.pi * p.foot_radius ** 2, rel=0.01)
    assert section.area >= 100.0
    assert bed_contact_area(v, f) == pytest.approx(section.area, rel=0.01)
    top = v[:, 2].max()
    lo, hi = A.stack(p, kit.layout, "S14").spans[A.BASE]
    depth = hi - lo
    rod = lambda r, d: m3d.Manifold.cylinder(d + 5, r, -1.0, 64, False).translate((0, 0, top - d))  # noqa: E731
    assert (base.solid ^ rod(p.pin_radius, depth - 0.01)).volume() < 1e-6
    assert (base.solid ^ rod(p.pin_radius, depth + 0.5)).volume() > 1.0
    assert (base.solid ^ rod(p.bore_radius + 0.5, depth - 0.01)).volume() > 1.0
    st = result.figures["base"]
    assert st["margin_mm"] > 0.9 * p.foot_radius and st["tip_angle_deg"] >= math.degrees(p.min_tip_angle)
    assert st["links_above_table_mm"] > 0


def test_check_figures(kit, result):
    f = result.figures
    assert result.ok, [x.message for x in result.findings if x.severity == "fail"]
    b = f["balance_mm"]
    assert b["fdm"] < 1e-3 < b["fdm_infill_error"] < b["solid"]
    assert f["least_clearance_mm"] > 0 and f["joint_stack_overlap_mm3"] == 0.0
    lo, hi = (math.degrees(x) for x in kit.params.workspace)
    assert f["free_range_deg"][0] <= lo and f["free_range_deg"][1] >= hi


def test_ten_percent_heavier_link_shows(kit):
    """At a 0.1 mm balance tolerance (the printer's resolution: the shipped design allows 0.3, what the
    pins' friction holds) a link printed 10 % heavier fails the balance check."""
    heavy = dataclasses.replace(kit, params=dataclasses.replace(kit.params, mass_scale=((5, 1.1),), tolerance=0.1))
    r = check_bennett(heavy)
    assert not r.ok
    assert r.figures["balance_mm"]["what_if_mass_scale"] > heavy.params.tolerance
    assert any(x.check == "balance" and x.severity == "fail" for x in r.findings)


def test_crossing_pins_are_caught(kit):
    """Seeded fault: the S101 and S710 stacks pulled through S (main's layout had them so) run the
    two pins through each other inside link 10; the layout model and the check both see it."""
    lay = A.Layout(kit.layout.layer, {**kit.layout.shift, "S710": -8.0, "S101": 0.0})
    p = kit.params
    ends, radii, tags = A.part_capsules(p, lay, kit.bodies, 10)
    room, what = A.own_clearance(p, lay, kit.bodies, 10, ends, radii, tags)
    assert room < -1.0 and ("S101" in what or "S710" in what), what
    bad = dataclasses.replace(kit, layout=lay)
    r = check_bennett(bad)
    assert any(x.check == "pins" and x.severity == "fail" and "link10" in x.parts for x in r.findings)


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
    reach = A.part_reach(p, kit.layout, kit.bodies, kit.pockets)
    speed = A.point_speed(p, *p.workspace, reach)
    coarse, step = A.shape_samples(p, *p.workspace, speed)
    fine = np.linspace(*p.workspace, 4 * (len(coarse) - 1) + 1)
    sweep = A.Sweep(p, fine, kit.bodies, kit.pockets)
    for i, c in sweep.capsules(kit.layout).items():
        if i == A.BASE:
            continue
        v = np.linalg.norm(np.diff(c.ends, axis=0), axis=-1) / np.diff(fine)[:, None, None]
        assert v.max() <= speed, i
    c = A.Sweep(p, coarse, kit.bodies, kit.pockets).profile(kit.layout)
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


@pytest.fixture(scope="module")
def fixed():
    """(resolved design, bodies) of the shipped design with its layout pinned (no search, no kit)."""
    p = resolve_bennett(load_design("tests/designs/bennett_fixed.yaml"))
    return p, A.bbf.body_joints(p.bb)


def _brute(caps, a, b):
    ca, cb = caps[a], caps[b]
    shared = L._shared(a, b)
    keep = np.array([[not (set(ta[1:]) & set(tb[1:]) & shared) for tb in cb.tags] for ta in ca.tags])
    if not keep.any():
        return None
    return float(np.where(keep[None], capsule_clearance(ca.ends, ca.radii, cb.ends, cb.radii), np.inf).min())


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_sweep_is_brute_force_under_its_threshold(seed, fixed):
    """The Bennett layout's capsule sweep, as the search and the check use it (batched, pruned by
    bounding spheres, remembered per part state), against brute force: every capsule pair of every
    pair of parts measured, features at a shared joint left out (tests/designs/bennett_fixed.yaml)."""
    P, BODIES = fixed
    rng = np.random.default_rng(seed)
    lay = A.Layout({A.BASE: 0, **{i: int(rng.integers(1, 7)) for i in range(1, 13)}},
                   {j: float(rng.choice([-20, -10, 0, 10, 20])) for j in A.bbf.JOINTS})
    angles = np.linspace(*P.workspace, 6)
    sweep = L.Sweep(P, angles, BODIES, below=8.0)
    got = sweep.all(lay)
    caps = sweep.capsules(lay)
    least = min(v for v, _ in got.values())
    for a, b in itertools.combinations(range(13), 2):
        want = _brute(caps, a, b)
        if want is None:
            assert (a, b) not in got
        elif want < 8.0:
            assert got[(a, b)][0] == pytest.approx(want, abs=1e-9), (a, b)
        else:
            assert 8.0 - 1e-9 <= got[(a, b)][0] <= want + 1e-9, (a, b)
    assert least == pytest.approx(min(x for a, b in itertools.combinations(range(13), 2)
                                      if (x := _brute(caps, a, b)) is not None), abs=1e-9)
    # a trial that moves one stack is measured again only where it changed, to the same result
    trial = A.Layout(lay.layer, {**lay.shift, "B2": lay.shift["B2"] + 10.0})
    again = sweep.all(trial)
    fresh = L.Sweep(P, angles, BODIES, below=8.0).all(trial)
    assert again.keys() == fresh.keys()
    assert all(again[k][0] == pytest.approx(fresh[k][0], abs=1e-9) and again[k][1] == fresh[k][1] for k in again)
    # the per-angle profile's least is the pairs' least
    assert sweep.profile(lay).min() == pytest.approx(min(least, 8.0), abs=1e-9)


def test_the_searched_layout_is_remembered_and_rebuilds_the_same_parts(kit, monkeypatch):
    """The layout search's answer is kept in partgen's cache (core.cache) under the resolved design:
    a second build of the same design does not search (the search would fail here) and makes the
    same parts, byte for byte, with the same figures; another design is another key."""
    from partgen.core.cache import recall
    import pickle

    known = recall("bennett-layout", pickle.dumps(kit.params, protocol=5))
    assert known is not None and dict(map(tuple, known["layer"])) == {int(k): v for k, v in kit.layout.layer.items()}

    def no_search(*a, **k):
        raise AssertionError("searched again")
    monkeypatch.setattr(A, "search_layout", no_search)
    again = A.build_bennett(kit.params)
    assert again.layout == kit.layout
    assert again.figures["search_clearance_mm"] == kit.figures["search_clearance_mm"]
    stl = lambda k: {p.name: mesh_arrays(p.solid) for p in k.parts if p.printed}  # noqa: E731
    a, b = stl(kit), stl(again)
    assert a.keys() == b.keys()
    for name in a:
        assert np.array_equal(a[name][0], b[name][0]) and np.array_equal(a[name][1], b[name][1]), name
    other = dataclasses.replace(kit.params, offset_step=kit.params.offset_step / 2)
    assert recall("bennett-layout", pickle.dumps(other, protocol=5)) is None


def test_a_part_is_reused_only_under_the_numbers_that_weigh_and_lay_it():
    """``kit._PartMemo`` (the parts a process built, reused by its later builds): a part built under a
    design is handed back under the same key and numbers, and never under another density, infill,
    wall, skin, overhang rule or least bed contact (each changes its masses or its print pose)."""
    p = resolve_bennett(load_design(CFG))
    key, built = ("link", "memo-test-part"), object()
    A._PartMemo(p)[key] = built
    assert A._PartMemo(p)[key] is built and key in A._PartMemo(dataclasses.replace(p))
    for change in ({"density": p.density * 1.01}, {"infill": p.infill + 0.05}, {"print_wall": p.print_wall + 0.4},
                   {"print_skin": p.print_skin + 0.2}, {"overhang_angle": p.overhang_angle + 0.1},
                   {"min_contact": p.min_contact + 1.0}):
        other = A._PartMemo(dataclasses.replace(p, **change))
        assert key not in other and other.get(key) is None, change
    assert ("link", "never built") not in A._PartMemo(p)


def test_least_per_pair_is_the_stable_sorts_first():
    """The sweep's least clearance of each part pair (and where it is) without a sort: the index a
    stable sort by (pair, clearance) puts first, ties included (clearances on a 0.1 mm grid tie often)."""
    rng = np.random.default_rng(26)
    for n in (1, 7, 500, 20000):
        d = np.round(rng.normal(3.0, 2.0, n), 1)
        pair = rng.integers(0, 169, n)
        order = np.lexsort((d, pair))
        keys, first = np.unique(pair[order], return_index=True)
        assert L._least_per_pair(d, pair) == dict(zip(keys.tolist(), order[first].tolist()))
    assert L._least_per_pair(np.zeros(0), np.zeros(0, int)) == {}
