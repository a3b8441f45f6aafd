"""Same design, same kit, on any machine (issue 25): every search and ``auto`` choice compares
quantised scores (core.quantise) and breaks ties in a stated order, so inputs perturbed by a few
ulps — what another machine's BLAS, SIMD width or summation order does to a float — make the same
choice. Each test perturbs the inputs of one search and compares the choice it makes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from partgen import pipeline
from partgen.core.quantise import RESOLUTION_MM, close, quantise, quantised

ROOT = Path(__file__).resolve().parents[2]
DESKTOP = ("prusa_mk4", "bambu_x1c", "ender3_v3", "bambu_a1_mini", "prusa_core_one", "voron24_350")


def ulps(x: float, n: int) -> float:
    """``x`` moved ``n`` representable floats up (n < 0: down)."""
    for _ in range(abs(n)):
        x = float(np.nextafter(x, math.inf if n > 0 else -math.inf))
    return x


def test_quantise_makes_ulp_differences_ties_and_keeps_real_ones():
    a = 4.203542891852281
    b = 4.20354289185228  # the two clearances one machine's Bennett search saw as different (issue 25)
    assert a != b and a > b
    assert quantise(a) == quantise(b) and close(a, b)
    assert quantised((0.0, a, -395.75)) > quantised((0.0, b, -398.25))  # the tie goes to the next key
    assert quantise(a + 2 * RESOLUTION_MM) > quantise(a)  # a real difference still orders
    assert quantise(math.inf) == math.inf and quantise(-math.inf) < quantise(-1e9)


def chain_choices(cfg: str, sets=(), printer=None) -> dict:
    """The discrete choices a chain's design makes. Its backlash is given (not ``auto``, which builds
    and checks the kit to choose: its choice is a bisection on whole jam counts of fixed draws, and
    tests/studies/test_autoplay.py holds it)."""
    sets = (*sets, "gears.backlash_per_gear_mm=0.05")
    spec = pipeline.load(ROOT / "configs" / cfg, over=pipeline.overrides(sets, printer)).spec
    m = spec.mechanism
    return {"module": spec.params.system.module,
            "teeth": [(s.D.teeth, s.M.teeth, s.G.teeth) for s in m.stages],
            "idlers": [tuple(np.round(s.idler, 6)) for s in m.stages],
            "links": [link.name for link in m.chain.links]}


@pytest.mark.parametrize("cfg, key, value, printer", [
    ("butterfly.yaml", "curve.scale_mm_per_unit", 30.0, None),  # teeth: auto, links of the paper's curve
    ("butterfly_desktop.yaml", "curve.scale_mm_per_unit", 30.0, "prusa_mk4"),  # module_mm: auto too
    ("butterfly_desktop.yaml", "curve.scale_mm_per_unit", 30.0, "bambu_x1c"),
    ("star.yaml", "curve.scale", 1.5, None),  # a drawn curve: which links are kept
    ("heart.yaml", "curve.scale", 28.0, None),
])
def test_chain_choices_survive_ulp_perturbation(cfg, key, value, printer):
    """``teeth: auto``, ``module_mm: auto``, the idler's side and the drawn curve's links: the same
    with the scale a few ulps either way (every length of the design moves by as much)."""
    base = chain_choices(cfg, printer=printer)
    for n in (-3, 2):
        assert chain_choices(cfg, [f"{key}={ulps(value, n)!r}"], printer) == base, n


def test_teeth_search_is_quantised_at_its_limits():
    """A link length exactly at Eq 12's limit for a candidate (tips + gap == S) decides the same
    a few ulps either way: the comparison is at 1e-6 mm, not at the last bit."""
    from fractions import Fraction

    from partgen.design.drivetrain import Limits, choose_stage
    from partgen.design.gearing import ToothSystem, make_gear

    system = ToothSystem(module=1.0, pressure_angle=math.radians(20))
    D, G = make_gear(30, system), make_gear(15, system)
    limits = Limits(min_pitch_diameter=10.0, min_root_diameter=6.0, tip_gap=2.0, idler_reach=1.0)
    edge = D.tip_radius + G.tip_radius + limits.tip_gap
    picks = {n: choose_stage(1, ulps(edge, n), Fraction(2, 1), system, limits) for n in (-3, 0, 3)}
    got = {n: (s.D.teeth, s.M.teeth, s.G.teeth) for n, s in picks.items()}
    assert len(set(got.values())) == 1, got


def test_print_orientation_survives_ulp_perturbation():
    """best_orientation (which face a part lies on) is the same with every vertex moved a few ulps."""
    from partgen.geometry.printing import best_orientation
    from partgen.geometry.solid import mesh_arrays
    import manifold3d as m3d

    # a plate with a boss: two flat faces of different size, a cylinder, and tied side faces
    solid = m3d.Manifold.cube((40, 30, 4)) + m3d.Manifold.cylinder(10, 6, 6, 48).translate((20, 15, 4))
    v, f = mesh_arrays(solid)
    base = best_orientation(v, f, 45.0, 10.0)
    rng = np.random.default_rng(25)
    for n in (-2, 3):
        w = np.nextafter(v, np.where(rng.random(v.shape) < 0.5, np.inf, -np.inf)) if n > 0 else v * (1 + n * 2.2e-16)
        o = best_orientation(w, f, 45.0, 10.0)
        assert np.allclose(o.down, base.down, atol=1e-9), n
        assert quantise(o.overhang_mm2, 1e-3) == quantise(base.overhang_mm2, 1e-3)


def test_plate_packing_survives_ulp_perturbation():
    """Which plate, copy and turn every part gets is the same with every vertex moved a few ulps;
    the positions agree to the packing's resolution."""
    import trimesh

    from partgen.export.plates import layout

    rng = np.random.default_rng(7)
    items = []
    for k in range(7):  # plates of several sizes, some of them square (tied turns)
        size = (20 + 15 * (k % 3), 20 + 10 * (k % 2) + 15 * (k % 3 == 0), 3)
        items.append((f"p{k}", trimesh.creation.box(size), 1 + k % 3))
    base = layout(items, (120.0, 100.0), margin=5.0)

    def moved(mesh):
        m = mesh.copy()
        m.vertices = np.nextafter(m.vertices, np.where(rng.random(m.vertices.shape) < 0.5, np.inf, -np.inf))
        return m

    for _ in range(4):
        got = layout([(n, moved(m), c) for n, m, c in items], (120.0, 100.0), margin=5.0)
        assert len(got.plates) == len(base.plates)
        for pa, pb in zip(base.plates, got.plates):
            assert [(p.name, p.copy, p.plate) for p in pa] == [(p.name, p.copy, p.plate) for p in pb]
            for p, q in zip(pa, pb):
                assert math.isclose(p.angle, q.angle, abs_tol=1e-6) and math.isclose(p.x, q.x, abs_tol=1e-6) \
                    and math.isclose(p.y, q.y, abs_tol=1e-6)


def test_bennett_layout_search_survives_ulp_perturbation():
    """The shipped Bennett design's whole layout search (the layout, the pockets sized, the layout
    refined for them) with the linkage's length a moved a few ulps (every joint of the linkage moves
    by about as much) picks the layout tests/designs/bennett_fixed.yaml pins — the one the
    unperturbed search picks too (test_bennett_cli holds that)."""
    from partgen.mechanisms.bennett_butterfly.kit import build_bennett
    from partgen.mechanisms.bennett_butterfly.layout import choose_offsets, coarse_samples, search_layout

    pinned = yaml.safe_load((ROOT / "tests" / "designs" / "bennett_fixed.yaml").read_text())["parts"]["layout"]
    want = ({int(k): v for k, v in pinned["layers"].items()}, {j: float(v) for j, v in pinned["shifts_mm"].items()})
    spec = pipeline.load(ROOT / "configs" / "bennett_butterfly.yaml",
                         over=pipeline.overrides([f"linkage.a_mm={ulps(105.0, 3)!r}"])).spec
    kit = build_bennett(spec)
    lay = kit.layout
    assert ({i: v for i, v in lay.layer.items() if i}, {j: v for j, v in lay.shift.items() if v}) == want


@pytest.mark.parametrize("overall, targets", [
    (10.0, [{}, {}]),  # the reducer: the overall ratio split over two stages
    (7.3, [{}, {}, {}]),  # an inexact ratio: many trains within the same error
    (None, [{"ratio": 3.7}, {"ratio": 2.2, "centre_distance": 48.4}]),  # a centre distance met by shift
])
def test_gear_train_teeth_survive_ulp_perturbation(overall, targets):
    """solve_train's choice (the split of the overall ratio, the pair nearest each ratio, the pair a
    centre distance's shifts reach) is the same with every ratio and distance a few ulps off."""
    from partgen.design.gear_train import StageTarget, TeethLimits, solve_train

    lim = TeethLimits(min_teeth=13, max_teeth=60, module=2.0)

    def solve(n: int):
        ts = [StageTarget(**{k: ulps(v, n) if isinstance(v, float) else v for k, v in t.items()}) for t in targets]
        got = solve_train(ts, lim, 2.0, math.radians(20), None if overall is None else ulps(overall, n))
        return [(s.driver, s.driven, None if s.shifts is None else tuple(round(x, 9) for x in s.shifts)) for s in got]

    base = solve(0)
    assert all(solve(n) == base for n in (-3, -1, 2, 4))
