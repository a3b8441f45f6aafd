"""The schema base every kind shares: the header (kind, name, description, printer, material) and the
shared checks' settings (``config.schema.MotionChecks``) with one set of defaults, which are also the
resolved ``checks.settings.CheckSettings``' own."""

import dataclasses

from partgen.checks.settings import CheckSettings
from partgen.config.schema import DesignHeader, MotionChecks, PlateChecks, nested_models
from partgen.mechanisms import REGISTRY

SHARED = ("interference_tolerance_mm3", "min_clearance_mm", "min_contact_ratio", "min_tip_width_roads",
          "plate_margin_mm")


def test_every_kind_starts_with_the_header():
    for kind, mech in REGISTRY.items():
        assert issubclass(mech.schema, DesignHeader), kind


def test_every_checks_block_with_the_shared_settings_has_their_defaults():
    """Wherever a kind's schema holds any of the shared checks' settings, it is a MotionChecks and
    its defaults are the base's: no kind drifts (the chain had 3 roads of tip, the train 2)."""
    found = 0
    for kind, mech in REGISTRY.items():
        for model in nested_models(mech.schema):
            shared = set(SHARED) & set(model.model_fields)
            if not shared:
                continue
            found += 1
            base = PlateChecks if shared == {"plate_margin_mm"} else MotionChecks
            assert issubclass(model, base), (kind, model.__name__, shared)
            for name in base.model_fields:
                assert model.model_fields[name].default == base.model_fields[name].default, (kind, name)
    assert found >= 5  # the chain's, the train's, the pair's, the bevel's, the crossed pair's


def test_the_resolved_settings_default_to_the_schemas():
    want = {f.name: f.default for f in dataclasses.fields(CheckSettings)}
    names = {"interference_tolerance": "interference_tolerance_mm3", "min_clearance": "min_clearance_mm",
             "plate_margin": "plate_margin_mm"}
    for field, default in want.items():
        if field == "samples":
            continue
        assert MotionChecks.model_fields[names.get(field, field)].default == default, field
