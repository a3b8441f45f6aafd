"""What the command line changes in a design before it is validated: ``--set KEY=VALUE`` (a key path
and a YAML value, as if written in the file) and ``--printer NAME|FILE`` (the printer profile).

The design is validated with the overrides in place, by the same schema; an error on a key that a
``--set`` wrote says so. The kit folder's design.yaml records the values they resolved to."""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import ConfigError, OptionError
from .yamlio import parse_yaml

__all__ = ["Setting", "Overrides", "parse_set", "apply_sets", "blame", "NO_OVERRIDES"]

_SEGMENT = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d{1,6}\])*)")


class UsageError(OptionError):
    """A bad ``--set`` or ``--printer``: the CLI prints the subcommand's usage with it (exit 2)."""

    usage = True


class SetConfigError(ConfigError):
    """A design that a ``--set`` made invalid (the message names the --set)."""

    usage = True


@dataclass(frozen=True)
class Setting:
    """One ``--set``: the key path (``gears.module_mm``), its parts and the value as YAML reads it."""

    key: str
    steps: tuple  # str (a mapping key) or int (a list index)
    value: object
    text: str  # as given: KEY=VALUE


@dataclass(frozen=True)
class Overrides:
    sets: tuple[Setting, ...] = ()
    printer: str | None = None  # --printer NAME|FILE

    def __bool__(self) -> bool:
        return bool(self.sets) or self.printer is not None


NO_OVERRIDES = Overrides()


def parse_set(text: str) -> Setting:
    """``KEY=VALUE`` → a Setting; UsageError for a malformed key or value."""
    key, eq, value = text.partition("=")
    key = key.strip()
    if not eq or not key:
        raise UsageError("--set", text, "expected KEY=VALUE, a key path and a YAML value (gears.module_mm=1.5)")
    steps: list = []
    for part in key.split("."):
        m = _SEGMENT.fullmatch(part)
        if m is None:
            raise UsageError("--set", text, f"{key!r} is not a key path: names joined by '.', list items as [i] "
                             "(gears.module_mm, teeth[0].D)")
        steps.append(m[1])
        steps += [int(i) for i in re.findall(r"\[(\d+)\]", m[2])]
    try:
        parsed = parse_yaml(value, Path("--set"))
    except ConfigError as e:
        raise UsageError("--set", text, f"the value is not YAML: {e.problem}") from None
    return Setting(key, tuple(steps), parsed, text)


def apply_sets(data: dict, sets: tuple[Setting, ...], path: Path) -> dict:
    """A copy of the design ``data`` with every ``--set`` written in (a missing mapping on the way is
    made; a list item must exist). ConfigError (with usage) naming the --set otherwise."""
    data = copy.deepcopy(data)
    for s in sets:
        node = data
        for i, step in enumerate(s.steps):
            last = i == len(s.steps) - 1
            where = _path(s.steps[:i]) or "the design"
            if isinstance(step, int):
                if not isinstance(node, list):
                    raise SetConfigError(path, _path(s.steps[:i + 1]), f"{where} is not a list (from --set {s.text})")
                if not 0 <= step < len(node):
                    raise SetConfigError(path, _path(s.steps[:i + 1]), f"{where} has {len(node)} items "
                                         f"(0 to {len(node) - 1}) (from --set {s.text})")
            elif not isinstance(node, dict):
                raise SetConfigError(path, _path(s.steps[:i + 1]), f"{where} is not a mapping of keys "
                                     f"(from --set {s.text})")
            if last:
                node[step] = copy.deepcopy(s.value)
            else:
                if isinstance(step, str) and step not in node:
                    node[step] = [] if isinstance(s.steps[i + 1], int) else {}
                node = node[step]
    return data


def _path(steps) -> str:
    out = ""
    for s in steps:
        out += f"[{s}]" if isinstance(s, int) else (f".{s}" if out else s)
    return out


def blame(e: ConfigError, sets: tuple[Setting, ...]) -> ConfigError:
    """``e`` as a SetConfigError naming the --set that wrote its key (or a key inside it), if one did."""
    for s in reversed(sets):
        k, key = s.key, e.key_path
        inside = lambda a, b: a == b or a.startswith(b + ".") or a.startswith(b + "[")  # noqa: E731
        if inside(key, k) or (key and inside(k, key)):
            return SetConfigError(e.file, key, f"{e.problem} (from --set {s.text})")
    return e
