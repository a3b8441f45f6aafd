"""Every kind has a tolerance model (the protocol's ``tolerance_model`` hook): gear trains (a spur
reducer, the herringbone pair, the planetary set, the rack). Each model moves the right way — more
play, fewer jams — and every shipped gear-train config gets a figure. (The wrist's and the Bennett's:
tests/mechanisms/wrist/test_tolerance_wrist.py and tests/mechanisms/bennett_butterfly/test_tolerance_bennett.py, with the kits they share.)"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from partgen import pipeline
from partgen.config.overrides import Overrides, parse_set
from partgen.core.protocol import tolerance_hook
from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms import REGISTRY

CONFIGS = Path(__file__).resolve().parents[2] / "configs"
N = 4000


def jam(model, n: int = N) -> float:
    return summarise(model, run_chunk(model, 0, 0, n))["overall"]["probability"]


def checked(name: str, *sets: str, samples: int = 24):
    over = Overrides(tuple(parse_set(s) for s in sets))
    loaded = pipeline.load(CONFIGS / f"{name}.yaml", over=over)
    kit = pipeline.make_kit(loaded)
    return loaded, kit, loaded.mechanism.check(loaded.spec, kit, samples, None)


def model(got, accuracy: float = 0.127, seated: bool = True):
    loaded, kit, result = got
    return tolerance_hook(loaded.mechanism)(loaded.spec, kit, result, accuracy, seated=seated)


def test_every_shipped_kind_has_a_model():
    kinds = {line.split(":", 1)[1].strip() for f in CONFIGS.glob("*.yaml") for line in f.read_text().splitlines()
             if line.startswith("kind:")}
    assert kinds >= {"gear_chain", "gear_pair", "gear_train", "wrist", "bennett_butterfly"}
    assert all(tolerance_hook(REGISTRY[k]) is not None for k in kinds)


@pytest.fixture(scope="module")
def trains():
    return {name: checked(name) for name in ("gear_train_reducer", "gear_train_herringbone", "gear_train_planetary",
                                              "gear_train_rack")}


def test_every_gear_train_config_gets_a_figure(trains):
    """Each model has its fits, meshes and (planetary) assembly margins, reads the check's own
    figures, and gives a probability strictly between 0 and 1 at ±0.3 mm."""
    for name, got in trains.items():
        m = model(got)
        groups = {x.group for x in m.margins}
        assert {"joint", "mesh"} <= groups, name
        fits = [r for r in got[2].figures["fits"]["rows"] if r["kind"] == "running"]
        assert sum(x.group == "joint" for x in m.margins) == len(fits), name
        p = jam(model(got, 0.3))
        assert 0.0 < p < 1.0, (name, p)
    reducer = model(trains["gear_train_reducer"])
    rows = trains["gear_train_reducer"][2].figures["meshes"]
    lash = {x.unit: x.nominal for x in reducer.margins if x.what == "backlash"}
    for r in rows:  # the seated credit is added to the backlash the check measured, never taken from it
        assert lash[f"{r['pair'][0]}/{r['pair'][1]}"] >= r["backlash_mm"]
    planetary = model(trains["gear_train_planetary"])
    assert {f"planet{i} assembly" for i in range(3)} <= set(planetary.units)
    assert {f"planet{i}/ring" for i in range(3)} <= set(planetary.units)


def test_seated_credits_play_only_where_the_meshes_take_it_up(trains):
    """A gear with one mesh is credited its bore's play; the planets (pushed out by the sun and in by
    the ring) and the sun (pushed by three planets) are credited none."""
    red_s, red_c = model(trains["gear_train_reducer"]), model(trains["gear_train_reducer"], seated=False)
    s = {(x.unit, x.what): x.nominal for x in red_s.margins}
    c = {(x.unit, x.what): x.nominal for x in red_c.margins}
    assert all(s[k] > c[k] for k in s if k[1] == "backlash")
    pl_s, pl_c = model(trains["gear_train_planetary"]), model(trains["gear_train_planetary"], seated=False)
    assert np.allclose(pl_s.nominal, pl_c.nominal) and np.allclose(pl_s.coeff, pl_c.coeff)


@pytest.mark.parametrize("name,key,small,large", [
    ("gear_train_rack", "shafts.running_clearance_diametral_mm", 0.1, 0.2),
    ("gear_train_planetary", "shafts.running_clearance_diametral_mm", 0.1, 0.2),
    ("gear_train_herringbone", "gears.backlash_per_gear_mm", 0.02, 0.1),
])
def test_more_play_fewer_jams(name, key, small, large):
    """The same design built with more running clearance (or backlash) jams less often, at ±0.2 mm."""
    tight, loose = checked(name, f"{key}={small}", samples=12), checked(name, f"{key}={large}", samples=12)
    pt, pl = jam(model(tight, 0.2)), jam(model(loose, 0.2))
    assert pl < pt, (name, pt, pl)


def test_backlash_moves_the_mesh_margins(trains):
    """The herringbone's mesh margins alone (from the check's own figures) at ±0.3 mm: with each gear's
    backlash allowance thinned by 0.1 mm the mesh jams far more often than at the design's."""
    got = trains["gear_train_herringbone"]
    m = model(got, 0.3)
    mesh = [k for k, x in enumerate(m.margins) if x.group == "mesh"]
    shrunk = replace(m, nominal=m.nominal - np.array([x.per_backlash for x in m.margins]) * 0.1)
    only = lambda mm: replace(mm, margins=tuple(mm.margins[k] for k in mesh), coeff=mm.coeff[:, mesh],  # noqa: E731
                                 nominal=mm.nominal[mesh])
    p, p_shrunk = jam(only(m)), jam(only(shrunk))
    assert 0.0 < p and p_shrunk > 5 * p and p_shrunk > p + 0.03, (p, p_shrunk)  # 0.6 % -> 7 % with 0.3 mm fits
