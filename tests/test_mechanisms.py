"""The mechanism registry: every kind is one explicit entry holding the whole protocol, the loader
names the kinds from it, and a misspelt kind is one error on ``kind``."""

import inspect
from pathlib import Path

import pytest
import yaml

from partgen.cli.main import main
from partgen.core.protocol import Mechanism
from partgen.errors import ConfigError
from partgen.mechanisms import REGISTRY, load_design

ROOT = Path(__file__).resolve().parents[1]
PROTOCOL = [n for n, v in vars(Mechanism).items() if inspect.isfunction(v) and not n.startswith("_")]


def test_every_shipped_config_names_a_registered_kind():
    kinds = {yaml.safe_load(p.read_text()).get("kind") for p in (ROOT / "configs").glob("*.yaml")}
    assert kinds <= set(REGISTRY) and len(kinds) >= 3


@pytest.mark.parametrize("kind", list(REGISTRY))
def test_each_mechanism_holds_the_whole_protocol(kind):
    mech = REGISTRY[kind]
    assert mech.kind == kind
    missing = [n for n in PROTOCOL + ["bill_text", "check_text", "trace_text", "csv", "subtitle", "findings"]
               if not callable(getattr(mech, n, None))]
    assert not missing, missing
    assert mech.schema.model_fields["kind"].annotation.__args__ == (kind,)


def test_a_misspelt_kind_is_one_error_on_kind(tmp_path, capsys):
    d = yaml.safe_load((ROOT / "configs" / "bennett_butterfly.yaml").read_text())
    d["kind"] = "bennet_butterfly"
    cfg = tmp_path / "typo.yaml"
    cfg.write_text(yaml.safe_dump(d))
    with pytest.raises(ConfigError) as e:
        load_design(cfg)
    assert e.value.key_path == "kind"
    msg = str(e.value)
    assert "did you mean 'bennett_butterfly'" in msg and all(k in msg for k in REGISTRY) and "more problem" not in msg
    assert main(["build", str(cfg), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ": kind: unknown mechanism 'bennet_butterfly'" in err[0]
    assert not (tmp_path / "out").exists()
