"""A running clearance under the round features' facet depth is warned by build with the rule the
check fails it by ("fit"): the sweep found the drive axle jammed in the base at 0 and 0.005 mm
radial with no warning."""

import pytest
import yaml

from partgen.mechanisms.gear_chain.resolve import load


def _spec(tmp_path, diametral):
    d = yaml.safe_load(open("configs/butterfly.yaml"))
    d["joints"]["running_clearance_diametral_mm"] = diametral
    p = tmp_path / "d.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    return load(p)


@pytest.mark.parametrize("diametral, warned", [(0.0, True), (0.01, True), (0.02, False), (0.2, False)])
def test_running_clearance_under_the_facets_is_warned_with_the_fit_rule(tmp_path, diametral, warned):
    fits = [f for f in _spec(tmp_path, diametral).mechanism.findings if f.rule == "fit"]
    assert bool(fits) == warned
    if warned:
        assert fits[0].severity == "warn" and fits[0].key == "joints" and "0.02 mm diametral" in fits[0].message
