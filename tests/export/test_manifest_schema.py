"""docs/manifest.schema.json holds for the kit of every shipped config (one schema, every
mechanism), and it can fail: a part without its centre of mass, or a role nobody documented.

Every distinct STL of those kits is also the file trimesh writes of the same triangles, and its
manifest figures (volume, centre of mass, bounding box) are trimesh's to the last bit: partgen
writes and weighs its parts in numpy (``export.stl``) so that ``build`` need not import trimesh."""

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
        data = (dest / p["file"]).read_bytes()
        read = trimesh.load(dest / p["file"], file_type="stl", process=False)
        mesh = trimesh.Trimesh(read.vertices, read.faces, process=False)  # normals computed, not read
        assert trimesh.exchange.stl.export_stl(mesh) == data, p["file"]
        assert p["volume_mm3"] == round(float(mesh.volume), 4)
        assert p["centre_of_mass_mm"] == [round(float(c), 4) for c in mesh.center_mass]
        assert p["bbox_mm"] == [round(float(x), 4) for x in mesh.extents]
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
