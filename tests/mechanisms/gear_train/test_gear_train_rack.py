"""Rack and pinion of kind gear_train: the rack's printed teeth are the basic rack (thickness at the
pitch line, flank angle), the pinion moves it r_p per radian on the printed sections with the
designed backlash, a rack pushed into the pinion fails, and the contact ratio is the textbook one."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely.geometry import LineString

from partgen import pipeline
from partgen.design.rack import rack_contact_ratio
from partgen.mechanisms.gear_train.mechanism import MECHANISM
from partgen.mechanisms.gear_train.rack.kit import build_rack
from partgen.testing import section_outline


@pytest.fixture(scope="module")
def rack(kit_of):
    return kit_of("gear_train_rack")


def test_printed_rack_teeth_are_the_basic_rack(rack):
    mesh = trimesh.load(rack.dest / "rack.stl")
    sec = section_outline(mesh, 4.0)
    spec = rack.loaded.spec
    # the STL's frame: the rack lies as built, its pitch line at the back's depth above its lowest y
    y_pitch = sec.bounds[1] + spec.back + spec.system.dedendum_coeff * 2.0
    cut = sec.intersection(LineString([(sec.bounds[0] - 1, y_pitch), (sec.bounds[2] + 1, y_pitch)]))
    widths = [g.length for g in cut.geoms]
    assert len(widths) == spec.rack_teeth
    assert np.allclose(widths, math.pi * 2.0 / 2 - 0.1, atol=1e-4)
    # the flank angle: thickness 1 mm above the pitch line is 2 tan α less
    up = sec.intersection(LineString([(sec.bounds[0] - 1, y_pitch + 1), (sec.bounds[2] + 1, y_pitch + 1)]))
    assert np.allclose([g.length for g in up.geoms], math.pi - 0.1 - 2 * math.tan(math.radians(20)), atol=1e-4)


def test_rack_contact_ratio_textbook():
    # z = 20, x = 0, 20°: (√(11² − 9.397²) − 10 sin 20° + 1/sin 20°)/(π cos 20°) per mm of module
    rb = 10 * math.cos(math.radians(20))
    want = (math.sqrt(11 ** 2 - rb ** 2) - 10 * math.sin(math.radians(20)) + 1 / math.sin(math.radians(20))) / (
        math.pi * math.cos(math.radians(20)))
    assert rack_contact_ratio(20, 1.0, math.radians(20)) == pytest.approx(want)
    assert 1.6 < want < 1.8


def test_check_and_trace_over_the_travel(rack):
    spec, kit = rack.loaded.spec, rack.kit
    result = MECHANISM.check(spec, kit, 16)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    b = result.figures["rack_mesh"]["backlash_mm"]
    assert 0.185 < b["min"] <= b["max"] < 0.215  # the two thinnings, 0.1 mm each, within the flanks' chords
    tr = MECHANISM.trace(spec, kit, 16, None)
    assert tr.stats["ratio_measured"] == pytest.approx(spec.pinion.pitch_radius, rel=1e-4)
    assert tr.stats["transmission_error_um"]["peak_to_peak"] < 20


def test_teeth_too_thick_for_the_mesh_fail(rack):
    spec = rack.loaded.spec
    fat = dataclasses.replace(spec.system, backlash_per_gear=-0.2)  # each tooth 0.2 mm thicker than nominal
    s = dataclasses.replace(spec, system=fat, pinion=dataclasses.replace(spec.pinion, system=fat))
    result = MECHANISM.check(s, build_rack(s), 8)
    assert not result.ok and any(f.check == "mesh" for f in result.findings if f.severity == "fail")


def test_rack_on_a_desktop_printer():
    loaded = pipeline.load(Path(__file__).resolve().parents[3] / "configs" / "gear_train_rack.yaml",
                           over=pipeline.overrides(printer="prusa_mk4"))
    result = MECHANISM.check(loaded.spec, MECHANISM.build(loaded.spec), 8)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
