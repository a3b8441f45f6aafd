"""Assembly steps (export/assembly.py): a mechanism's own steps name only the kit's parts and use each
once; a mechanism without them gets the generic order (the base first, then kit order)."""

from __future__ import annotations

from pathlib import Path

import pytest

from types import SimpleNamespace

from partgen import pipeline
from partgen.core.parts import Part
from partgen.export.assembly import assembly_section, default_steps, steps_of

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def pair():
    loaded = pipeline.load(ROOT / "configs" / "gear_pair.yaml")
    return loaded, pipeline.make_kit(loaded)


def test_a_mechanism_without_steps_gets_the_generic_order(pair):
    loaded, kit = pair

    class Bare:  # the protocol's required parts only: no assembly_steps
        pass

    steps = steps_of(Bare(), loaded.spec, kit)
    assert steps == default_steps(kit)
    assert steps[0] == ("Stand the base on the table.", ("base",))
    assert [names for _, names in steps[1:]] == [("gear1",), ("gear2",)]


def test_the_gear_pair_steps_and_a_bad_step_is_refused(pair):
    loaded, kit = pair
    steps = steps_of(loaded.mechanism, loaded.spec, kit)
    assert [names for _, names in steps] == [("base",), ("gear1",), ("gear2",)]
    assert f"{loaded.spec.gear2.teeth} teeth" in steps[2][0]

    class Wrong:
        def assembly_steps(self, spec, kit):
            return [("fit the flux capacitor", ("capacitor",))]

    with pytest.raises(ValueError, match="capacitor"):
        steps_of(Wrong(), loaded.spec, kit)


def test_the_section_lists_steps_in_order_with_pictures():
    title, body = assembly_section([("one", ("a", "b")), ("two", ("c",))], {"a": b"\x89PNG", "c": b"\x89PNG"})
    assert title == "Assembly" and body.index("one") < body.index("two")
    assert body.count("<img") == 2 and 'alt="a"' in body and 'alt="b"' not in body and "<figcaption>b</figcaption>" in body


def test_every_part_of_the_belt_chain_is_in_one_step(kit_of):
    built = kit_of("butterfly_belt")
    steps = steps_of(built.loaded.mechanism, built.loaded.spec, built.kit)
    used = [n for _, names in steps for n in names]
    assert sorted(used) == sorted(p.name for p in built.kit.parts)
    assert any("belt1" in names and "T1" in names for _, names in steps)


def test_the_bennett_steps_pin_every_joint_once_after_its_links():
    """On the Bennett kit's part names (12 links, the base, a pin per joint, some fills): each link and
    each joint's pin in one step, a pin never before the links it joins."""
    from partgen.design.bennett_butterfly import JOINTS
    from partgen.mechanisms import REGISTRY

    names = ["base"] + [f"link{i:02d}" for i in range(1, 13)] + [f"pin_{j}" for j in JOINTS] + ["fill_link02"]
    kit = SimpleNamespace(parts=tuple(Part(n, "x", None, printed=not n.startswith(("pin", "fill"))) for n in names))
    steps = steps_of(REGISTRY["bennett_butterfly"], None, kit)
    used = [n for _, ns in steps for n in ns]
    assert sorted(used) == sorted(names)
    at = {n: k for k, (_, ns) in enumerate(steps) for n in ns}
    assert at["fill_link02"] < at["base"] < at["link01"]
    for j, ((a, b), _, _) in JOINTS.items():
        assert at[f"pin_{j}"] >= max(at[f"link{a:02d}"], at[f"link{b:02d}"]), j


@pytest.mark.parametrize("cfg", ["gear_train_reducer.yaml", "gear_train_herringbone.yaml", "gear_train_planetary.yaml",
                                 "gear_train_rack.yaml"])
def test_gear_train_steps_go_from_the_bottom_plate_up(cfg):
    """Every part once; frame_bottom first, frame_top (where there is one) last; each shaft no later
    than the gears it carries, a shaft's bought screw and nut with it; shafts in the train's order."""
    loaded = pipeline.load(Path(__file__).resolve().parents[2] / "configs" / cfg)
    kit = pipeline.make_kit(loaded)
    steps = steps_of(loaded.mechanism, loaded.spec, kit)
    order = [n for _, names in steps for n in names]
    assert sorted(order) == sorted(p.name for p in kit.parts)
    assert order[0] == "frame_bottom"
    if "frame_top" in order:
        assert order[-1] == "frame_top"
    at = {n: i for i, n in enumerate(order)}
    shafts = [p.name for p in kit.parts if p.name.startswith("shaft")]
    assert [at[s] for s in shafts] == sorted(at[s] for s in shafts)
    for _, names in steps:
        gears = [n for n in names if n.startswith(("gears", "sun", "pinion"))]
        if gears:
            assert any(n.startswith("shaft") for n in names), names  # a gear goes on with its shaft
    assert all("Fit the bought parts" not in text for text, _ in steps)
