"""Every bore that takes a pin or axle is open where the pin enters (checks/bores.py), and every part
lies on the flat face that needs the least support (geometry.printing.least_support_flip): seeded
faults fail, the blocked volume matches its formula, the shipped kits' bores are all open."""

from __future__ import annotations

import math
from pathlib import Path
from dataclasses import replace

import manifold3d as m3d
import pytest

from partgen import pipeline
from partgen.checks.bed import bed_findings, bed_summary
from partgen.checks.bores import LEAD_MM, MARGIN_MM, bore_blocked, bore_findings
from partgen.core.parts import Bore, Part
from partgen.geometry.printing import (MIN_BED_CONTACT_MM2, bed_contact_area, best_orientation, least_support_flip,
                                      overhang_area)
from partgen.geometry.solid import mesh_arrays

from partgen.config.loader import PRINTERS_DIR, printer_limits, read_yaml, validate
from partgen.config.schema import Printer

R, SEG = 4.0, 32


def _limits(name: str):
    path = PRINTERS_DIR / f"{name}.yaml"
    return printer_limits(validate(Printer, read_yaml(path), path))


def _polygon_area(r: float, n: int = SEG) -> float:
    return 0.5 * n * r * r * math.sin(2 * math.pi / n)


def _block_with(void_z0: float, void_z1: float) -> m3d.Manifold:
    """A 30 × 30 × 20 block less a Ø8 cylinder from void_z0 to void_z1 on its centre line."""
    body = m3d.Manifold.cube((30.0, 30.0, 20.0))
    return body - m3d.Manifold.cylinder(void_z1 - void_z0, R, R, SEG).translate((15.0, 15.0, void_z0))


def _rules(found):
    return {(f.rule, f.parts[0]) for f in found if f.severity == "fail"}


DOWN_15 = Bore("pin", (15.0, 15.0, 20.0), (0.0, 0.0, -1.0), 2 * R, 15.0)  # a pin from the top, 15 mm deep


def test_a_sealed_bore_fails_with_its_cap_in_the_way():
    sealed = _block_with(5.0, 15.0)  # a cavity closed by 5 mm of the block above it
    found, figures = bore_findings([Part("sealed", "x", sealed, bores=(DOWN_15,))])
    assert ("bore-open", "sealed") in _rules(found)
    # what blocks the rod (the pin's radius less MARGIN) is the 5 mm cap above the cavity
    assert figures["sealed"]["pin"]["blocked_mm3"] == pytest.approx(5.0 * _polygon_area(R - MARGIN_MM), rel=2e-3)
    opened = _block_with(5.0, 25.0)  # the same bore open at the top
    found, figures = bore_findings([Part("opened", "x", opened, bores=(DOWN_15,))])
    assert not _rules(found) and figures["opened"]["pin"] == {"blocked_mm3": 0.0, "enters": "from the top"}


def test_a_skin_over_the_mouth_fails_and_a_pin_too_deep_or_too_wide_is_blocked():
    blind = _block_with(5.0, 20.0)  # blind from the top: a floor 5 mm thick
    assert bore_blocked(blind, DOWN_15) == 0.0
    assert bore_blocked(blind, replace(DOWN_15, depth_mm=16.0)) == pytest.approx((1 - MARGIN_MM) * _polygon_area(R - MARGIN_MM),
                                                                         rel=2e-3)
    assert bore_blocked(blind, replace(DOWN_15, diameter_mm=2 * R + 0.2)) > 1.0
    skinned = blind + m3d.Manifold.cube((30.0, 30.0, 0.2)).translate((0.0, 0.0, 19.8))  # a 0.2 mm skin over the mouth
    found, _ = bore_findings([Part("skinned", "x", skinned, bores=(DOWN_15,))])
    assert ("bore-open", "skinned") in _rules(found)
    # the same bore entered from the bed side of the block is the wrong end: its floor is in the way
    up = Bore("pin", (15.0, 15.0, 0.0), (0.0, 0.0, 1.0), 2 * R, 15.0)
    assert bore_blocked(blind, up) == pytest.approx(5.0 * _polygon_area(R - MARGIN_MM), rel=2e-3)


def test_the_entry_is_said_as_the_part_prints():
    blind = _block_with(5.0, 20.0)
    _, figures = bore_findings([Part("flipped", "x", blind, print_flip=True, bores=(DOWN_15,))])
    assert figures["flipped"]["pin"] == {"blocked_mm3": 0.0, "enters": "from the bed side"}
    assert LEAD_MM > 0  # the rod starts outside the part: a skin at the very mouth is inside it


@pytest.fixture(scope="module")
def pair():
    return pipeline.make_kit(pipeline.load(Path(__file__).resolve().parents[2] / "configs" / "gear_pair.yaml"))


def test_the_gear_pair_bores_are_open_and_a_sealed_gear_fails(pair):
    found, figures = bore_findings(pair.parts)
    assert not _rules(found) and set(figures) == {"gear1", "gear2"}
    g1 = next(p for p in pair.parts if p.name == "gear1")
    r = g1.bores[0].diameter_mm / 2 + 0.5
    skin = m3d.Manifold.cylinder(0.3, r, r, 64)  # a first layer printed over the bore's mouth
    broken = [replace(p, solid=p.solid + skin) if p is g1 else p for p in pair.parts]
    found, figures = bore_findings(broken)
    assert _rules(found) == {("bore-open", "gear1")}
    assert figures["gear1"]["post"]["blocked_mm3"] == pytest.approx(
        0.3 * _polygon_area(g1.bores[0].diameter_mm / 2 - MARGIN_MM), rel=0.02)


def test_every_bore_of_the_chain_is_open_and_fits_its_pin_closely(kit_of):
    kit = kit_of("butterfly").kit
    found, figures = bore_findings(kit.parts)
    assert not _rules(found)
    named = {p.name: {b.name for b in p.bores} for p in kit.parts if p.bores}
    assert {"G1", "drive", "D1", "M1", "B1", "B11", "base", "crank", "pen_holder"} <= set(named)
    assert named["base"] == {"drive axle", "leg1 peg", "leg2 peg", "leg3 peg", "leg4 peg"}
    assert "pen spigot" in named["B11"] and named["pen_holder"] == {"pen"}
    # each declared bore is the bore: a pin 0.4 mm wider (diametral; the running fits are 0.3) meets its wall
    seen = set()
    for p in kit.parts:
        for b in p.bores:
            if (id(p.solid), b.name) not in seen:
                seen.add((id(p.solid), b.name))
                assert bore_blocked(p.solid, replace(b, diameter_mm=b.diameter_mm + 0.4)) > 0.01, (p.name, b.name)


def test_a_part_lies_on_the_face_that_needs_least_support():
    """A T (a 10 × 10 × 10 stem under a 30 × 10 × 5 bar) lies on its bar; a cone stands on its base,
    not its tip (a point contact, which the bed rule fails)."""
    tee = m3d.Manifold.cube((10.0, 10.0, 10.0)).translate((10.0, 0.0, 0.0)) + \
        m3d.Manifold.cube((30.0, 10.0, 5.0)).translate((0.0, 0.0, 10.0))
    assert least_support_flip(tee) is True
    cone = m3d.Manifold.cylinder(10.0, 0.0, 8.0, 64)  # tip at z = 0
    assert least_support_flip(cone) is True
    found, _ = bed_findings([Part("cone", "x", cone)], _limits("prusa_mk4"))
    assert ("bed-contact", "cone") in _rules(found)
    found, figures = bed_findings([Part("cone", "x", cone, print_flip=True)], _limits("prusa_mk4"))
    assert not _rules(found) and figures["orientation"]["cone"]["contact_mm2"] == pytest.approx(_polygon_area(8.0, 64), abs=0.05)


def test_the_chain_parts_lie_on_their_least_support_face(kit_of):
    kit = kit_of("butterfly").kit
    found, figures = bed_findings(kit.parts, kit.printer)
    for p in (p for p in kit.parts if p.printed):
        v, f = mesh_arrays(p.solid)
        chosen, other = ((0, 0, 1), (0, 0, -1)) if p.print_flip else ((0, 0, -1), (0, 0, 1))
        assert overhang_area(v, f, chosen, 45.0) <= overhang_area(v, f, other, 45.0) + 0.05, p.name
    assert kit.part("crank").print_flip and not kit.part("pen_holder").print_flip
    # no other flat face (any plane of the hull the part's own faces lie in) needs less support
    for name in ("crank", "pen_holder", "drive_axle", "leg1", "G2"):
        p = kit.part(name)
        v, f = mesh_arrays(p.solid)
        chosen = overhang_area(v, f, (0, 0, 1) if p.print_flip else (0, 0, -1), 45.0)
        assert best_orientation(v, f, 45.0, MIN_BED_CONTACT_MM2).overhang_mm2 >= chosen - 0.05, name
    needs = {f.parts[0] for f in found if f.rule == "needs-supports"}
    assert needs == set(figures["needs_supports_mm2"]) and "pen_holder" in needs
    _, bores = bore_findings(kit.parts)
    line = bed_summary({**figures, "bores": bores})
    # every bore of every distinct printed part (gears with their own backlash are parts of their own)
    n = sum(len(p.bores) for p in {(id(p.solid), p.print_flip): p for p in kit.parts if p.printed}.values())
    assert n >= 43 and f"{n} of {n} bores open" in line and "upside down: crank;" in line and "pen_holder 78 mm²" in line
    ph = figures["orientation"]["pen_holder"]
    v, f = mesh_arrays(kit.part("pen_holder").solid)
    assert ph["contact_mm2"] == pytest.approx(bed_contact_area(v, f), abs=0.1) and ph["lies_on"] == "bottom"
