"""``gears.backlash_per_gear_mm: auto``: the least backlash with which a print of the kit jams
with probability at most ``tolerance.max_jam_probability`` on the design's printer.

The design is built and checked once at ``AUTO_PLAY_START_MM``; the mechanism's tolerance model of
that check (gears seated by their meshes, docs/tolerance.md) gives every margin, and each mesh's
backlash margin moves with the backlash by its ``per_backlash``; ``design.tolerance.least_play``
picks the least value on a 0.005 mm grid that meets the target on 20,000 fixed prints (seed 0).
The design is then loaded with that number in place of ``auto``: the kit, its pinned design.yaml
and every check see the number. One search per design per process, and the choice is remembered
between runs (``core.cache``: under the resolved design, the design and printer documents,
partgen's source and the libraries' versions, so a remembered choice is the one the search would
make now).
"""

from __future__ import annotations

import copy
import pickle
from dataclasses import replace
from pathlib import Path

from ..config.loader import LoadedDesign
from ..config.schema import AUTO_PLAY_START_MM
from ..core.cache import recall, remember
from ..core.protocol import tolerance_hook
from ..design.tolerance import PLAY_STEP_MM, least_play
from ..errors import ConfigError, DesignError

__all__ = ["KEY", "wants_auto", "resolve_auto"]

KEY = ("gears", "backlash_per_gear_mm")
_DONE: dict = {}


def wants_auto(raw: LoadedDesign) -> bool:
    data = raw.data if raw.data is not None else raw.document()
    node = data.get(KEY[0]) if isinstance(data, dict) else None
    return isinstance(node, dict) and node.get(KEY[1]) == "auto"


def _with(raw: LoadedDesign, value: float) -> LoadedDesign:
    data = copy.deepcopy(raw.data if raw.data is not None else raw.document())
    data[KEY[0]][KEY[1]] = value
    return replace(raw, data=data, design=type(raw.design).model_validate(data))


def _builds(raw: LoadedDesign, mech, value: float) -> str | None:
    """None when the design resolves with ``value``; else what stops it."""
    try:
        mech.resolve(_with(raw, round(value, 6)))
    except ConfigError as e:
        return f"{e.key_path}: {e.problem}" if getattr(e, "key_path", None) else str(e)
    return None


def resolve_auto(raw: LoadedDesign, mech) -> tuple[LoadedDesign, dict]:
    """(the design with the chosen number, the allocation: value, P(jam) it reaches, its interval,
    the target, the samples)."""
    key = (str(Path(raw.path).resolve()), raw.digest())  # the path too: a design may name files beside it
    if key in _DONE:
        value, alloc = _DONE[key]
        return _with(raw, value), alloc
    hook = tolerance_hook(mech)
    if hook is None:
        raise ConfigError(raw.path, ".".join(KEY), f"auto needs a tolerance model: a {mech.kind} design has none yet")
    start = _with(raw, AUTO_PLAY_START_MM)
    spec = mech.resolve(start)
    what = raw.digest().encode() + b"\0" + pickle.dumps(spec, protocol=5)
    known = recall("auto-play", what)
    if known is not None:
        _DONE[key] = (known["value"], known["allocation"])
        return _with(raw, known["value"]), known["allocation"]
    try:
        kit = mech.build(spec, None)
    except DesignError as e:
        raise ConfigError(raw.path, e.key_path, e.problem) from None
    result = mech.check(spec, kit, None, None)
    model = hook(spec, kit, result, kit.printer.xy_accuracy)
    target = raw.design.tolerance.max_jam_probability
    got = least_play(model, AUTO_PLAY_START_MM, target)
    limit = None
    if _builds(raw, mech, got["backlash_per_gear_mm"]) is not None:
        # thinner teeth break a rule the design is held to (tip width, ...): the most that builds
        lo, hi = 1, int(round(got["backlash_per_gear_mm"] / PLAY_STEP_MM)) - 1
        problem = _builds(raw, mech, got["backlash_per_gear_mm"])
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if _builds(raw, mech, mid * PLAY_STEP_MM) is None:
                lo = mid
            else:
                hi = mid - 1
        if _builds(raw, mech, lo * PLAY_STEP_MM) is not None:
            raise ConfigError(raw.path, ".".join(KEY), f"auto: no backlash from {PLAY_STEP_MM} mm builds: {problem}")
        limit = {"needed_mm": got["backlash_per_gear_mm"], "problem": problem}
        got = least_play(model, AUTO_PLAY_START_MM, target, most=round(lo * PLAY_STEP_MM, 6))
    value = got["backlash_per_gear_mm"]
    alloc = {"key": ".".join(KEY), **got, "accuracy_mm": kit.printer.xy_accuracy, "printer": kit.printer.name,
             "meshes": sum(m.what == "backlash" for m in model.margins), "limited_by": limit}
    _DONE[key] = (value, alloc)
    remember("auto-play", what, {"value": value, "allocation": alloc})
    return _with(raw, value), alloc
