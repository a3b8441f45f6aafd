"""A drawn curve in (``curve.points`` as CSV or inline, ``curve.svg``), a gear-chain kit out: the
readers, the closed-curve rules, bad input (exit 2, file and key or line, nothing written) and the
whole path build → trace with the deviation measured against the user's samples."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import yaml
from helpers import modified

from partgen import pipeline
from partgen.cli.main import main
from partgen.config.drawing import read_svg_path
from partgen.errors import ConfigError


SCALE_MM = 100.0


def epicycle(n=400, small=5.0):
    """P = 100 e^{iθ} + 30 e^{-2iθ} + small·e^{4iθ} mm at n equal θ steps: two links of 100 and
    30 mm and one of ``small`` mm (under a 20 mm printer minimum when small < 20)."""
    t = 2 * np.pi * np.arange(n) / n
    return 100 * np.exp(1j * t) + 30 * np.exp(-2j * t) + small * np.exp(4j * t) * np.exp(0.3j)


def write_csv(path, z, header="x_mm,y_mm"):
    path.write_text(header + "\n" + "".join(f"{p.real:.9f},{p.imag:.9f}\n" for p in z))


def design(tmp_path, curve: dict, name="drawn") -> "Path":
    """The default design with ``curve`` drawn, its backlash pinned (0.1 mm, what auto gives on the
    Fortus): auto play builds and checks two kits a design, and no test here is about it
    (tests/studies/test_autoplay*.py are)."""
    return modified("butterfly", tmp_path, {"name": name, "curve": curve, "gears.backlash_per_gear_mm": 0.1},
                    name=f"{name}.yaml")


def run_bad(tmp_path, capsys, cfg, *fragments):
    dest = tmp_path / "out_kit"
    code = main(["build", str(cfg), "-o", str(dest), "-q"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err and not dest.exists()
    for f in fragments:
        assert f in err, (f, err)
    return err


# --- bad input -------------------------------------------------------------------------------------

def test_too_few_points(tmp_path, capsys):
    write_csv(tmp_path / "c.csv", epicycle(n=12))
    run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv"}), "c.csv", "12 points", "at least 16")


@pytest.mark.parametrize("cell, fragment", [("nan", "not a finite number"), ("abc", "'abc' is not a number"),
                                            ("1e9", "beyond")])
def test_bad_cell_names_its_line(tmp_path, capsys, cell, fragment):
    z = epicycle()
    lines = ["x_mm,y_mm"] + [f"{p.real},{p.imag}" for p in z]
    lines[6] = f"{cell},{z[5].imag}"  # the file's line 7
    (tmp_path / "c.csv").write_text("\n".join(lines) + "\n")
    run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv"}), "c.csv: line 7", fragment)


def test_bad_header(tmp_path, capsys):
    write_csv(tmp_path / "c.csv", epicycle(), header="x,y")
    run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv"}), "c.csv: line 1", "x_mm,y_mm")


def test_open_curve_needs_close(tmp_path, capsys):
    z = epicycle()[:300]  # three quarters of the way round
    write_csv(tmp_path / "c.csv", z)
    err = run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv"}), "drawn.yaml: curve.points", "open",
                  "curve.close: true")
    gap = abs(z[-1] - z[0])
    assert f"{gap:.3g} mm" in err
    # with close: true the ends are joined and the chain is fitted to the closed curve
    spec = pipeline.load(design(tmp_path, {"points": "c.csv", "close": True, "max_deviation_mm": 60.0})).spec
    d = spec.mechanism.drawing
    assert len(d.samples) > 300 and abs(d.samples[-1] - d.samples[0]) < gap / 10


def test_file_outside_the_design_folder(tmp_path, capsys):
    (tmp_path / "sub").mkdir()
    write_csv(tmp_path / "c.csv", epicycle())
    cfg = design(tmp_path / "sub", {"points": "../c.csv"})
    run_bad(tmp_path, capsys, cfg, "curve.points", "outside the design's folder")


def test_curve_too_small_for_the_printer_names_the_scale(tmp_path, capsys):
    write_csv(tmp_path / "c.csv", epicycle() / 10)  # links 10, 3, 0.5 mm: under the 20 mm minimum
    err = run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv", "max_deviation_mm": 1.0}),
                  "curve.max_deviation_mm", "20 mm", "curve.scale: ")
    scale = float(err.split("curve.scale: ")[1].split()[0])
    # the suggestion holds: at that scale the two long links are printable and the budget met
    spec = pipeline.load(design(tmp_path, {"points": "c.csv", "max_deviation_mm": 1.0, "scale": scale})).spec
    assert spec.mechanism.drawing.rows[spec.mechanism.drawing.chosen - 1].hausdorff_mm <= 1.0


def test_too_few_links_allowed_names_the_count(tmp_path, capsys):
    write_csv(tmp_path / "c.csv", epicycle(small=25.0))
    err = run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv", "max_deviation_mm": 0.5, "max_links": 2}),
                  "curve.max_deviation_mm", "curve.max_links: 3")


SVG_HEAD = '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 50 50">'


@pytest.mark.parametrize("body, key, fragment", [
    ("<rect width='10' height='10'/>", "curve.svg", "no <path>"),
    ("<path d='M 0 0 L 10 0 L 10 10'/>", "curve.svg", "no closed subpath"),
])
def test_svg_without_a_closed_path(tmp_path, capsys, body, key, fragment):
    (tmp_path / "c.svg").write_text(SVG_HEAD + body + "</svg>")
    run_bad(tmp_path, capsys, design(tmp_path, {"svg": "c.svg"}), f"c.svg: {key}", fragment)


def test_svg_missing_path_id(tmp_path, capsys):
    (tmp_path / "c.svg").write_text(SVG_HEAD + "<path id='a' d='M 0 0 L 10 0 L 10 10 Z'/></svg>")
    run_bad(tmp_path, capsys, design(tmp_path, {"svg": "c.svg", "svg_path_id": "b"}),
            "drawn.yaml: curve.svg_path_id", "no <path> with id 'b'", "its paths: a")


def test_svg_entities_are_not_expanded(tmp_path, capsys):
    bomb = ('<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]>'
            + SVG_HEAD + "<path id='&b;' d='M 0 0 L 10 0 L 10 10 Z'/></svg>")
    (tmp_path / "c.svg").write_text(bomb)
    run_bad(tmp_path, capsys, design(tmp_path, {"svg": "c.svg"}), "c.svg: curve.svg", "entities")


def test_svg_without_units_needs_a_scale(tmp_path, capsys):
    (tmp_path / "c.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100%" viewBox="0 0 50 50">'
                                    "<path d='M 0 0 L 10 0 L 10 10 Z'/></svg>")
    run_bad(tmp_path, capsys, design(tmp_path, {"svg": "c.svg"}), "curve.svg_mm_per_unit")


# --- the readers -------------------------------------------------------------------------------------

def test_svg_units_arcs_and_transforms(tmp_path):
    # a circle of radius 10 user units as two arcs, inside a translated group; the page maps 50 units
    # onto 100 mm, so the circle is 20 mm in radius, centred at (2·(25+5), -2·25) mm (y flipped up)
    (tmp_path / "c.svg").write_text(
        SVG_HEAD + "<g transform='translate(5 0)'><path id='o' d='M 15 25 A 10 10 0 0 1 35 25 A 10 10 0 0 1 15 25 Z'/>"
        "</g></svg>")
    xy = read_svg_path(tmp_path / "c.svg", None, None, tmp_path / "x.yaml")
    r = np.hypot(xy[:, 0] - 60.0, xy[:, 1] + 50.0)
    assert len(xy) > 100 and np.allclose(r, 20.0, atol=1e-6)
    # a stated scale overrides the page's units: 1 mm per user unit
    xy1 = read_svg_path(tmp_path / "c.svg", "o", 1.0, tmp_path / "x.yaml")
    assert np.allclose(np.hypot(xy1[:, 0] - 30.0, xy1[:, 1] + 25.0), 10.0, atol=1e-6)


def test_cubic_bezier_points_lie_on_the_curve(tmp_path):
    # a closed path of one cubic and its chord: points satisfy the Bernstein form B(t) for some t
    (tmp_path / "c.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="40mm" '
                                    'viewBox="0 0 40 40"><path d="M 0 0 C 0 30 40 30 40 0 Z"/></svg>')
    xy = read_svg_path(tmp_path / "c.svg", None, None, tmp_path / "x.yaml")
    t = np.linspace(0, 1, 20001)
    bx = 3 * (1 - t) * t ** 2 * 40 + t ** 3 * 40
    by = -(3 * (1 - t) ** 2 * t * 30 + 3 * (1 - t) * t ** 2 * 30)
    curve = xy[xy[:, 1] < -1e-9]
    from scipy.spatial import cKDTree  # each point's nearest of the 20001 B(t) (a brute-force matrix was ~3 s)
    d, _ = cKDTree(np.column_stack([bx, by])).query(curve)
    assert len(curve) > 50 and d.max() < 0.01


def test_inline_points_match_the_csv(tmp_path):
    z = epicycle(n=64, small=0.0)
    write_csv(tmp_path / "c.csv", z)
    a = pipeline.load(design(tmp_path, {"points": "c.csv"})).spec.mechanism
    b = pipeline.load(design(tmp_path, {"points": [[float(p.real), float(p.imag)] for p in z]}, name="inline")).spec.mechanism
    assert [(l.name, round(l.length, 6)) for l in a.chain.links] == [(l.name, round(l.length, 6)) for l in b.chain.links]
    assert sorted((l.name, round(l.length, 6)) for l in a.chain.links) == [("L1", 100.0), ("M2", 30.0)]


# --- the whole path --------------------------------------------------------------------------------------

def test_build_and_trace_measure_the_pen_against_the_samples(tmp_path, capsys):
    """The 5 mm term is under the printer's 20 mm link: two links are kept, and trace's deviation is
    the pen of the kit as built against the CSV's samples — at the same crank angle exactly the
    dropped 5 mm term, and a Hausdorff distance checked by brute force."""
    z = epicycle(small=5.0)
    write_csv(tmp_path / "c.csv", z)
    cfg = design(tmp_path, {"points": "c.csv", "max_deviation_mm": 6.0})
    kit = tmp_path / "kit"
    assert main(["build", str(cfg), "-o", str(kit)]) == 0
    out = capsys.readouterr().out
    assert "links vs deviation" in out and "<- chosen" in out
    assert (kit / "curve.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()
    assert yaml.safe_load((kit / "design.yaml").read_text())["curve"]["points"] == "curve.csv"
    man = json.loads((kit / "manifest.json").read_text())
    assert sorted(l["name"] for l in man["design"]["links"]) == ["L1", "M2"]
    assert main(["trace", str(kit), "--json", "--no-plots"]) == 0
    stats = json.loads(capsys.readouterr().out)
    assert stats["target"] == "drawing" and stats["drawing_samples"] == 400
    assert stats["max_deviation_mm"] == pytest.approx(5.0, abs=1e-5)
    assert stats["rms_mm"] == pytest.approx(5.0, abs=1e-5)
    # independent: the kit's links as written, turned at their speeds, against the samples
    t = np.linspace(0, 2 * np.pi, 8000, endpoint=False)
    pen = sum(l["length_mm"] * np.exp(1j * (l["speed"] * t + math.radians(l["initial_angle_deg"])))
              for l in man["design"]["links"]) + complex(*man["design"]["ground_offset_mm"])
    dist = np.abs(pen[:, None] - z[None, :])
    brute = max(dist.min(axis=0).max(), dist.min(axis=1).max())  # point sets: ≥ the polyline figure
    assert 0.5 < stats["hausdorff_mm"] <= brute + 1e-6 and brute - stats["hausdorff_mm"] < 1.0
    assert stats["hausdorff_mm"] <= 6.0
    # the report carries the trade-off: one row per chain measured, the chosen one within budget
    assert main(["report", str(kit), "-o", str(tmp_path / "report"), "--samples", "36"]) in (0, 1)
    page = (tmp_path / "report" / "index.html").read_text()
    assert "Links against deviation from curve.csv (400 samples, by samples)" in page
    assert "2 chosen" in page and "your drawing" in page


def test_a_curve_drawn_clockwise_is_reversed_so_link_1_turns_forwards(tmp_path):
    z = np.conj(epicycle(small=0.0))  # the mirror image, drawn the other way: M1 100 mm, L2 30 mm
    write_csv(tmp_path / "c.csv", z)
    mech = pipeline.load(design(tmp_path, {"points": "c.csv"})).spec.mechanism
    assert [(l.name, round(l.length, 6)) for l in mech.chain.links] == [("L1", 100.0), ("M2", 30.0)]
    d = mech.drawing
    assert d.samples[0] == pytest.approx(z[0]) and d.samples[1] == pytest.approx(z[-1])
    from partgen.design.drawing import measure
    assert measure(mech.chain, d)[1] < 1e-6  # the chain passes through every sample at its crank angle


def test_oversized_file_and_short_inline_list(tmp_path, capsys):
    from partgen.config.drawing import MAX_FILE_BYTES

    with open(tmp_path / "c.csv", "w") as f:
        f.write("x_mm,y_mm\n")
        f.write("1.000000000,2.000000000\n" * (MAX_FILE_BYTES // 24 + 10))
    run_bad(tmp_path, capsys, design(tmp_path, {"points": "c.csv"}), "curve.points", "MB", "at most")
    pts = [[float(p.real), float(p.imag)] for p in epicycle(n=10)]
    run_bad(tmp_path, capsys, design(tmp_path, {"points": pts}, name="inline"), "inline.yaml: curve.points",
            "10 points", "at least 16")


def test_parametrisation_is_the_users_choice(tmp_path):
    # the same CSV, unevenly sampled: by samples θ_i = 2πi/n; by arc length θ follows the distance walked
    t = 2 * np.pi * np.arange(300) / 300
    u = t + 0.3 * np.sin(t)  # uneven steps along the curve
    z = 100 * np.exp(1j * u) + 30 * np.exp(-2j * u)
    write_csv(tmp_path / "c.csv", z)
    a = pipeline.load(design(tmp_path, {"points": "c.csv", "max_deviation_mm": 50.0})).spec.mechanism.drawing
    b = pipeline.load(design(tmp_path, {"points": "c.csv", "max_deviation_mm": 50.0, "parametrisation": "arc_length"},
                             name="arc")).spec.mechanism.drawing
    assert a.parametrisation == "samples" and np.allclose(a.theta, t)
    walked = np.concatenate([[0], np.cumsum(np.abs(np.diff(z)))])
    perimeter = walked[-1] + abs(z[0] - z[-1])
    assert b.parametrisation == "arc_length" and np.allclose(b.theta, 2 * np.pi * walked / perimeter)
