"""A link too short to carry its two gears is refused on the key that made it short (the link
table's length, or the curve), before the chain's tooth rules blame ``teeth``."""

import yaml
from helpers import ROOT, modified

from partgen.cli.main import main


def _err(tmp_path, capsys, p):
    assert main(["build", str(p), "-o", str(tmp_path / "kit"), "-q"]) == 2
    assert not (tmp_path / "kit").exists()
    return capsys.readouterr().err


def test_a_short_link_in_a_table_names_its_length(tmp_path, capsys):
    p = modified("butterfly_liu2017", tmp_path, {"links[7].length_mm": 0.011})
    err = _err(tmp_path, capsys, p)
    assert "links[7].length_mm: link 8" in err and "0.011 mm long" in err and "at least 15 mm" in err, err


def test_a_curve_term_that_makes_a_tiny_link_names_the_curve(tmp_path, capsys):
    err = _err(tmp_path, capsys, modified("butterfly", tmp_path, {"curve.polar.sin.7": 0.011}))
    assert ": curve: at 30 mm per unit the curve makes link" in err and "curve.drop_links" in err, err
    # the link it names is the short one: its length times the printer's smallest gear is refused
    length = float(err.split(" mm long")[0].split()[-1])
    assert 0 < length < 15


def test_a_link_of_exactly_the_smallest_gear_is_not_refused_for_its_length(tmp_path, capsys):
    p = modified("butterfly_liu2017", tmp_path, {"links[7].length_mm": 15.0})
    code = main(["build", str(p), "-o", str(tmp_path / "kit"), "-q"])
    err = capsys.readouterr().err
    assert "too short to carry two gears" not in err
    assert code in (0, 2)  # the chain's own rules may still refuse the teeth, on their key


def test_neither_curve_nor_links_is_one_error_on_curve(tmp_path, capsys):
    err = _err(tmp_path, capsys, modified("butterfly", tmp_path, drop=["curve"]))
    assert ": curve: required key is missing" in err and "more problem" not in err, err


def test_both_curve_and_links_is_an_error_on_links(tmp_path, capsys):
    liu = yaml.safe_load((ROOT / "configs" / "butterfly_liu2017.yaml").read_text())
    err = _err(tmp_path, capsys, modified("butterfly", tmp_path, {"links": liu["links"]}))
    assert ": links: give 'curve'" in err and "not both" in err, err


def test_a_vanishing_curve_term_is_refused_on_its_key(tmp_path, capsys):
    # 1e-300 made no link, so drop_links' L10 was "not there"
    err = _err(tmp_path, capsys, modified("butterfly", tmp_path, {"curve.polar.sin.9": 1e-300}))
    assert ": curve.polar.sin.9: a term under 1e-9" in err and err.count("got") == 1, err
