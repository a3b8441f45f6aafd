"""Every printed part meets the bed on a flat contact, is one shell, and says when it needs supports
(checks/bed.py): seeded faults fail, measured areas match their formulas."""

from __future__ import annotations

import math

import manifold3d as m3d
import pytest

from partgen.checks.bed import MIN_BED_CONTACT_MM2, bed_contact_and_overhang, bed_findings
from partgen.core.parts import Part
from partgen.config.loader import PRINTERS_DIR, printer_limits, read_yaml, validate
from partgen.config.schema import Printer
from partgen.geometry.solid import print_arrays


def _limits(name: str):
    path = PRINTERS_DIR / f"{name}.yaml"
    return printer_limits(validate(Printer, read_yaml(path), path))


def _rules(parts):
    found, figures = bed_findings(parts, _limits("prusa_mk4"))
    return {(f.rule, f.parts[0]) for f in found}, found, figures


def test_a_block_stands_on_its_face():
    block = m3d.Manifold.cube((20.0, 10.0, 5.0))
    bed, over = bed_contact_and_overhang(*print_arrays(block)[:2], 45.0)
    assert bed == pytest.approx(200.0, rel=1e-9) and over == 0.0
    assert _rules([Part("block", "x", block)])[0] == set()


def test_a_sphere_touches_at_a_point_and_fails():
    ball = m3d.Manifold.sphere(10.0, 96)
    bed, over = bed_contact_and_overhang(*print_arrays(ball)[:2], 45.0)
    assert bed < 1.0  # the lowest facet at most
    # the lower cap steeper than 45° from the vertical: a cap of height r(1 - sin 45°), area 2πr h
    assert over == pytest.approx(2 * math.pi * 10.0 * 10.0 * (1 - math.sin(math.radians(45))), rel=0.03)
    rules, found, figures = _rules([Part("ball", "x", ball)])
    assert ("bed-contact", "ball") in rules and figures["needs_supports_mm2"]["ball"] == pytest.approx(over, abs=0.1)


def test_a_sealed_bore_is_a_second_shell_and_fails():
    body = m3d.Manifold.cube((30.0, 30.0, 20.0))
    void = m3d.Manifold.cylinder(10.0, 4.0, 4.0, 64).translate((15.0, 15.0, 5.0))  # closed at both ends
    sealed = body - void
    rules, found, _ = _rules([Part("sealed", "x", sealed)])
    assert ("shells", "sealed") in rules
    opened = body - m3d.Manifold.cylinder(30.0, 4.0, 4.0, 64).translate((15.0, 15.0, 5.0))  # open at the top
    assert ("shells", "opened") not in _rules([Part("opened", "x", opened)])[0]


def test_an_overhang_is_measured_and_flipping_removes_it():
    """A T: a 10 × 10 × 10 stem under a 30 × 10 × 5 bar overhangs 20 × 10 mm² of ceiling; printed
    upside down it stands on the bar with no overhang."""
    tee = m3d.Manifold.cube((10.0, 10.0, 10.0)).translate((10.0, 0.0, 0.0)) + \
        m3d.Manifold.cube((30.0, 10.0, 5.0)).translate((0.0, 0.0, 10.0))
    bed, over = bed_contact_and_overhang(*print_arrays(tee)[:2], 45.0)
    assert bed == pytest.approx(100.0) and over == pytest.approx(200.0)
    bed, over = bed_contact_and_overhang(*print_arrays(tee, True)[:2], 45.0)
    assert bed == pytest.approx(300.0) and over == pytest.approx(0.0, abs=1e-9)


def test_a_thin_edge_is_too_little_contact():
    wedge = m3d.Manifold.cube((15.0, 1.0, 10.0))  # 15 mm² on the bed
    rules, found, figures = _rules([Part("fin", "x", wedge)])
    assert 15.0 < MIN_BED_CONTACT_MM2 and ("bed-contact", "fin") in rules
    assert figures["least_bed_contact_mm2"] == pytest.approx(15.0)
