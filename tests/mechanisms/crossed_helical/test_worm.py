"""A single-start ZI worm and a plain helical wheel (kind crossed_helical with one thread): the
thread's transverse section is the involute of its base circle (measured on the float32 mesh at
three heights, µm), the pair meshes exactly in 3-D at phases over a worm turn (0 mm³, > 0 with the
backlash made negative), its backlash is the designed one, the ratio is 30, and the self-locking
answer follows from the lead angle and the stated friction."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import trimesh

from partgen.design.crossed_helical import ThreadSpec, crossed_pair, efficiency, friction_angle
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.crossed_helical.contact import contact_angles, designed_backlash, mesh_overlaps
from partgen.mechanisms.crossed_helical.kit import build_crossed, locking
from partgen.mechanisms.crossed_helical.mechanism import MECHANISM
from partgen.mechanisms.crossed_helical.resolve import gear_spec, is_worm
from partgen.testing import measure_worm_flanks, mesh_problems


@pytest.mark.parametrize("lead_deg", [5.0, 9.0, 9.2, 15.0, 30.0])
def test_worm_efficiency_and_self_locking_from_the_lead_angle(lead_deg):
    pair = crossed_pair((1, 40), 2.0, math.radians(20), math.radians(90 - lead_deg), math.radians(90))
    g, mu = math.radians(lead_deg), 0.15
    phi = friction_angle(pair, mu)
    assert phi == pytest.approx(math.atan(0.15 / math.cos(math.radians(20))))
    # the textbook worm formulas: tan γ / tan(γ + φ') driving, tan(γ − φ') / tan γ driven backwards
    assert efficiency(pair, mu) == pytest.approx(math.tan(g) / math.tan(g + phi), rel=1e-12)
    assert efficiency(pair, mu, backwards=True) == pytest.approx(math.tan(g - phi) / math.tan(g), rel=1e-12)
    assert (efficiency(pair, mu, backwards=True) <= 0) == (g <= phi)  # locks exactly when γ ≤ φ' (9.07°)
    assert efficiency(pair, 0.0) == pytest.approx(1.0) and is_worm(pair)


def test_thread_section_is_the_involute_of_the_base_circle():
    pair = crossed_pair((2, 40), 2.0, math.radians(20), math.radians(80), math.radians(90))
    t = gear_spec(pair, 0, 0.1, 0.002)
    assert isinstance(t, ThreadSpec) and t.teeth == 2
    pts = t.section(0.002)
    r, a = np.hypot(*pts.T), np.arctan2(pts[:, 1], pts[:, 0])
    assert r.max() == pytest.approx(t.tip_radius, abs=1e-9) and r.min() == pytest.approx(t.root_radius, abs=1e-9)
    # flank points: the involute's polar angle at their radius, to rounding
    band = (r > t.root_radius + 0.1) & (r < t.tip_radius - 0.1)
    phi = np.mod(a[band] + math.pi / 2, math.pi) - math.pi / 2  # fold the two starts onto one
    assert np.abs(np.abs(phi) - t.flank_angle(r[band])).max() < 1e-12
    # the tooth is half the transverse pitch thick at the pitch circle, less the thinning
    assert 2 * t.pitch_radius * t.flank_angle(t.pitch_radius) == pytest.approx(math.pi * t.module / 2 - 0.1, abs=1e-12)


@pytest.fixture(scope="module")
def worm(kit_of):
    return kit_of("gear_train_worm")


def test_shipped_worm_meshes_exactly_and_locks(worm):
    spec, kit = worm.loaded.spec, worm.kit
    assert isinstance(spec.gear1, ThreadSpec) and spec.pair.ratio == 30
    result = MECHANISM.check(spec, kit, 4)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    f = result.figures
    assert f["max_overlap_mm3"] == 0.0
    designed = designed_backlash(spec)
    assert designed == pytest.approx((0.1 * math.cos(math.radians(85)) + 0.1 * math.cos(math.radians(5)))
                                     / math.cos(math.radians(5)))
    assert designed - 0.003 <= f["backlash_mm"]["min"] <= f["backlash_mm"]["max"] <= designed + 0.006
    lock = locking(spec)
    assert lock["lead_angle_deg"] == pytest.approx(5.0) and lock["self_locking"]
    assert worm.manifest["design"]["self_locking"] is True


def test_shipped_worm_check_fails_with_negative_backlash(worm):
    spec = worm.loaded.spec
    tight = dataclasses.replace(spec, gear1=gear_spec(spec.pair, 0, -0.1, spec.tol),
                                gear2=gear_spec(spec.pair, 1, -0.1, spec.tol))
    assert (mesh_overlaps(build_crossed(tight), 2) > 0.01).all()


def test_worm_ratio_and_flanks(worm):
    spec, kit = worm.loaded.spec, worm.kit
    c = contact_angles(kit, [0.0, 2 * math.pi], 1e-7)["ahead"]
    loaded = [float(spec.angle2(t)) + d for t, d in zip((0.0, 2 * math.pi), c)]
    assert abs(2 * math.pi / (loaded[1] - loaded[0])) == pytest.approx(30.0, rel=1e-6)
    # the thread's sections at three heights: the involute turned by z tan β / r, along the flank's
    # normal (tangent to the base circle)
    b = spec.face_width[0]
    v, f = mesh_arrays(kit.part("gear1").solid)
    mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)
    dev = measure_worm_flanks(mesh, spec.gear1, spec.pair.twist(0, b) / b, (-0.3 * b, 0.02 * b, 0.4 * b))
    worst = float(np.abs(dev).max())
    assert worst < 0.006, worst  # mm: the chord tolerance 0.005 mm (slices and section) and float32


def test_worm_stls_are_closed_shells(worm):
    for p in worm.manifest["parts"]:
        mesh = trimesh.load(worm.dest / p["file"], file_type="stl")
        assert not mesh_problems(mesh, (250.0, 210.0, 220.0)), (p["name"], mesh_problems(mesh))
        assert len(mesh.split(only_watertight=False)) == 1, p["name"]
