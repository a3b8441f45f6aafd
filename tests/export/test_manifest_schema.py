"""docs/manifest.schema.json holds for the kit of every shipped config (one schema, every
mechanism), and it can fail: a part without its centre of mass, or a role nobody documented."""

import copy
import json
from pathlib import Path

import jsonschema
import numpy as np
import pytest
import trimesh

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "docs" / "manifest.schema.json").read_text())
CONFIGS = sorted(p.stem for p in (ROOT / "configs").glob("*.yaml"))


def _manifest(kit_of, name):
    dest = kit_of(name).dest
    return json.loads((dest / "manifest.json").read_text()), dest


def test_every_shipped_config_is_tested():
    assert len(CONFIGS) >= 10 and {"butterfly", "wrist_sphere", "bennett_butterfly", "gear_pair"} <= set(CONFIGS)


@pytest.mark.parametrize("name", CONFIGS)
def test_manifest_holds_the_schema(kit_of, name):
    man, dest = _manifest(kit_of, name)
    jsonschema.validate(man, SCHEMA)
    for p in man["parts"]:  # the centre of mass is the STL's own
        mesh = trimesh.load(dest / p["file"], file_type="stl")
        assert np.allclose(mesh.center_mass, p["centre_of_mass_mm"], atol=1e-3)
        assert 0 < p["printed_mass_g"] <= p["mass_g"] * (1 + 1e-9)


def test_the_schema_can_fail(kit_of):
    man = copy.deepcopy(_manifest(kit_of, "butterfly")[0])
    del man["parts"][0]["centre_of_mass_mm"]
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(man, SCHEMA)
    man = copy.deepcopy(_manifest(kit_of, "butterfly")[0])
    man["parts"][0]["role"] = "sprocket"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(man, SCHEMA)
