"""``auto`` play: the least backlash and running clearance with which a print of the kit jams with
probability at most ``tolerance.max_jam_probability`` on the design's printer.

The keys a kind accepts ``auto`` on are its schema's ``AUTO_PLAY`` (dotted key -> role; a kind that
names none: ``gears.backlash_per_gear_mm`` as a backlash). Two roles:

* ``backlash``: each gear thinned at its reference pitch circle; a mesh's backlash margin moves by
  its ``per_backlash``; grid ``PLAY_STEP_MM`` (0.005 mm) from one step to ``PLAY_MAX_MM``; built at
  ``AUTO_PLAY_START_MM``.
* ``running``: a diametral running clearance; it moves every margin as every running bore printed
  that much larger does (``design.allocate.hole_slope``: the fit's radial gap by half of it, and the
  meshes the bores' play is credited to); grid ``RUNNING_STEP_MM`` (0.01 mm diametral) from one
  step to ``RUNNING_MAX_MM``; built at ``AUTO_RUNNING_START_MM``.
* ``radial``: a radial clearance (a kind's sockets over its domes): ``running`` in radial mm, at
  half its grid, start and most. A radial clearance Δ larger is each cavity it sizes printed 2Δ
  larger, as a diameter (``design.allocate.radial_slope``: twice the cavities' coefficients).

The design is built and checked once with every ``auto`` key at its start value; the mechanism's
tolerance model of that check (gears seated by their meshes, docs/tolerance.md) gives every margin
and each knob's slopes; ``design.allocate.least_allocation`` picks the values on 20,000 fixed prints
(seed 0): one knob by bisection, two by the staircase of least pairs, the least total play (the sum
of every mesh's backlash and every fit's radial gap the values open) with ties to the smaller value
of the earlier key. Then, where the kind takes a value per gear and per joint (its schema's
``PER_UNIT_PLAY``), each gear's backlash and each running fit's clearance are allocated on their own
from the uniform choice (``design.allocate.allocate_units``: the least total play with a model
probability of a jam no more than the uniform choice's, seated and in the worst case; ``_per_unit``), and the allocation is adopted when it saves more than one grid
step of the coarsest key over the whole kit: those keys become mappings ``{default: the uniform
value, <gear or joint>: its own}``. The design is then loaded with those numbers in place of
``auto``: the kit, its pinned design.yaml and every check see the numbers. A value that does not build (thinner teeth than
a rule allows, a bore that leaves no wall) caps its knob at the most that builds, and the search runs
again. One search per design per process, and the choice is remembered between runs
(``core.cache``: under the resolved design at the start values, the design and printer documents,
partgen's source and the libraries' versions, so a remembered choice is the one the search would
make now; the allocation is kept as JSON, so a remembered one reads exactly as a new one).
Within a search each design is resolved once, and the kit built and checked of the choice (when
no per-unit allocation changed it) is handed to ``pipeline.make_kit`` once (``searched_kit``), so
``build`` does not build that kit a second time.
"""

from __future__ import annotations

import copy
import json
import math
import pickle
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..config.loader import LoadedDesign
from ..config.schema import AUTO_PLAY_START_MM
from ..core.cache import recall, remember
from ..core.quantise import quantise
from ..core.protocol import tolerance_hook
from ..design.allocate import (Knob, Unit, _draws, allocate_units, gear_slopes, hole_slope, joint_slopes,
                               least_allocation, play_weight, radial_slope)
from ..design.tolerance import AUTO_SAMPLES, PLAY_MAX_MM, PLAY_STEP_MM
from ..errors import ConfigError, DesignError

__all__ = ["KEY", "ROLES", "auto_keys", "wants_auto", "at_start", "resolve_auto", "AUTO_RUNNING_START_MM",
           "RUNNING_STEP_MM", "RUNNING_MAX_MM"]

KEY = ("gears", "backlash_per_gear_mm")
AUTO_RUNNING_START_MM = 0.3  # a running clearance: auto is built and checked at this value first
RUNNING_STEP_MM = 0.01  # diametral (0.005 mm radial)
RUNNING_MAX_MM = 1.0

ROLES = {  # role -> (label, start, step, most)
    "backlash": ("backlash per gear", AUTO_PLAY_START_MM, PLAY_STEP_MM, PLAY_MAX_MM),
    "running": ("running clearance, diametral", AUTO_RUNNING_START_MM, RUNNING_STEP_MM, RUNNING_MAX_MM),
    "radial": ("clearance, radial", AUTO_RUNNING_START_MM / 2, RUNNING_STEP_MM / 2, RUNNING_MAX_MM / 2),
}
_DONE: dict = {}
VERIFY_ROUNDS = 3  # builds of the chosen values checked on their own kit's model, at most
HELD_OUT = 7  # the chunk index of other prints an allocation's jams are reported on (the choice: chunk 0)


def _data(raw: LoadedDesign) -> dict:
    return raw.data if raw.data is not None else raw.document()


def _get(data, key: str):
    node = data
    for part in key.split("."):
        if not isinstance(node, dict):
            return None
        node = node.get(part)
    return node


def auto_keys(raw: LoadedDesign) -> dict[str, str]:
    """{dotted key: role} of the keys the design sets to ``auto`` (in the schema's order)."""
    declared = getattr(type(raw.design), "AUTO_PLAY", None) or {".".join(KEY): "backlash"}
    data = _data(raw)
    return {k: role for k, role in declared.items() if _get(data, k) == "auto"}


def wants_auto(raw: LoadedDesign) -> bool:
    return bool(auto_keys(raw))


def _with(raw: LoadedDesign, values: dict) -> LoadedDesign:
    """The design with each key set to its number, or to its mapping {default: mm, <name>: mm}."""
    data = copy.deepcopy(_data(raw))
    for key, value in values.items():
        *path, last = key.split(".")
        node = data
        for part in path:
            node = node.setdefault(part, {})
        node[last] = ({k: round(float(v), 6) for k, v in value.items()} if isinstance(value, dict)
                      else round(float(value), 6))
    return replace(raw, data=data, design=type(raw.design).model_validate(data))


def at_start(raw: LoadedDesign) -> LoadedDesign:
    """The design with every ``auto`` play key at its start value (what the search builds)."""
    keys = auto_keys(raw)
    return _with(raw, {k: ROLES[r][1] for k, r in keys.items()}) if keys else raw


def _spec(raw: LoadedDesign, mech, values: dict, memo: dict):
    """``mech.resolve`` of the design with ``values`` (``_with``), each design once: ``memo`` is one
    search's own (the design's digest -> its resolved design; the search's path is one)."""
    at = _with(raw, values)
    d = at.digest()
    if d not in memo:
        memo[d] = mech.resolve(at)
    return memo[d]


def _builds(raw: LoadedDesign, mech, values: dict, memo: dict) -> str | None:
    """None when the design resolves with ``values``; else what stops it."""
    try:
        _spec(raw, mech, values, memo)
    except ConfigError as e:
        return f"{e.key_path}: {e.problem}" if getattr(e, "key_path", None) else str(e)
    return None


def _slope(role: str, model) -> np.ndarray:
    if role == "backlash":
        return np.array([m.per_backlash for m in model.margins], dtype=float)
    if role == "radial":
        return radial_slope(model)
    return hole_slope(model)


def resolve_auto(raw: LoadedDesign, mech, start_spec=None) -> tuple[LoadedDesign, dict]:
    """(the design with the chosen numbers, the allocation: each key's value, the P(jam) it reaches,
    its interval, the target, the samples, what one more step of each would buy). ``start_spec``:
    ``mech.resolve(at_start(raw))`` when the caller has it already."""
    key = (str(Path(raw.path).resolve()), raw.digest())  # the path too: a design may name files beside it
    if key in _DONE:
        values, alloc = _DONE[key]
        return _with(raw, values), alloc
    keys = auto_keys(raw)
    hook = tolerance_hook(mech)
    if hook is None:
        raise ConfigError(raw.path, next(iter(keys)), f"auto needs a tolerance model: a {mech.kind} design has none yet")
    start = at_start(raw)
    spec = mech.resolve(start) if start_spec is None else start_spec
    specs = {start.digest(): spec}  # this search's resolved designs by digest (``_spec``)
    what = raw.digest().encode() + b"\0" + pickle.dumps(spec, protocol=5)
    known = recall("auto-play", what)
    if known is not None:
        _DONE[key] = (known["values"], known["allocation"])
        return _with(raw, known["values"]), known["allocation"]
    try:
        kit = mech.build(spec, None)
        mech.refuse(spec, kit)  # a part `build` would not write (empty, larger than the printer): before the check
    except DesignError as e:
        raise ConfigError(raw.path, e.key_path, e.problem) from None
    result = mech.check(spec, kit, None, None)
    as_checked = {id(kit): (kit, copy.deepcopy(result))}  # each kit's check as it came (for searched_result)
    model = hook(spec, kit, result, kit.printer.xy_accuracy)
    tol = getattr(raw.design, "tolerance", None)
    target = tol.max_jam_probability if tol is not None else 0.01

    built_at = {k: ROLES[r][1] for k, r in keys.items()}  # the values the model's kit was built with
    least: dict = {}  # grid index each key may not go below (a re-search only raises)

    def knobs(most: dict) -> list[Knob]:
        out = []
        for k, role in keys.items():
            label, s0, step, top = ROLES[role]
            out.append(Knob(k, label, built_at[k], _slope(role, model), step, least.get(k, 1),
                            most.get(k, int(round(top / step)))))
        return out

    most: dict = {}
    limits: dict = {}
    starts = {k: ROLES[r][1] for k, r in keys.items()}
    got = least_allocation(model, knobs(most), target, AUTO_SAMPLES)
    for k, role in keys.items():  # a value that does not build caps its knob at the most that does
        step = ROLES[role][2]
        problem = _builds(raw, mech, {**starts, k: got["values"][k]}, specs)
        if problem is None:
            continue
        lo, hi = 1, int(round(got["values"][k] / step)) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if _builds(raw, mech, {**starts, k: mid * step}, specs) is None:
                lo = mid
            else:
                hi = mid - 1
        if _builds(raw, mech, {**starts, k: lo * step}, specs) is not None:
            raise ConfigError(raw.path, k, f"auto: no value from {step:g} mm builds: {problem}")
        limits[k] = {"needed_mm": got["values"][k], "problem": problem}
        most[k] = lo
        got = least_allocation(model, knobs(most), target, AUTO_SAMPLES)
    # the choice verified on the kit it builds: that kit's own model (its check, its margins) on the
    # same prints; where it jams more than allowed, search again from it (only upwards)
    verified = []
    start_checked = (spec, kit, result, model)
    for n in range(VERIFY_ROUNDS):
        spec_v = _spec(raw, mech, got["values"], specs)
        if spec_v is start_checked[0]:  # the choice is the start values: its kit was built and checked above
            _, kit_v, result_v, model_v = start_checked
        else:
            try:
                kit_v = mech.build(spec_v, None)
            except DesignError as e:
                raise ConfigError(raw.path, e.key_path, e.problem) from None
            result_v = mech.check(spec_v, kit_v, None, None)
            as_checked[id(kit_v)] = (kit_v, copy.deepcopy(result_v))
            model_v = hook(spec_v, kit_v, result_v, kit_v.printer.xy_accuracy)
        own = int((_draws(model_v, AUTO_SAMPLES, got["seed"]) < 0.0).any(axis=1).sum())
        allowed = int(math.floor(target * AUTO_SAMPLES + 1e-9)) if got["reached"] else got["jams"]
        verified.append({"values": dict(got["values"]), "jams": own, "allowed": allowed})
        spec, kit, result, model = spec_v, kit_v, result_v, model_v
        built_at = dict(got["values"])
        if own <= allowed or n == VERIFY_ROUNDS - 1:  # the last round's values stand, verified or not (it says)
            break
        least = {k: int(round(got["values"][k] / ROLES[r][2])) for k, r in keys.items()}
        got = least_allocation(model, knobs(most), target, AUTO_SAMPLES)
    values = got["values"]
    per_unit = _per_unit(raw, mech, model, keys, got, most,
                         lambda: hook(spec, kit, result, kit.printer.xy_accuracy, seated=False), built_at, specs)
    design_values = dict(values)
    if per_unit["adopted"]:
        for k, own in per_unit["own"].items():
            design_values[k] = {"default": values[k], **own}
    alloc = {"key": ", ".join(keys), **got, "accuracy_mm": kit.printer.xy_accuracy, "printer": kit.printer.name,
             "meshes": len({m.unit for m in model.margins if m.what.startswith("backlash")}),  # one unit: a heel and a toe margin
             "joints": sum(m.group == "joint" and m.what == "radial gap" for m in model.margins),
             "limited_by": limits or None, "credits": model.credits, "per_unit": per_unit, "verified": verified}
    if per_unit["adopted"]:  # the kit is built with the allocation: its figures are the headline
        alloc["uniform"] = {k: got[k] for k in ("jams", "probability", "ci95", "cost_mm")}
        alloc.update({k: per_unit[k] for k in ("jams", "probability", "ci95", "cost_mm", "units", "groups")})
    if ".".join(KEY) in values:  # the name the backlash alone had (tests, --json readers)
        alloc["backlash_per_gear_mm"] = values[".".join(KEY)]
    try:
        alloc = json.loads(json.dumps(alloc))  # as it is remembered: the same whether searched now or not
    except (TypeError, ValueError):
        pass  # not JSON: not remembered
    else:
        remember("auto-play", what, {"values": design_values, "allocation": alloc})
    _DONE[key] = (design_values, alloc)
    chosen = _with(raw, design_values)
    same = _spec(raw, mech, values, specs) is spec and not per_unit["adopted"]
    _hand_over(chosen, mech, specs.get(chosen.digest()), kit if same else None,
               as_checked[id(kit)][1] if same else None)
    return chosen, alloc


_HANDED: dict = {}  # at most one: (kind, path, digest) -> (resolved design, its kit still to hand over or None,
#                                  (its kit, that kit's check) or None) of the last search's choice


def _handed_key(raw: LoadedDesign, mech) -> tuple:
    return mech.kind, str(Path(raw.path).resolve()), raw.digest()


def _hand_over(chosen: LoadedDesign, mech, spec, kit, result=None) -> None:
    """Keep the chosen design's resolved design and, when the last verification round built exactly
    that design (no per-unit allocation adopted), its kit and its check, for ``searched_spec``,
    ``searched_kit`` and ``searched_check``."""
    _HANDED.clear()
    if spec is not None:
        checked = (kit, result) if kit is not None and result is not None else None
        _HANDED[_handed_key(chosen, mech)] = (spec, kit, checked)


def searched_spec(raw: LoadedDesign, mech):
    """The resolved design the last search made of its choice when ``raw`` is that choice (the design
    ``resolve_auto`` returned: same kind, path and digest), else None. ``mech.resolve`` is a pure
    function of the design file's path and document and the printer's: it is what ``mech.resolve(raw)``
    returns now."""
    got = _HANDED.get(_handed_key(raw, mech))
    return got[0] if got is not None else None


def searched_kit(raw: LoadedDesign, mech, spec):
    """The kit the last search built and checked of its choice, handed over once (then forgotten), when
    ``raw`` is that choice and ``spec`` the very resolved design ``searched_spec`` gave; else None. It
    is the kit ``mech.build(spec)`` builds now: the same resolved design (same digest and path, the
    same object), the same code in the same process, and nothing but ``mech.check`` has read it (a
    check reads a kit; it does not change it)."""
    key = _handed_key(raw, mech)
    got = _HANDED.get(key)
    if got is None or got[0] is not spec or got[1] is None:
        return None
    _HANDED[key] = (got[0], None, got[2])
    return got[1]


def searched_check(raw: LoadedDesign, mech, kit):
    """A copy of the check (``mech.check(spec, kit, None, None)``: the design's own samples, as it came)
    the last search made of its choice's kit, when ``raw`` is that choice and ``kit`` that very kit
    object (``searched_kit``'s); else None. It is the check that call makes now: the same resolved
    design, the same kit, the same code."""
    got = _HANDED.get(_handed_key(raw, mech))
    if got is None or got[2] is None or got[2][0] is not kit:
        return None
    return copy.deepcopy(got[2][1])


def _units(model, keys: dict, got: dict, most: dict, built_at: dict) -> tuple[list[Unit], list[int]] | str:
    """(each gear's and each running fit's unit, the uniform choice's grid index of each) of a
    model (its kit built with ``built_at``: key -> mm), or what stops the split."""
    units, start = [], []
    for k, role in keys.items():
        label, _, step, top = ROLES[role]
        s0 = built_at[k]
        slopes = gear_slopes(model) if role == "backlash" else joint_slopes(model)
        if not slopes or not np.allclose(sum(slopes.values()), _slope(role, model), atol=1e-12):
            return f"{k}: the model's margins do not split into one per {'gear' if role == 'backlash' else 'joint'}"
        i0 = int(round(got["values"][k] / step))
        for name, sl in slopes.items():
            units.append(Unit(k, name, s0, sl, step, 1, most.get(k, int(round(top / step)))))
            start.append(i0)
    return units, start


def _per_unit(raw: LoadedDesign, mech, model, keys: dict, got: dict, most: dict, worst_model, built_at: dict,
              specs: dict) -> dict:
    """Each gear its own backlash and each running fit its own clearance, from the uniform choice
    ``got`` (``design.allocate.allocate_units``, on the same prints and grids, each unit at most its
    key's most), with a probability of a jam (each margin's exact normal tail, summed) no more than
    at the uniform values: play is moved between the units by the model itself, not by the luck of
    any prints; adopted when it saves more play than one grid step of the coarsest key over the
    whole kit (the uniform choice's own resolution), meets the target on the same 20,000 prints as
    the uniform choice, and builds without a warning the uniform kit has not. The result says why not
    when it is not.

    The worst case is held too (``worst_model()``: the same check's model with no bore play
    credited, every gear centred): the allocation may not raise its probability above the uniform
    choice's (``allocate_units``' guard), so a kit that leans on its gears being seated never gets
    worse than the uniform kit when they are not."""
    per = getattr(type(raw.design), "PER_UNIT_PLAY", frozenset())
    out = {"adopted": False, "why": None, "threshold": "more than one grid step of the coarsest key over the kit"}
    if not per or not set(keys) <= set(per):
        out["why"] = f"a {mech.kind} design takes one value per key"
        return out
    split = _units(model, keys, got, most, built_at)
    if isinstance(split, str):
        out["why"] = split
        return out
    units, start = split
    worst = worst_model()
    wsplit = _units(worst, keys, got, most, built_at)
    if isinstance(wsplit, str) or [(u.key, u.name) for u in wsplit[0]] != [(u.key, u.name) for u in units]:
        out["why"] = "the worst case's model does not split into the same gears and joints: one value per key"
        return out
    res = allocate_units(model, units, start, got["samples"], got["seed"], guard=(worst, wsplit[0]))
    uniform = sum(play_weight(model, u.slope) * u.value(i) for u, i in zip(units, start))
    saving = uniform - res["cost_mm"]
    need = max(got["weights"][k] * ROLES[r][2] for k, r in keys.items())
    own = {k: {u.name: v for u, v in zip(units, res["values"]) if u.key == k and v != got["values"][k]} for k in keys}
    out.update({"analytic": res["analytic"], "own": {k: o for k, o in own.items() if o}, "uniform_cost_mm": round(uniform, 6),
                "saving_mm": round(max(saving, 0.0), 6),
                "saving_pct": round(100 * max(saving, 0.0) / uniform, 3) if uniform else 0.0,
                "threshold_mm": round(need, 6), "exchanges": res["exchanges"],
                **{k: res[k] for k in ("jams", "probability", "ci95", "cost_mm")}})
    jam = res["jam"]
    uidx = model.unit_index
    per_u = [(int(jam[:, uidx == u].any(axis=1).sum()), u) for u in range(len(model.units))]
    out["units"] = [{"unit": model.units[u], "group": model.margins[int(np.flatnonzero(uidx == u)[0])].group, "jams": n}
                    for n, u in sorted(per_u, key=lambda t: (-t[0], t[1])) if n][:5]
    out["values_by_unit"] = {u.key + ":" + u.name: v for u, v in zip(units, res["values"])}
    out["groups"] = {g: int(jam[:, [m.group == g for m in model.margins]].any(axis=1).sum())
                     for g in got["groups"]}
    if quantise(saving) <= quantise(need):
        g = res["guard"]
        out["why"] = (f"held to the uniform values' worst case (no bore play credited: P(jam) {100 * g['start']:.3g} % "
                      f"by the model) it saves {max(saving, 0.0):.3g} mm of {uniform:.3g} mm, not more than one grid "
                      f"step of the coarsest key over the kit ({need:.3g} mm): the uniform values are kept")
        return out
    # reported: the jams on prints neither choice was made on (another 20,000: seed, chunk HELD_OUT)
    held = _draws(model, got["samples"], got["seed"], HELD_OUT)
    S = np.array([u.slope for u in units])
    starts = np.array([u.start for u in units])

    def held_jams(vals) -> int:
        return int(((held + (np.asarray(vals) - starts) @ S) < 0.0).any(axis=1).sum())
    out["held_out"] = {"prints": got["samples"], "uniform_jams": held_jams([u.value(i) for u, i in zip(units, start)]),
                       "jams": held_jams(res["values"])}
    wdraws = _draws(worst, got["samples"], got["seed"])
    wS = np.array([u.slope for u in wsplit[0]])

    def worst_jams(vals) -> int:
        return int(((wdraws + (np.asarray(vals) - starts) @ wS) < 0.0).any(axis=1).sum())
    out["worst_case"] = {"prints": got["samples"], "seat": worst.credits,
                         "uniform_jams": worst_jams([u.value(i) for u, i in zip(units, start)]),
                         "jams": worst_jams(res["values"]), "analytic": res["guard"]}
    allowed = int(math.floor(got["target"] * got["samples"] + 1e-9)) if got["reached"] else got["jams"]
    if res["jams"] > allowed:
        out["why"] = (f"it jams {res['jams']} of the {got['samples']:,} prints, more than the target's {allowed}: "
                      "the uniform values are kept")
        return out
    design = {k: ({"default": got["values"][k], **own[k]} if own[k] else got["values"][k]) for k in keys}
    problem = _builds(raw, mech, design, specs)
    if problem is None:
        warn = lambda v: sum(f.severity == "warn" for f in mech.findings(_spec(raw, mech, v, specs)))  # noqa: E731
        if warn(design) > warn(got["values"]):
            problem = "a gear's own backlash breaks a rule the uniform kit meets (tip width)"
    if problem is not None:
        out["why"] = f"the allocation does not build ({problem}): the uniform values are kept"
        return out
    out["adopted"] = True
    return out
