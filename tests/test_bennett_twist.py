"""A Bennett linkage within a degree of planar is refused on the twist's key before any geometry
(the bad-input run found α = 0.011° writing link04 as two touching bodies)."""

import pytest
from helpers import modified

from partgen.mechanisms.bennett_butterfly.resolve import MIN_TWIST_DEG, resolve_bennett
from partgen.mechanisms import load_design
from partgen.errors import ConfigError


def _design(tmp_path, **linkage):
    return load_design(modified("bennett_butterfly", tmp_path, {f"linkage.{k}": v for k, v in linkage.items()}))


@pytest.mark.parametrize("linkage, key", [
    ({"alpha_deg": 0.011}, "linkage.alpha_deg"),
    ({"alpha_deg": 179.5}, "linkage.alpha_deg"),
    ({"alpha_deg": 1.5, "b_mm": 50.0}, "linkage.b_mm"),  # β = asin(50/105 sin 1.5°) = 0.71°
])
def test_an_all_but_planar_twist_is_refused_on_its_key(tmp_path, linkage, key):
    with pytest.raises(ConfigError) as e:
        resolve_bennett(_design(tmp_path, **linkage))
    assert e.value.key_path == key and "all but planar" in e.value.problem


def test_the_smallest_twist_passes_the_rule(tmp_path):
    params = resolve_bennett(_design(tmp_path, alpha_deg=MIN_TWIST_DEG))
    assert params is not None
