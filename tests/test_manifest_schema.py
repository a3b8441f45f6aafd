"""docs/manifest.schema.json holds for the kit of every shipped config (one schema, every
mechanism), and it can fail: a part without its centre of mass, or a role nobody documented."""

import copy
import json
from pathlib import Path

import jsonschema
import numpy as np
import pytest
import trimesh

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = json.loads((ROOT / "docs" / "manifest.schema.json").read_text())
CONFIGS = sorted(p.stem for p in (ROOT / "configs").glob("*.yaml"))


@pytest.fixture(scope="module")
def manifests(shipped_kits):
    return {name: (json.loads((dest / "manifest.json").read_text()), dest) for name, (_, _, _, dest) in shipped_kits.items()}


def test_every_shipped_config_has_a_kit(manifests):
    assert set(manifests) == set(CONFIGS)


@pytest.mark.parametrize("name", CONFIGS)
def test_manifest_holds_the_schema(manifests, name):
    man, dest = manifests[name]
    jsonschema.validate(man, SCHEMA)
    for p in man["parts"]:  # the centre of mass is the STL's own
        mesh = trimesh.load(dest / p["file"], file_type="stl")
        assert np.allclose(mesh.center_mass, p["centre_of_mass_mm"], atol=1e-3)
        assert 0 < p["printed_mass_g"] <= p["mass_g"] * (1 + 1e-9)


def test_the_schema_can_fail(manifests):
    man = copy.deepcopy(manifests["butterfly"][0])
    del man["parts"][0]["centre_of_mass_mm"]
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(man, SCHEMA)
    man = copy.deepcopy(manifests["butterfly"][0])
    man["parts"][0]["role"] = "sprocket"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(man, SCHEMA)
