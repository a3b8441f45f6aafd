"""Measured biases: `build` compensates the geometry by them, the tolerance study draws around them.

A kit built for a biased profile, *printed* (the bias applied to its STLs), has the unbiased kit's
geometry: its nominal fits. Nothing is printed: the arithmetic is checked on the meshes."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely.geometry import Point

from partgen import pipeline, studies
from partgen.cli.main import main
from partgen.config.yamlio import read_yaml_file
from partgen.design.tolerance import add_tallies, chunk_sizes, run_chunk
from partgen.geometry.compensate import compensate, is_round
from partgen.geometry.measure import from_mesh, section, slabs
from shapely.geometry import Polygon

ROOT = Path(__file__).resolve().parents[2]
DESIGN = ROOT / "configs" / "gear_pair.yaml"
MK4 = (ROOT / "partgen" / "printers" / "prusa_mk4.yaml").read_text()
HOLE, PIN, OUTLINE = -0.12, 0.04, 0.105


def _profile(folder: Path, name: str, biases: str = "") -> Path:
    p = folder / f"{name}.yaml"
    p.write_text(MK4 + biases)
    return p


def _biases(compensate: bool, hole=HOLE, pin=PIN, outline=OUTLINE) -> str:
    return (f"biases:\n  hole_diametral_mm: {hole}\n  pin_diametral_mm: {pin}\n  outline_diametral_mm: {outline}\n"
            f"  compensate: {'true' if compensate else 'false'}\n")


@pytest.fixture(scope="module")
def profiles(tmp_path_factory):
    d = tmp_path_factory.mktemp("profiles")
    return {"plain": _profile(d, "plain"), "biased": _profile(d, "biased", _biases(True)),
            "uncompensated": _profile(d, "uncompensated", _biases(False)),
            "oversize": _profile(d, "oversize", _biases(False, hole=0.12, pin=-0.04, outline=-0.105))}


@pytest.fixture(scope="module")
def kits(profiles, tmp_path_factory):
    d = tmp_path_factory.mktemp("kits")
    out = {}
    for name in ("plain", "biased"):
        assert main(["build", str(DESIGN), "--printer", str(profiles[name]), "-o", str(d / name), "-q"]) == 0
        out[name] = d / name
    return out


def _solid(folder: Path, part: str):
    m = trimesh.load(folder / f"{part}.stl", force="mesh")
    return from_mesh(np.asarray(m.vertices), np.asarray(m.faces))


def _bore(shape) -> float:
    """Inscribed diameter of the section's (one) hole about its centre."""
    polys = shape.geoms if hasattr(shape, "geoms") else [shape]
    holes = [r for p in polys for r in p.interiors]
    assert len(holes) == 1
    ring = holes[0]
    c = Polygon(ring).centroid
    return 2 * Point(c).distance(ring)


def test_the_manifest_says_what_was_compensated(kits):
    man = read_yaml_file(kits["biased"] / "manifest.json")  # JSON is YAML
    comp = man["design"]["compensation"]
    assert comp["compensated"] == ["base", "gear1", "gear2"] and comp["as_designed"] == []
    assert comp["hole_diametral_mm"] == HOLE
    assert "compensation" not in read_yaml_file(kits["plain"] / "manifest.json")["design"]


@pytest.mark.parametrize("part", ["gear1", "gear2"])
def test_a_biased_kit_printed_has_the_nominal_fits(kits, part):
    plain, biased = _solid(kits["plain"], part), _solid(kits["biased"], part)
    printed = compensate(biased, -HOLE, -PIN, -OUTLINE)  # the printer adds its bias back
    z = 0.5 * (plain.bounding_box()[2] + plain.bounding_box()[5])
    a, b, p = section(plain, z), section(biased, z), section(printed, z)
    # the kit differs from the uncalibrated one exactly by the compensation: the bore opened by 0.12 mm,
    # the teeth trimmed by 0.105 / 2 on every flank
    assert _bore(b) - _bore(a) == pytest.approx(-HOLE, abs=2e-3)
    tip = lambda s: max(math.hypot(x, y) for x, y in (s.geoms[0] if hasattr(s, "geoms") else s).exterior.coords)  # noqa: E731
    assert tip(b) - tip(a) == pytest.approx(-OUTLINE / 2, abs=2e-3)
    # printed, it is the plain kit again: same bore, same tip, same area to the float32 STL's precision
    assert _bore(p) == pytest.approx(_bore(a), abs=2e-3)
    assert tip(p) == pytest.approx(tip(a), abs=2e-3)
    assert p.symmetric_difference(a).area < 0.002 * a.length  # under 2 µm of boundary on average


def test_posts_take_the_pin_bias(kits):
    plain, biased = _solid(kits["plain"], "base"), _solid(kits["biased"], "base")
    top = [s for s in slabs(plain)][-1]  # the posts' slab: round outer contours only
    zs = 0.5 * (top.z0 + top.z1)
    a, b = section(plain, zs), section(biased, zs)
    pa = sorted(a.geoms, key=lambda g: g.centroid.x)
    pb = sorted(b.geoms, key=lambda g: g.centroid.x)
    for ga, gb in zip(pa, pb):
        assert is_round(ga)
        ra = max(math.dist((ga.centroid.x, ga.centroid.y), q) for q in ga.exterior.coords)
        rb = max(math.dist((gb.centroid.x, gb.centroid.y), q) for q in gb.exterior.coords)
        assert 2 * (rb - ra) == pytest.approx(-PIN, abs=3e-3)  # trimmed by the pin bias (mitred chords: ≤ 1/cos)


def _p_jam(profile: Path, samples: int = 20000) -> tuple[float, np.ndarray]:
    """P(jam) at ±0.3 mm (seated gears jam rarely at the profiles' ±0.1: a baseline that can move both ways)."""
    loaded = pipeline.load(DESIGN, over=pipeline.overrides((), str(profile)))
    model, _, _ = studies.nominal_model(loaded, 0.3, 24)
    total = add_tallies([run_chunk(model, 7, i, n) for i, n in enumerate(chunk_sizes(samples, 5000))])
    return total.jams / total.n, model.nominal


def test_tolerance_draws_around_the_bias(profiles):
    p0, n0 = _p_jam(profiles["plain"])
    p_small, n_small = _p_jam(profiles["uncompensated"])   # holes small, pins and teeth fat: more jams
    p_big, n_big = _p_jam(profiles["oversize"])            # the other way: fewer
    p_comp, n_comp = _p_jam(profiles["biased"])            # compensated by build: as if unbiased
    # by hand: a radial gap moves by (hole - pin) / 2; the gears sit where the mesh pushes them
    # (docs/tolerance.md), so the centre distance grows by both bores' radial play, 2 (hole - pin) / 2;
    # tip-root by 2 x -0.5 x outline plus that; the backlash by 2 x -1.064 x outline (the teeth's
    # coefficient in gear_pair's model) plus 2 tan α_w times that (α_w of 17/31 teeth, m 2, at 48.011 mm)
    np.testing.assert_allclose(n_small[:2] - n0[:2], (HOLE - PIN) / 2, atol=1e-12)
    seat = 2 * (HOLE - PIN) / 2
    tan_aw = math.tan(math.acos(48 * math.cos(math.radians(20)) / 48.011))
    assert n_small[3] - n0[3] == pytest.approx(-OUTLINE + seat, abs=1e-9)
    assert n_small[2] - n0[2] == pytest.approx(-2 * OUTLINE * 1.0642 + 2 * tan_aw * seat, abs=5e-4)
    assert p_small > 2 * p0 + 0.01 and p_big < p0 / 2, (p0, p_small, p_big)
    np.testing.assert_array_equal(n_comp, n0)
    assert p_comp == p0


def test_only_prism_stacks_are_compensated():
    import manifold3d as m3d
    from partgen.geometry.compensate import is_prism_stack
    post = m3d.Manifold.cylinder(5.0, 2.5, 2.5, 64)
    cone = m3d.Manifold.cylinder(5.0, 2.5, 2.0, 64)
    assert is_prism_stack(post) and not is_prism_stack(cone)
    assert compensate(cone, HOLE, PIN, OUTLINE) is None
    trimmed = compensate(post, HOLE, PIN, OUTLINE)
    r = max(math.hypot(x, y) for x, y in section(trimmed, 2.5).exterior.coords)
    assert 2 * r == pytest.approx(5.0 - PIN, abs=1e-3)  # a round contour takes the pin bias


def test_outputs_say_whether_the_values_are_measured(profiles, tmp_path, capsys):
    assert main(["build", str(DESIGN), "--printer", str(profiles["plain"]), "-o", str(tmp_path / "a"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["printer_values"] == "typical"
    assert main(["build", str(DESIGN), "--printer", str(profiles["plain"]), "-o", str(tmp_path / "b"), "-q"]) == 0
    assert "typical values, not measured" in capsys.readouterr().err
    cal = tmp_path / "cal.yaml"
    assert main(["calibrate", "--printer", "prusa_mk4", str(ROOT / "configs" / "calibration" / "example_results.yaml"),
                 "-o", str(cal)]) == 0
    capsys.readouterr()
    assert main(["build", str(DESIGN), "--printer", str(cal), "-o", str(tmp_path / "c"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["printer_values"] == "measured"
