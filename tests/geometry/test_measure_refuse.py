"""geometry.measure.refuse_oversize: what every kind's build refuses as too big for its printer."""

import manifold3d as m3d
import pytest

from partgen.core.parts import Part
from partgen.errors import DesignError
from partgen.geometry.measure import refuse_oversize


def test_a_part_too_big_in_every_orientation_is_refused_naming_the_key():
    slab = Part("slab", "plate", m3d.Manifold.cube([50.0, 20.0, 10.0]))
    refuse_oversize([slab], (60.0, 60.0, 60.0), "gears.module_mm")  # fits as it is
    refuse_oversize([slab], (15.0, 25.0, 55.0), "gears.module_mm")  # fits turned: 10 × 20 × 50
    with pytest.raises(DesignError) as e:
        refuse_oversize([slab], (45.0, 45.0, 45.0), "gears.module_mm")
    assert e.value.key_path == "gears.module_mm" and "slab measures" in str(e.value) and "any orientation" in str(e.value)
    bought = Part("bought", "axle", m3d.Manifold.cube([500.0, 5.0, 5.0]), printed=False)
    refuse_oversize([bought], (45.0, 45.0, 45.0), "gears.module_mm")  # not printed: not measured
