"""The mechanism registry: every kind is one explicit entry holding the whole protocol, the loader
names the kinds from it, and a misspelt kind is one error on ``kind``."""

import inspect
from pathlib import Path

import pytest
import yaml
from helpers import modified

from partgen.cli.main import main
from partgen.core.protocol import OPTIONAL_HOOKS, Mechanism, OptionalHooks
from partgen.errors import ConfigError
from partgen.mechanisms import REGISTRY, load_design

ROOT = Path(__file__).resolve().parents[2]


def shape(fn) -> list[tuple[str, object, object]]:
    """A callable's parameters as the callers see them (self left out): name, kind, default. The
    annotations may be narrower in a mechanism (its own spec and kit types)."""
    ps = list(inspect.signature(fn).parameters.values())
    if ps and ps[0].name == "self":
        ps = ps[1:]
    return [(p.name, p.kind, p.default) for p in ps]


def protocol_members(proto) -> dict[str, object]:
    """name -> the protocol's function, or "attribute" for a declared attribute."""
    out = {n: v for n, v in vars(proto).items() if inspect.isfunction(v) and not n.startswith("_")}
    out.update({n: "attribute" for n in getattr(proto, "__annotations__", {}) if not n.startswith("_")})
    return out


REQUIRED, OPTIONAL = protocol_members(Mechanism), protocol_members(OptionalHooks)


def drift(mech) -> list[str]:
    """What about ``mech`` differs from the protocol: a missing member, an extra public member, a
    method shaped otherwise (parameters, kinds, defaults), an attribute that is a method."""
    out = []
    public = {n for n in dir(mech) if not n.startswith("_")}
    for name, want in REQUIRED.items():
        if name not in public:
            out.append(f"missing {name}")
        elif want == "attribute":
            if callable(getattr(mech, name)) and name != "schema":
                out.append(f"{name} should be an attribute")
        elif not callable(getattr(mech, name)):
            out.append(f"{name} should be a method")
        elif shape(getattr(mech, name)) != shape(want):
            out.append(f"{name}{inspect.signature(getattr(mech, name))} is not the protocol's {inspect.signature(want)}")
    for name in sorted(public - set(REQUIRED)):
        if name not in OPTIONAL:
            out.append(f"extra {name}: not in core.protocol (declare it, or make it private)")
        elif shape(getattr(mech, name)) != shape(OPTIONAL[name]):
            out.append(f"{name}{inspect.signature(getattr(mech, name))} is not the hook's {inspect.signature(OPTIONAL[name])}")
    return out


def test_every_shipped_config_names_a_registered_kind():
    kinds = {yaml.safe_load(p.read_text()).get("kind") for p in (ROOT / "configs").glob("*.yaml")}
    assert kinds <= set(REGISTRY) and len(kinds) >= 3


@pytest.mark.parametrize("kind", list(REGISTRY))
def test_each_mechanism_is_exactly_the_protocol(kind):
    """Every member the protocol declares, shaped as it declares it, and nothing public besides the
    optional hooks it declares too (issue 26: the protocol is what is called)."""
    mech = REGISTRY[kind]
    assert mech.kind == kind
    assert not drift(mech), drift(mech)
    assert mech.schema.model_fields["kind"].annotation.__args__ == (kind,)
    assert set(OPTIONAL) == set(OPTIONAL_HOOKS)


def test_the_signature_test_catches_a_drift():
    """A mechanism with a member missing, one with an extra argument, an undeclared public member and
    a hook of another shape: each is named."""
    base = REGISTRY["gear_pair"]

    class Broken(type(base)):
        def check(self, spec, kit, samples=None, progress=None, extra=1):  # an argument the callers never pass
            return super().check(spec, kit, samples, progress)

        def shiny(self):  # public, undeclared
            return 1

        def tolerance_model(self, spec, kit, result):  # a hook shaped otherwise
            return None
    got = drift(Broken())
    assert any(d.startswith("check(") for d in got), got
    assert any(d.startswith("extra shiny") for d in got), got
    assert any(d.startswith("tolerance_model(") for d in got), got

    class Missing(type(base)):
        subtitle = None  # not a method any more
    assert any("subtitle should be a method" in d for d in drift(Missing())), drift(Missing())
    assert not drift(base)


def test_callers_use_only_declared_members():
    """pipeline, studies, the CLI and export call on a mechanism only what the protocol declares
    (its members, or the optional hooks by getattr): read from their source."""
    import re

    pkg = ROOT / "partgen"
    src = "\n".join(p.read_text() for p in [pkg / "pipeline.py", pkg / "studies.py", *sorted((pkg / "cli").glob("*.py")),
                                           *sorted((pkg / "export").glob("*.py"))])
    called = set(re.findall(r"\b(?:mech|mechanism|loaded\.mechanism)\.([a-z_]+)", src))
    called |= set(re.findall(r"getattr\((?:mech|mechanism|loaded\.mechanism), \"([a-z_]+)\"", src))
    assert called, "found no calls: the pattern no longer matches the callers"
    assert called <= set(REQUIRED) | set(OPTIONAL), called - set(REQUIRED) - set(OPTIONAL)


def test_a_misspelt_kind_is_one_error_on_kind(tmp_path, capsys):
    cfg = modified("bennett_butterfly", tmp_path, {"kind": "bennet_butterfly"}, name="typo.yaml")
    with pytest.raises(ConfigError) as e:
        load_design(cfg)
    assert e.value.key_path == "kind"
    msg = str(e.value)
    assert "did you mean 'bennett_butterfly'" in msg and all(k in msg for k in REGISTRY) and "more problem" not in msg
    assert main(["build", str(cfg), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ": kind: unknown mechanism 'bennet_butterfly'" in err[0]
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("config", ["butterfly_liu2017", "gear_train_reducer", "gear_train_planetary", "gear_train_rack"])
def test_kits_the_shared_checks_take_are_checked_kits(config):
    """What the shared checks read of a kit is declared (``core.protocol.CheckedKit``): every kit a
    mechanism hands them has it, with the settings, printer and face width its params must carry."""
    from partgen import pipeline
    from partgen.core.protocol import CheckedKit

    kit = pipeline.make_kit(pipeline.load(Path(__file__).resolve().parents[2] / "configs" / f"{config}.yaml"))
    assert isinstance(kit, CheckedKit)
    for name in ("checks", "printer", "face_width"):
        assert hasattr(kit.params, name), name
    from partgen.core.parts import Contact
    assert kit.contacts and all(isinstance(c, Contact) for c in kit.contacts)
    assert kit.part(kit.parts[0].name) is kit.parts[0]
