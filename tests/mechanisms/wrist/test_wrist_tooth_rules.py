"""A wrist's dome teeth must be rooted in the pitch surface on a footprint the printer can lay
down; otherwise the design is refused on the key to change (before any geometry: a detached ball
is a second shell in gear1's STL)."""

import math

import numpy as np
import pytest
import yaml

from partgen.cli.main import main
from partgen.geometry import wrist as W

CFG = "configs/wrist_sphere.yaml"


def _design(tmp_path, radius, height):
    d = yaml.safe_load(open(CFG))
    d["wrist"]["tooth"] = {"shape": "dome", "radius_mm": radius, "height_mm": height}
    p = tmp_path / "w.yaml"
    p.write_text(yaml.safe_dump(d))
    return p


@pytest.mark.parametrize("radius, height, key, words", [
    (0.011, 2.6, "wrist.tooth.radius_mm", "float above the surface"),   # the fuzz case that wrote 20 shells
    (2.8, 5.6, "wrist.tooth.height_mm", "float above the surface"),
    (2.8, 0.011, "wrist.tooth.height_mm", "under the printer's 1 mm wall"),
])
def test_a_dome_that_cannot_root_is_refused_on_its_key(tmp_path, capsys, radius, height, key, words):
    p = _design(tmp_path, radius, height)
    assert main(["build", str(p), "-o", str(tmp_path / "kit"), "-q"]) == 2
    err = capsys.readouterr().err
    assert f"{key}:" in err and words in err, err
    assert not (tmp_path / "kit").exists()


def test_the_footprint_rule_is_the_balls_section_by_the_surface():
    """The rule's footprint 2·sqrt(h(2r − h)) is where the placed ball meets the surface: measure it
    on the dome that dome_teeth places on a plane (radius_of constant at the pole's tangent plane)."""
    r, h = 2.8, 0.6
    dome = W.dome_teeth([(0.0, 1)], lambda a: np.full_like(np.asarray(a, float), 50.0), r, h)[0]
    c = np.array(dome.centre)
    # at the pole the surface is the sphere of radius 50 about the origin; its normal is z
    assert c[2] + r == pytest.approx(50.0 + h, abs=1e-9)
    below = 50.0 - c[2]  # the plane z = 50 cuts the ball at this height above its centre
    measured = 2 * math.sqrt(r * r - below * below)
    assert measured == pytest.approx(2 * math.sqrt(h * (2 * r - h)), rel=1e-9)


@pytest.mark.parametrize("bend", [0.011, 2.0])
def test_a_bend_too_small_for_a_sound_socket_sweep_is_refused(tmp_path, capsys, bend):
    """2° made gear2's swept sockets edges shared by four faces (exit 3); 10° builds."""
    d = yaml.safe_load(open("configs/wrist_quasi_ellipsoid.yaml"))
    d["wrist"]["max_bend_deg"] = bend
    p = tmp_path / "w.yaml"
    p.write_text(yaml.safe_dump(d))
    assert main(["build", str(p), "-o", str(tmp_path / "kit"), "-q"]) == 2
    assert "wrist.max_bend_deg:" in capsys.readouterr().err
    assert not (tmp_path / "kit").exists()
