"""Every key a design file or a printer profile may hold says what it is: the docs' config reference
(scripts/docs_hooks.py) is generated from the pydantic schemas, so a field without a description is
a blank row a maker cannot read."""

from __future__ import annotations

import typing

import pytest
from pydantic import BaseModel

from partgen.config.schema import Printer
from partgen.config.schema import nested_models as models
from partgen.mechanisms import REGISTRY

SCHEMAS = {**{kind: mech.schema for kind, mech in REGISTRY.items()}, "printer": Printer}


def undescribed(model: type[BaseModel]) -> list[str]:
    """Fields of ``model`` and the models it holds whose description is missing or says nothing."""
    bad = []
    for m in models(model):
        for name, f in m.model_fields.items():
            words = (f.description or "").split()
            if len(words) < 2 or " ".join(words).strip(" .").lower() == name.replace("_", " "):
                bad.append(f"{m.__name__}.{name}")
    return bad


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_every_field_is_described(kind):
    schema = SCHEMAS[kind]
    assert len(models(schema)) >= 2  # the walk reaches nested models (Material at least)
    assert undescribed(schema) == []


def test_the_walk_finds_nested_models_and_blank_fields():
    """The check sees a blank field in a model nested in a list inside a union."""
    from partgen.config.schema import Strict

    class Inner(Strict):
        x_mm: float

    class Outer(Strict):
        a: int = 1
        """A described field."""
        inner: list[Inner] | None = None
        """Nested rows."""

    assert Inner in models(Outer)
    assert undescribed(Outer) == ["Inner.x_mm"]


def test_docstrings_are_descriptions_and_field_descriptions_win():
    """``use_attribute_docstrings`` on the shared base: a docstring under a field is its description,
    and an explicit ``Field(description=...)`` is kept."""
    assert "reference pitch diameter" in REGISTRY["gear_pair"].schema.model_fields["gears"].annotation \
        .model_fields["module_mm"].description
    assert Printer.model_fields["nozzle_diameter_mm"].description == "the nozzle's bore"
