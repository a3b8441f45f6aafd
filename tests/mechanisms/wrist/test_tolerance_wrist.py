"""The wrist's tolerance model: each dome tooth in its socket over the workspace, and the cross gear
in mesh with its mate (docs/tolerance.md "Wrist"). Runs with tests/mechanisms/wrist/test_wrist.py
(its session kits, ``conftest.SHARED``)."""

import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from shapely import affinity
from shapely.geometry import Polygon

from partgen.core.findings import Result
from partgen.core.protocol import tolerance_hook
from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms.wrist.tolerance import DIRECTIONS, MATE_TILTS_DEG, MATE_UNIT, mate_turns


def jam(model, n: int = 4000) -> float:
    return summarise(model, run_chunk(model, 0, 0, n))["overall"]["probability"]


def clear(kit, clearance=None) -> tuple:
    """The kit (with another clearance: its spec's, as the model reads it) and a check result that found
    the sockets clear."""
    r = Result()
    r.figures["max_overlap_mm3"] = 0.0
    return (kit if clearance is None else replace(kit, spec=replace(kit.spec, clearance=clearance))), r


@pytest.fixture(scope="module")
def checked(kit_of):
    """The shipped wrist_sphere kit's check at 8 samples (the pair's poses and play, and its mate's: 3
    turns, 1 backlash pose), run once for the module: the dome model's test and the mate's read it."""
    b = kit_of("wrist_sphere")
    return b.loaded.mechanism.check(b.loaded.spec, b.kit, 8, None)


def test_wrist_model_from_its_check(kit_of, checked):
    b = kit_of("wrist_sphere")
    mech = b.loaded.mechanism
    result = checked
    assert result.figures["max_overlap_mm3"] == 0.0
    m = tolerance_hook(mech)(b.loaded.spec, b.kit, result, 0.127)
    domes = [k for k, x in enumerate(m.margins) if x.unit != MATE_UNIT]
    assert len(m.units) == len(b.kit.domes) + 1 == 20 and len(domes) == 19 * (DIRECTIONS + 1)
    assert len(m.margins) == len(domes) + 3 * len(mate_turns(b.kit.spec)) * len(MATE_TILTS_DEG)
    assert np.allclose(m.nominal[domes], b.loaded.spec.clearance)
    p = jam(m)
    assert 0.0 < p < 0.5
    # a dome's side gap falls by as much as the dome moves towards that side, and by half its growth
    k = next(i for i, x in enumerate(m.margins) if x.unit == "dome 3" and x.what == "side gap 0°")
    col = {f.name: m.coeff[i, k] for i, f in enumerate(m.features) if m.coeff[i, k]}
    assert col == {"gear1 domes": -0.5, "gear2 sockets": 0.5, "gear1 dome 3 u": -1.0, "gear2 socket 3 u": 1.0}
    seated, centred = m, tolerance_hook(mech)(b.loaded.spec, b.kit, result, 0.127, seated=False)
    assert np.array_equal(seated.nominal, centred.nominal)  # no bores: the worst case is the headline


def test_more_clearance_fewer_jams_and_an_overlap_jams(kit_of):
    b = kit_of("wrist_sphere")
    hook = tolerance_hook(b.loaded.mechanism)
    p = [jam(hook(b.loaded.spec, *clear(b.kit, c), 0.127)) for c in (0.10, 0.15, 0.25)]
    assert p[0] > p[1] > p[2], p
    assert jam(hook(b.loaded.spec, *clear(b.kit), 0.3)) > p[1]  # a worse printer jams more
    r = Result()
    r.figures["max_overlap_mm3"] = 0.5  # the nominal check found the sockets too tight
    assert jam(hook(b.loaded.spec, b.kit, r, 0.127)) > 0.99


# --- the cross gear and its mate -------------------------------------------------------------------

@pytest.fixture(scope="module")
def mate_checked(kit_of, checked):
    """(kit, the check's figures with the mate's) of the shipped wrist_sphere kit: the mate's part of
    ``checked`` (``mate_sampling(8)``: 3 turns at each tilt, 1 backlash pose)."""
    from partgen.mechanisms.wrist.checks import mate_sampling

    assert mate_sampling(8) == {"psi_samples": 3, "backlash_poses": 1}
    return kit_of("wrist_sphere").kit, checked


def mate_jam(model, n: int = 20000) -> float:
    s = summarise(model, run_chunk(model, 0, 0, n))
    return next(u["probability"] for u in s["units"] if u["unit"] == MATE_UNIT)


def test_the_mate_mesh_margins_read_the_check(kit_of, mate_checked):
    """The mesh's nominal backlash is the check's measured one; a flank moved out by e = δ/2 takes
    2e/cos α off it, the centre distance 2 tan α per mm; tip to root: the meshes' radii."""
    kit, r = mate_checked
    m = tolerance_hook(kit_of("wrist_sphere").loaded.mechanism)(kit.spec, kit, r, 0.127)
    ks = [k for k, x in enumerate(m.margins) if x.unit == MATE_UNIT]
    alpha = kit.spec.cross.system.pressure_angle
    col = lambda k: {f.name: m.coeff[i, k] for i, f in enumerate(m.features) if m.coeff[i, k]}  # noqa: E731
    for k in ks:
        x = m.margins[k]
        c = col(k)
        if x.what.startswith("backlash"):
            assert m.nominal[k] == r.figures["mate"]["backlash_min_mm"]
            assert c["cross_mate teeth"] == c["cross_gear teeth"] == pytest.approx(-1 / math.cos(alpha))
            # the centre distance's terms: a unit vector (the line of centres) in each part's frame, × 2 tan α
            mp = math.hypot(c.get("cross_mate bore x", 0.0), c.get("cross_mate bore y", 0.0))
            assert mp == pytest.approx(2 * math.tan(alpha))
        elif "cs→mp" in x.what:  # the generated root: the cutter's tip was the cross gear's grown by the clearance
            assert m.nominal[k] == pytest.approx(kit.spec.mate.clearance, abs=0.02)
            assert c["cross_mate teeth"] == -0.5
    # an overlapping pair: no margin left, only the prints that come out smaller everywhere turn
    bad = Result()
    bad.figures.update(max_overlap_mm3=0.0, mate={**r.figures["mate"], "max_overlap_mm3": 0.5})
    assert mate_jam(tolerance_hook(kit_of("wrist_sphere").loaded.mechanism)(kit.spec, kit, bad, 0.127)) > 0.5


def test_more_mate_clearance_fewer_mate_jams(kit_of, mate_checked):
    """The mate cut with less clearance (the same design otherwise), checked on its meshes: less
    backlash measured and more of its prints jam."""
    from partgen.geometry.cross_mate import mate_gear
    from partgen.mechanisms.wrist.mate import check_mate

    kit, r = mate_checked
    hook = tolerance_hook(kit_of("wrist_sphere").loaded.mechanism)
    tight_spec = replace(kit.spec, mate=replace(kit.spec.mate, clearance=kit.spec.mate.clearance / 2))
    solid, _ = mate_gear(tight_spec.cross, tight_spec.mate)
    tight = replace(kit, spec=tight_spec, parts=tuple(replace(p, solid=solid) if p.name == "cross_mate" else p
                                                      for p in kit.parts))
    rt = Result()
    rt.figures["max_overlap_mm3"] = 0.0
    check_mate(tight, rt, psi_samples=3, backlash_poses=1)
    assert rt.figures["mate"]["backlash_min_mm"] < r.figures["mate"]["backlash_min_mm"]
    p_tight, p_shipped = mate_jam(hook(tight_spec, tight, rt, 0.127)), mate_jam(hook(kit.spec, kit, r, 0.127))
    assert p_tight > p_shipped, (p_tight, p_shipped)
    assert mate_jam(hook(kit.spec, kit, r, 0.3)) > p_shipped  # a worse printer jams more


def _free_turns(touches, limit: float, tol: float = 1e-5) -> float:
    from partgen.checks.contact import free_turn

    return sum(free_turn(lambda d: touches(s * d), 0.0, limit, tol) for s in (1, -1))


def test_backlash_moves_as_the_model_says_with_the_centre_distance(kit_of, mate_checked):
    """Exact, on the meshes (the check's 3-D bisection, finer): the mate's bore moved 0.05 mm (its
    teeth moved off the cross gear along the line of centres) at one of the model's poses. The
    model's backlash margin there predicts 2 tan α · 0.05 mm = 0.036 mm more: within 10 %."""
    from partgen.geometry.cross_mate import cross_pose, mate_pose
    from partgen.geometry.measure import intersection
    from partgen.mechanisms.wrist.mate import TOUCH_MM3

    kit, r = mate_checked
    spec = kit.spec
    by = {p.name: p.solid for p in kit.parts}
    m = tolerance_hook(kit_of("wrist_sphere").loaded.mechanism)(spec, kit, r, 0.127)
    psi = float(mate_turns(spec)[1])
    k = next(i for i, x in enumerate(m.margins) if x.unit == MATE_UNIT and x.what.startswith("backlash")
             and f"ψ {math.degrees(psi):.0f}°, tilt 0°" in x.what)
    Tc, Tm = cross_pose(psi, spec.cross, spec.mate), mate_pose(psi, spec.cross, spec.mate)
    toward = Tm[:3, 3] / np.linalg.norm(Tm[:3, 3])
    n_mp = Tm[:3, :3].T @ -toward  # towards the cross gear, in the mate's frame
    e = 0.05
    bore = e * n_mp  # the bore moved towards the cross gear: on its shaft the teeth stand e further off it
    idx = {f.name: i for i, f in enumerate(m.features)}
    predicted = sum(m.coeff[idx[f"cross_mate bore {a}"], k] * bore[j] for j, a in enumerate("xy"))
    assert predicted == pytest.approx(2 * math.tan(spec.cross.system.pressure_angle) * e, rel=1e-9)

    def backlash(shift) -> float:
        def touches(d):
            T = mate_pose(psi + d, spec.cross, spec.mate)
            T[:3, 3] += shift
            return intersection(by["cross_gear"], Tc, by["cross_mate"], T)[0] > TOUCH_MM3
        return _free_turns(touches, math.radians(3.0)) * spec.mate.pitch_radius(spec.cross)

    j0, j1 = backlash(np.zeros(3)), backlash(-Tm[:3, :3] @ bore)  # the teeth move −bore, in the world
    assert j0 == pytest.approx(r.figures["mate"]["backlash_min_mm"], abs=0.01)
    assert j1 - j0 == pytest.approx(predicted, rel=0.1), (j0, j1, predicted)


def test_backlash_moves_as_the_model_says_with_the_mates_outline(mate_checked):
    """Exact in the mid-plane (the pair is a spur mesh there): the mate's generated section grown by
    e = 0.02 mm (its outline as a diameter δ = 2e) loses δ/cos α of backlash, as the model's
    coefficient says: within 10 %."""
    from partgen.geometry.cross_gear import GROW
    from partgen.geometry.cross_mate import cross_pose, mate_pose, mate_section
    from partgen.geometry.gear import gear_outline

    kit, _ = mate_checked
    cs, mate = kit.spec.cross, kit.spec.mate
    sec = mate_section(cs, mate)
    T = np.linalg.inv(mate_pose(0.0, cs, mate)) @ cross_pose(0.0, cs, mate)
    prof = np.asarray(Polygon(gear_outline(cs).points).buffer(GROW, join_style="mitre").exterior.coords)
    P = np.column_stack([np.zeros(len(prof)), prof]) @ T[:3, :3].T + T[:3, 3]
    window = shapely.Point(0, 0).buffer(mate.tip_radius(cs) + 1.0, 64)
    other = shapely.intersection(Polygon(P[:, :2]).buffer(0), window)  # the cross gear near the mate, mate frame

    def backlash(section) -> float:
        shapely.prepare(other)
        touches = lambda d: shapely.intersection(affinity.rotate(section, d, origin=(0, 0), use_radians=True),  # noqa: E731
                                                 other).area > 1e-9
        return _free_turns(touches, math.radians(3.0), 1e-7) * mate.pitch_radius(cs)

    e = 0.02
    j0, j1 = backlash(sec), backlash(sec.buffer(e, join_style="mitre"))
    predicted = -2 * e / math.cos(cs.system.pressure_angle)
    assert j0 == pytest.approx(2 * mate.clearance / math.cos(cs.system.pressure_angle), rel=0.05)
    assert j1 - j0 == pytest.approx(predicted, rel=0.1), (j0, j1, predicted)
