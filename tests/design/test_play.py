"""What play costs (docs/tolerance.md): the pen's error band of a chain from its backlash and joint
play, and a gear train's lost motion at the output."""

from __future__ import annotations

import math

import numpy as np
import pytest

from partgen import pipeline
from partgen.config.overrides import parse_set
from partgen.design.play import _gains, _transfer, chain_play, pen_band
from partgen.design.synthesis import Chain, Link, trace
from partgen.design.trace import built_chain
from partgen.pipeline import Overrides

THETA = 2 * np.pi * np.arange(360) / 360


def _spec(config: str, *sets: str):
    return pipeline.load(f"configs/{config}.yaml", over=Overrides(tuple(parse_set(s) for s in sets))).spec


@pytest.fixture(scope="module")
def chain():
    return _spec("butterfly", "gears.backlash_per_gear_mm=0.05")


def test_jacobian_matches_the_exact_chain(chain):
    """The pen's displacement per free angle equals the exact change of the traced path when the
    link angles move by T·ε (the stages' recurrence): the linearisation is exact to first order."""
    mech = chain.mechanism
    play = chain_play(mech, 0.1)
    g = _gains(mech, THETA, play.rho)
    built = built_chain(mech)
    n = len(built.links)
    T = _transfer(play.rho, n)
    for j in (0, 3, n - 1):
        eps = 1e-6
        moved = Chain(tuple(Link(l.name, l.speed, l.length, l.phase + T[k, j] * eps)
                            for k, l in enumerate(built.links)), built.offset)
        exact = (trace(moved, THETA) - trace(built, THETA)) / eps
        assert np.max(np.abs(exact - g[j])) < 1e-3 * np.max(np.abs(g[j]))
    # a free angle of link 1 (the crank's lost motion) moves the pen along its path: velocity × Δθ/speed_1
    vel = np.gradient(trace(built, THETA), THETA)
    assert np.max(np.abs(g[0] - vel / built.links[0].speed)) < 0.02 * np.max(np.abs(vel))


def test_recurrence_transfer():
    """T follows α_k+1 = α_k + ρ_k (α_k-1 − α_k): a free angle of link 1 turns link 2 by 1 − ρ_1."""
    T = _transfer(np.array([0.5, 2.0]), 3)
    assert T[0].tolist() == [1.0, 0.0, 0.0]
    assert T[1, 0] == pytest.approx(0.5) and T[1, 1] == 1.0
    assert T[2, 0] == pytest.approx(0.5 + 2.0 * (1.0 - 0.5)) and T[2, 1] == pytest.approx(1 - 2.0)


def test_worst_case_bounds_every_take_up(chain):
    """No placement of the play (random corners of the zonotope) moves the pen beyond the worst case,
    and some come within 5 % of it."""
    mech = chain.mechanism
    band = pen_band(mech, 0.1, THETA, 0.0, prints=10)
    g = _gains(mech, THETA, band.play.rho)
    rng = np.random.default_rng(1)
    best = 0.0
    for _ in range(400):
        s = rng.choice([-1.0, 1.0], len(band.play.h))
        phi = rng.uniform(0, 2 * np.pi)
        d = np.abs((s * band.play.h) @ g + band.play.c.sum() * np.exp(1j * phi))
        assert np.all(d <= band.worst * (1 + 1e-4))  # 360 directions: exact to 4e-5
        best = max(best, float((d / band.worst).max()))
    assert best > 0.95


def test_band_grows_with_backlash_and_clearance(chain):
    """More backlash per gear or a looser running fit widens both the worst case and the 95 % band."""
    base = pen_band(chain.mechanism, 0.1, THETA, 0.127, prints=500)
    loose = pen_band(chain.mechanism, 0.2, THETA, 0.127, prints=500)
    more = _spec("butterfly", "gears.backlash_per_gear_mm=0.15")
    lash = pen_band(more.mechanism, 0.1, THETA, 0.127, prints=500)
    for b in (loose, lash):
        assert b.worst.max() > base.worst.max() * 1.05
        assert b.p95_max > base.p95_max * 1.05
    assert base.p95_max < base.worst.max()
    tight = pen_band(chain.mechanism, 0.0, THETA, 0.0, prints=50)
    zero = _spec("butterfly", "gears.backlash_per_gear_mm=0")
    none = pen_band(zero.mechanism, 0.0, THETA, 0.0, prints=50)
    assert none.worst.max() < 1e-6 < tight.worst.max()


def test_trace_json_has_the_band_for_chain_and_belt():
    for config in ("butterfly", "butterfly_belt"):
        over = Overrides((parse_set("gears.backlash_per_gear_mm=0.05"),))  # no auto search: a quick test
        stats = pipeline.trace(f"configs/{config}.yaml", 720, plots_dir=False, over=over).trace.stats
        b = stats["pen_error_band_mm"]
        assert 0 < b["p50_max"] <= b["p95_max"]
        assert b["worst_case_max"] > 0 and len(b["link_free_angle_arcmin"]) == len(b["joint_radial_play_mm"])
    # the belt's stages are not modelled (free angle 0 after link 1); its joints' play still counts
    assert b["link_free_angle_arcmin"][1:] == [0.0] * (len(b["link_free_angle_arcmin"]) - 1)
    assert b["worst_case_max"] >= sum(b["joint_radial_play_mm"]) - 1e-9


# --- gear trains: lost motion at the output -----------------------------------------------------------

# (the stages' growth with backlash and clearance: tests/mechanisms/gear_train/test_stages_play.py)


def test_train_backlash_matches_the_printed_outlines():
    """The formula's backlash at the output agrees with the backlash trace measures by turning the
    printed outlines (drive flank to coast flank), and trace --json carries it with the band."""
    stats = pipeline.trace("configs/gear_train_reducer.yaml", 16, plots_dir=False).trace.stats
    lm = stats["lost_motion_arcmin"]
    assert lm["backlash"] == pytest.approx(stats["backlash_arcmin"]["mean"], rel=0.05)
    band = lm["transmission_error_band_arcmin"]
    assert band["width"] >= lm["total"] * 0.95 and band["low"] < 0 < band["high"]
