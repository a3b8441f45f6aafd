"""A seeded sweep of random but plausible designs of every mechanism (benchmarks/sweep.py makes
them, as a user tweaking a shipped YAML would): each is built or cleanly refused, never crashes;
every STL it writes is one closed, oriented manifold shell when read back as a slicer reads it,
with the manifest's volume; a sample of the chain kits is checked, and any design, mesh or
printability rule it fails is one build warned about. (The benchmark runs the same for as many
designs as you like: `python benchmarks/sweep.py --designs 300`.)"""

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent
_spec = importlib.util.spec_from_file_location("partgen_sweep", ROOT / "benchmarks" / "sweep.py")
sweep = sys.modules.setdefault("partgen_sweep", importlib.util.module_from_spec(_spec))
_spec.loader.exec_module(sweep)

SEED = 17
RULE_CHECKS = {"design", "mesh", "printability"}


@pytest.fixture(scope="module")
def chain_outcomes(tmp_path_factory):
    """Six random chain designs (gears and belts), built; the first two that build are checked."""
    out, checked = [], 0
    for d in sweep.designs("chain", 6, SEED):
        work = tmp_path_factory.mktemp(d["name"])
        o = sweep.run_one("chain", d, work, check=checked < 2, samples=24)
        checked += o.checked
        out.append(o)
    return out


def test_chain_designs_build_or_refuse_and_every_part_is_one_shell(chain_outcomes):
    bad = [(o.name, o.status, o.detail[:300]) for o in chain_outcomes if o.status in ("crashed", "bad_mesh")]
    assert bad == []
    built = [o for o in chain_outcomes if o.status == "built"]
    assert len(built) >= 3, [(o.name, o.detail[:200]) for o in chain_outcomes]  # the sweep tests something
    assert all(o.parts >= 20 for o in built)
    for o in chain_outcomes:
        if o.status == "refused":  # a refusal names the key and says why
            assert ": " in o.detail and "Traceback" not in o.detail


def test_checked_chain_kits_fail_no_rule_build_did_not_warn_about(chain_outcomes):
    checked = [o for o in chain_outcomes if o.checked]
    assert len(checked) == 2
    for o in checked:
        unwarned = [(rule, msg) for (rule, warned), msg in zip(o.fails, o.messages)
                    if not warned and (rule in sweep.RULES or rule in RULE_CHECKS)]
        assert unwarned == [], (o.name, unwarned)


def test_wrist_designs_build_one_shell_parts(tmp_path):
    for d in sweep.designs("wrist", 2, SEED):
        d["wrist"]["sweep"] = {"theta_steps": 2, "psi_steps": 6}  # the coarsest sweep: this is about meshes
        o = sweep.run_one("wrist", d, tmp_path / d["name"])
        assert o.status in ("built", "refused"), (o.name, o.status, o.detail[:400])


def test_a_bennett_design_builds_one_shell_parts(tmp_path):
    d = sweep.designs("bennett", 1, SEED)[0]
    o = sweep.run_one("bennett", d, tmp_path / d["name"])
    assert o.status == "built", (o.status, o.detail[:400])
    assert o.parts >= 13
