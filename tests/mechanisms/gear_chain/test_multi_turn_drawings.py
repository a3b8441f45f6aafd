"""Drawings without a once-per-cycle term (the crank turns as often as the drawing needs), samples
that go round a curve several times (one drawing per cycle), and ``curve.scale: auto`` (the
smallest enlargement that builds): the pure functions, a small design, and the shipped
configs/lissajous.yaml built, checked and traced."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
import yaml

from partgen import pipeline
from partgen.cli.main import main
from partgen.design import drawing as D
from partgen.design.synthesis import Chain, Link, trace
from partgen.design.trace import built_chain, built_speeds, crank_turns

from test_drawn_curves import design, epicycle, write_csv


def lissajous(n=720, size=80.0):
    t = 2 * np.pi * np.arange(n) / n
    return size * (np.sin(3 * t) + 1j * np.sin(2 * t))


# --- the lead and the retiming (pure) -------------------------------------------------------------------

def test_the_lead_is_the_lowest_harmonic_that_matters():
    _, _, links, _ = D.fit(lissajous(), "samples")
    assert sorted(l.speed for l in links if l.length > 1e-6) == [-3, -2, 2, 3]
    assert D.lead(links).name == "L2"  # ±2 tie at 40 mm: +2
    mk = lambda name, speed, length: Link(name, speed, length, 0.0)  # noqa: E731
    # the longer of ±k leads; a once-per-cycle term under a tenth of the longest does not
    assert D.lead((mk("L3", 3, 50.0), mk("M2", -2, 30.0), mk("L2", 2, 20.0))).name == "M2"
    assert D.lead((mk("L3", 3, 50.0), mk("L1", 1, 4.9), mk("M3", -3, 20.0))).name == "L3"
    assert D.lead((mk("L3", 3, 50.0), mk("L1", 1, 5.0), mk("M3", -3, 20.0))).name == "L1"
    assert D.lead(()) is None


def test_retime_divides_the_speeds_and_keeps_one_round():
    n = 400
    t = 2 * np.pi * np.arange(n) / n
    z = epicycle(n=n, small=0.0)  # 100 e^{iθ} + 30 e^{-2iθ}, once round
    twice = 100 * np.exp(2j * t) + 30 * np.exp(-4j * t)  # the same curve, twice round
    _, off, links, theta = D.fit(twice, "samples")
    d = D.Drawing(twice, theta, "samples")
    chain = Chain(tuple(l for l in links if l.length > 1.0), off)
    assert sorted(chain.speeds) == [-4, 2]
    once, d1 = D.retime(chain, d)
    assert sorted(once.speeds) == [-2, 1] and {l.name for l in once.links} == {"L1", "M2"}
    assert d1.rounds == 2 and len(d1.samples) == n // 2 and d1.theta.max() < 2 * np.pi
    # the retimed chain passes through every kept sample at its (doubled) angle, and those are one round
    assert np.abs(trace(once, d1.theta) - d1.samples).max() < 1e-9
    assert np.abs(d1.samples - z[::2]).max() < 1e-9  # sample i of the second file is z at 2θ_i
    # a chain whose speeds share no factor is left alone
    same, d2 = D.retime(once, d1)
    assert same is once and d2 is d1


def test_scale_ladder_is_quantised_ordered_and_its_first_rung_is_the_bound():
    z = lissajous(size=1.0)
    _, off, links, theta = D.fit(z, "samples")
    d = D.Drawing(z, theta, "samples")
    ladder = D.scale_ladder(off, links, d, 1.0, 4, 20.0, 400.0, "L2")
    assert ladder and list(ladder) == sorted(ladder) and len(ladder) <= 40
    # three significant figures, at least 5 % apart
    for s in ladder:
        e = math.floor(math.log10(s)) - 2
        assert abs(s / 10**e - round(s / 10**e)) < 1e-9
    assert all(b >= a * D.SCALE_STEP * (1 - 1e-9) for a, b in zip(ladder, ladder[1:]))
    # the first rung: the 0.5-unit links reach the printer's 20 mm (40×), rounded up; just under it they do not
    assert ladder[0] == 40.0 and 0.5 * ladder[0] >= 20.0 - 1e-9  # exactly 0.5-unit links: 40 on the nose
    # the last rung still lets the longest link fit the 400 mm reach; a tighter reach cuts the ladder
    assert 0.5 * ladder[-1] <= 400.0
    short = D.scale_ladder(off, links, d, 1.0, 4, 20.0, 25.0, "L2")
    assert short and max(short) * 0.5 <= 25.0 and len(short) < len(ladder)
    # no window at all: a budget no four links meet and a printer minimum no link reaches
    assert D.scale_ladder(off, links, d, 1e-9, 2, 20.0, 400.0, "L2") == ()


# --- a small design: the crank turns twice; samples that go round twice -----------------------------------

def test_a_lissajous_figure_builds_with_the_crank_turning_twice(tmp_path):
    write_csv(tmp_path / "c.csv", lissajous())
    mech = pipeline.load(design(tmp_path, {"points": "c.csv", "max_deviation_mm": 1.0})).spec.mechanism
    assert mech.chain.links[0].name == "L2" and sorted(mech.chain.speeds) == [-3, -2, 2, 3]
    assert crank_turns(mech) == 2 and mech.drawing.rounds == 1
    # as built (speeds from the teeth) the links turn at the design speeds, so the pen passes through
    # every sample at its angle, over one cycle = two crank turns
    assert built_speeds(mech) == tuple(Fraction(s) for s in mech.chain.speeds)
    assert np.abs(trace(built_chain(mech), mech.drawing.theta) - mech.drawing.samples).max() < 1e-6
    # the drive pair is 1:1: the crank turns with link 1, whose speed is the drawing's lowest harmonic
    assert mech.drive.teeth == mech.G1.teeth


def test_samples_that_go_round_twice_make_one_drawing_per_cycle(tmp_path):
    n = 600
    t = 2 * np.pi * np.arange(n) / n
    z = 100 * np.exp(2j * t) + 30 * np.exp(-4j * t)  # one curve traced twice over the file
    write_csv(tmp_path / "c.csv", z)
    mech = pipeline.load(design(tmp_path, {"points": "c.csv", "max_deviation_mm": 1.0})).spec.mechanism
    assert [l.name for l in mech.chain.links] == ["L1", "M2"] and crank_turns(mech) == 1
    d = mech.drawing
    assert d.rounds == 2 and len(d.samples) == n // 2
    assert np.abs(trace(built_chain(mech), d.theta) - d.samples).max() < 1e-6


# --- the shipped lissajous.yaml: auto scale, build, check, trace -----------------------------------------

@pytest.fixture(scope="module")
def shipped(kit_of):
    return kit_of("lissajous")


def test_shipped_lissajous_auto_scale_is_the_smallest_rung_that_builds(shipped):
    mech = shipped.loaded.spec.mechanism
    note = [f for f in mech.findings if f.rule == "auto-scale"]
    assert len(note) == 1 and f"auto chose {mech.drawing.scale:g}" in note[0].message
    assert not [f for f in mech.findings if f.severity == "warn"]
    # the kit pins the scale it was built at
    design_yaml = yaml.safe_load((shipped.dest / "design.yaml").read_text())
    assert design_yaml["curve"]["scale"] == mech.drawing.scale
    assert mech.chain.links[0].length == pytest.approx(0.5 * mech.drawing.scale, rel=1e-4)
    # the rung below does not build without a warning (re-resolved at that scale)
    from partgen.errors import ConfigError
    from partgen.mechanisms.gear_chain.resolve import _fitted, resolve_spec

    loaded = shipped.loaded.raw
    off, links, d, head, _, _ = _fitted(loaded, 1.0)
    ladder = D.scale_ladder(off, links, d, 1.0, 4, 20.0, math.hypot(250, 210), head.name)
    i = ladder.index(mech.drawing.scale)
    assert i > 0
    try:
        below = resolve_spec(loaded, ladder[i - 1])
        assert [f for f in below.mechanism.findings if f.severity == "warn"]
    except ConfigError:
        pass


def test_shipped_lissajous_checks_and_traces_within_its_budget(shipped, capsys):
    assert main(["check", str(shipped.dest), "--samples", "90", "--no-plates", "-q"]) == 0
    capsys.readouterr()
    assert main(["trace", str(shipped.dest), "--json", "--no-plots"]) == 0
    stats = json.loads(capsys.readouterr().out)
    assert stats["crank_turns_per_drawing"] == "2" and stats["speeds"] == ["2", "-2", "3", "-3"]
    budget = yaml.safe_load((shipped.dest / "design.yaml").read_text())["curve"]["max_deviation_mm"]
    assert stats["target"] == "drawing" and 0 < stats["hausdorff_mm"] <= budget
    # independently: the manifest's links turned at their speeds against the shipped CSV at the kit's scale
    man = json.loads((shipped.dest / "manifest.json").read_text())
    assert man["design"]["crank_turns_per_drawing"] == "2"
    xy = np.loadtxt(shipped.dest / "curve.csv", delimiter=",", skiprows=1)
    z = (xy[:, 0] + 1j * xy[:, 1]) * man_scale(shipped)
    t = 2 * np.pi * np.arange(len(z)) / len(z)
    pen = sum(l["length_mm"] * np.exp(1j * (l["speed"] * t + math.radians(l["initial_angle_deg"])))
              for l in man["design"]["links"]) + complex(*man["design"]["ground_offset_mm"])
    assert np.abs(pen - z).max() < 1e-3  # the CSV's 6 decimals at scale ~85


def man_scale(shipped) -> float:
    return yaml.safe_load((shipped.dest / "design.yaml").read_text())["curve"]["scale"]


def test_build_output_says_how_often_the_crank_turns(shipped):
    text = shipped.loaded.mechanism.bill_text(shipped.loaded.spec, shipped.manifest, shipped.dest, 0.0)
    assert "the crank turns 2 times per drawing" in text and "L2" in text


def test_scale_ladder_is_the_same_for_inputs_an_ulp_apart():
    z = lissajous(size=1.0)
    out = []
    for zz in (z, z * (1 + 2e-16), z + 1e-15):
        _, off, links, theta = D.fit(zz, "samples")
        out.append(D.scale_ladder(off, links, D.Drawing(zz, theta, "samples"), 1.0, 4, 20.0, 400.0, "L2"))
    assert out[0] == out[1] == out[2]


def test_auto_scale_without_a_window_is_refused_on_its_key(tmp_path, capsys):
    write_csv(tmp_path / "c.csv", lissajous(size=1.0))
    cfg = design(tmp_path, {"points": "c.csv", "scale": "auto", "max_links": 2, "max_deviation_mm": 0.5})
    dest = tmp_path / "kit"
    assert main(["build", str(cfg), "-o", str(dest), "-q"]) == 2
    err = capsys.readouterr().err
    assert "curve.scale" in err and "auto: no scale" in err and "Traceback" not in err, err
    assert not dest.exists()
