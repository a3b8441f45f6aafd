"""Wrist gear pairs as built: watertight and printable, 19 dome teeth on gear 1, gear 2's swept
sockets clear gear 1 everywhere in the workspace while its teeth stay engaged."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import trimesh

from partgen.mechanisms.wrist.kit import build_wrist
from partgen.mechanisms import load_design
from partgen.mechanisms.wrist.resolve import resolve_wrist
from partgen.design import spherical as sph
from partgen.geometry import wrist as W
from partgen.geometry.measure import intersection
from partgen.testing import mesh_problems

ROOT = Path(__file__).resolve().parents[3]
CONFIGS = ["wrist_sphere", "wrist_quasi_ellipsoid"]


@pytest.fixture(scope="module", params=CONFIGS)
def built(request, kit_of):
    """(spec, kit) of each wrist config, from the session's `partgen build` of it."""
    b = kit_of(request.param)
    assert b.loaded.spec == resolve_wrist(load_design(ROOT / "configs" / f"{request.param}.yaml"))
    return b.loaded.spec, b.kit


@pytest.mark.parametrize("name", CONFIGS)
def test_wrist_kits_build_watertight_and_fit(name, kit_of):
    loaded, kit, man, folder = kit_of(name)
    expected = ["gear1", "gear2"] + (["cross_gear", "cross_mate"] if name == "wrist_sphere" else [])
    assert [p["name"] for p in man["parts"]] == expected
    for p in man["parts"]:
        mesh = trimesh.load(folder / p["file"], file_type="stl", force="mesh")
        assert mesh_problems(mesh, kit.params.printer.envelope) == []
        assert p["volume_mm3"] == pytest.approx(mesh.volume, rel=1e-6)


def _blank(spec, kit, gear):
    end = sph.valid_end(spec.I)
    if gear == 1:
        r_of = lambda a: sph.pitch_radii(np.clip(a, 0, end), spec.I, spec.A)[0]  # noqa: E731
    else:
        th = lambda b: 2 * np.arctan(np.tan(np.asarray(b) / 2) / spec.I)  # noqa: E731
        r_of = lambda b: sph.pitch_radii(np.clip(th(b), 0, end), spec.I, spec.A)[1]  # noqa: E731
    return W.revolved_cap(r_of, math.radians(kit.figures["cap_deg"][gear - 1]), -spec.base_height, 8.0, spec.tol)


def test_gear1_has_19_dome_teeth_of_the_designed_size(built):
    """Count the teeth on the mesh: vertices standing more than half a tooth above the pitch
    surface, grouped by proximity; each group's top is the tooth height above the surface."""
    spec, kit = built
    v = np.asarray(kit.parts[0].solid.to_mesh().vert_properties, dtype=float)[:, :3]
    r = np.linalg.norm(v, axis=1)
    alpha = np.arccos(np.clip(v[:, 2] / r, -1, 1))
    inside = alpha <= math.radians(kit.figures["cap_deg"][0]) - 1e-6
    end = sph.valid_end(spec.I)
    height = r - sph.pitch_radii(np.clip(alpha, 0, end), spec.I, spec.A)[0]
    high = v[inside & (height > 0.7 * spec.tooth_height)]
    hh = height[inside & (height > 0.7 * spec.tooth_height)]
    label = -np.ones(len(high), dtype=int)
    n = 0
    for i in range(len(high)):  # flood-fill groups of points closer than 1 mm (a dome's tessellation is finer)
        if label[i] >= 0:
            continue
        label[i], todo = n, [i]
        while todo:
            j = todo.pop()
            near = np.flatnonzero((label < 0) & (np.linalg.norm(high - high[j], axis=1) < 1.0))
            label[near] = n
            todo.extend(near.tolist())
        n += 1
    assert n == sum(spec.ring_teeth) == 19
    for k in range(n):
        assert hh[label == k].max() == pytest.approx(spec.tooth_height, abs=0.1)


def test_unit_ratio_pitch_surfaces_are_spheres(built):
    spec, kit = built
    if spec.I != 1.0:
        pytest.skip("spheres only for I = 1")
    v = np.asarray(kit.parts[1].solid.to_mesh().vert_properties)[:, :3]
    r = np.linalg.norm(v, axis=1)
    top = v[:, 2] > 0.7 * spec.A / 2  # the cap
    assert (r[top] - spec.A / 2).max() < 1e-4  # nothing stands out of the sphere
    assert (spec.A / 2 - r[top]).max() < spec.tooth_height + spec.clearance + 0.05  # sockets: a grown tooth deep
    assert np.quantile(np.abs(r[top] - spec.A / 2), 0.2) < 0.01  # most of the cap is the sphere itself


def test_sockets_clear_gear1_and_teeth_stay_engaged_over_the_workspace(built):
    spec, kit = built
    g1, g2 = kit.parts[0].solid, kit.parts[1].solid
    domes = W.domes_union(kit.domes)
    blank2 = _blank(spec, kit, 2)
    rng = np.random.default_rng(7)
    grid = [(t, p) for t in np.linspace(0, kit.theta_max, 4) for p in 2 * np.pi * np.arange(6) / 6]
    off = [(rng.uniform(0, kit.theta_max), rng.uniform(0, 2 * np.pi)) for _ in range(12)]
    for theta, psi in grid + off:
        T = kit.pose2(theta, psi)
        assert intersection(g1, np.eye(4), g2, T)[0] < 0.01, (theta, psi)
        engaged = (domes ^ blank2.transform(T[:3, :])).volume()
        assert engaged > 1.0, (theta, psi)


def test_negative_clearance_sockets_interfere():
    """Seeded fault: teeth shrunk relative to their sockets' cutters is fine, but sockets cut by
    teeth *smaller* than the teeth (clearance -0.3 mm) must overlap gear 1.

    The pose looked at, θ = ψ = 0, is a pose of every socket sweep (θ and ψ both start at 0), so
    the socket cut there decides the overlap whatever the grid's density: the coarsest sweep (2 × 6
    poses, as tests/test_bench_sweep.py builds) shows it as well as a dense one (12 mm³ at 4 × 12, 45 mm³
    at 2 × 6; with +0.3 mm both are 0), and the cross gear, a part of its own, is left out (a
    seventh of the time it took)."""
    spec = resolve_wrist(load_design(ROOT / "configs" / "wrist_sphere.yaml"))
    kit = build_wrist(replace(spec, clearance=-0.3, theta_steps=2, psi_steps=6, cross=None))
    T = kit.pose2(0.0, 0.0)
    assert intersection(kit.parts[0].solid, np.eye(4), kit.parts[1].solid, T)[0] > 0.05


def test_wrist_check_passes_and_measures_play(built):
    """Zero overlap, teeth engaged everywhere, play bounded in bending and reported in twist
    (domes hold twist only through the teeth beside the contact: several degrees); `check
    --samples 18` looks at about 18 grid poses and 4 random ones, and the play at 3 bends."""
    from partgen.mechanisms import REGISTRY
    from partgen.mechanisms.wrist.checks import wrist_sampling
    spec, kit = built
    res = REGISTRY["wrist"].check(spec, kit, 18)
    grid = wrist_sampling(18)["grid"]
    assert res.figures["poses"] == grid[0] * grid[1] + 4 and 15 <= grid[0] * grid[1] <= 21
    assert res.ok, [f.message for f in res.findings]
    assert res.figures["max_overlap_mm3"] <= 0.01 and res.figures["min_engaged_mm3"] > 1.0
    play = res.figures["play"]
    for row in play:
        assert 0.05 < row["bend_play_deg"] < 5.0
    # twist about gear 2's own axis: loose at the pole (the contact is on that axis), held away from it
    twist = [row["twist_play_deg"] for row in play]
    assert twist[0] > 5.0 and twist[-1] < 3.0 and twist[0] > twist[1] > twist[-1]


def test_wrist_trace_reports_the_math_and_draws_it(tmp_path, capsys):
    import json

    from partgen.cli.main import main
    code = main(["trace", str(ROOT / "configs" / "wrist_quasi_ellipsoid.yaml"), "--json", "--plots", str(tmp_path)])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["kind"] == "wrist"
    assert out["ode_vs_closed_form_max"] < 1e-9 and out["mating_angle_methods_max_rad"] < 1e-9
    assert out["valid_end_deg"] == pytest.approx(math.degrees(2 * math.atan(1 / 0.6667)), abs=1e-6)
    assert [r["teeth"] for r in out["rows"]] == [1, 6, 12]
    assert all(abs(r["lat_pitch_off"]) > 1e-4 for r in out["rows"][1:])
    from PIL import Image
    assert Image.open(tmp_path / "wrist.png").size[0] > 1000


def test_cross_gear_keeps_its_profile_through_both_ring_axes(kit_of):
    """The ABENICS-style cross gear of wrist_sphere: section the printed mesh just above its
    equatorial base (the plane through both ring axes) and compare with the 2-D involute profile."""
    import shapely
    from shapely.geometry import Polygon

    from partgen.geometry.gear import gear_outline
    from partgen.testing import section_outline
    _, kit, man, folder = kit_of("wrist_sphere")
    entry = next(p for p in man["parts"] if p["name"] == "cross_gear")
    mesh = trimesh.load(folder / entry["file"], file_type="stl", force="mesh")
    assert mesh_problems(mesh) == []
    spec = next(p for p in kit.parts if p.name == "cross_gear").gear
    sec = section_outline(mesh, 0.02)
    prof = Polygon(gear_outline(spec).points)
    assert shapely.symmetric_difference(Polygon(sec.exterior), prof).area < 0.02 * prof.length  # a ~0.02 mm band


def test_cross_gear_tooth_count_rule():
    import math as _m

    from partgen.design.gearing import ToothSystem, make_gear
    from partgen.geometry.cross_gear import cross_gear, equatorial_error, ring_gear
    good = make_gear(24, ToothSystem(module=2.5, pressure_angle=_m.radians(20), profile_shift=0.0, chord_tolerance=0.02))
    assert equatorial_error(cross_gear(good), good) < 0.05
    bad = make_gear(22, ToothSystem(module=2.5, pressure_angle=_m.radians(20), profile_shift=0.0, chord_tolerance=0.02))
    with pytest.raises(ValueError, match="multiple of 4"):
        cross_gear(bad)
    forced = ring_gear(bad, 88)
    assert equatorial_error(forced ^ forced.rotate((0.0, 0.0, 90.0)), bad) > 50.0  # the rule is real


def test_cross_gear_bad_teeth_is_a_config_error(tmp_path, capsys):
    import yaml

    from partgen.cli.main import main
    d = yaml.safe_load((ROOT / "configs" / "wrist_sphere.yaml").read_text())
    d["printer"] = "fortus450mc"
    d["wrist"]["cross_gear"]["teeth"] = 22
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(yaml.safe_dump(d))
    assert main(["build", str(cfg), "-o", str(tmp_path / "out")]) == 2
    assert "wrist.cross_gear.teeth" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_wrist_report_page(tmp_path, kit_of, prime_kit_cache):
    import re

    from partgen.cli.main import main
    prime_kit_cache(kit_of("wrist_quasi_ellipsoid"))  # the report builds nothing anew: the session's kit
    assert main(["report", str(ROOT / "configs" / "wrist_quasi_ellipsoid.yaml"), "--samples", "24", "-o",
                 str(tmp_path)]) == 0
    text = (tmp_path / "index.html").read_text()
    for heading in ("Design", "Math", "Parts", "Check"):
        assert f">{heading}</h2>" in text
    imgs = re.findall(r'<img src="data:image/png;base64,', text)
    assert len(imgs) >= 4  # the math figure, both gears, the bent pair
    assert "twist play" in text and not re.search(r"""src=["'](https?:|file:)""", text)


def test_check_samples_set_the_wrist_poses():
    from partgen.mechanisms.wrist.checks import wrist_sampling

    assert wrist_sampling(None) == {}
    assert wrist_sampling(96) == {"grid": (6, 16), "random_poses": 24, "play_thetas": 4}  # the default's
    few = wrist_sampling(24)
    assert few["grid"][0] * few["grid"][1] in range(20, 29) and few["play_thetas"] == 3 and few["random_poses"] == 6
    many = wrist_sampling(1000)
    assert 900 <= many["grid"][0] * many["grid"][1] <= 1100 and many["grid"][1] > many["grid"][0]
