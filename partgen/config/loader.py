"""Read a design YAML and its printer profile into validated models; every failure is a ConfigError
naming the file, the key path and the problem."""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import yaml
from pydantic import BaseModel, ValidationError

from ..errors import ConfigError
from .schema import BennettDesign, Design, Printer, WristDesign

__all__ = ["LoadedDesign", "load_design", "read_yaml", "key_path"]

M = TypeVar("M", bound=BaseModel)


@dataclass(frozen=True)
class LoadedDesign:
    path: Path
    design: Design | WristDesign | BennettDesign
    printer_path: Path
    printer: Printer


def read_yaml(path: Path) -> dict:
    """The YAML mapping in ``path``; ConfigError for a missing file, bad syntax or a non-mapping."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ConfigError(path, "", "no such file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(path, "", f"cannot read: {e}") from None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        problem = getattr(e, "problem", None) or str(e).splitlines()[0]
        raise ConfigError(path, "", f"invalid YAML{where}: {problem}") from None
    if data is None:
        raise ConfigError(path, "", "the file is empty: expected a mapping of design keys")
    if not isinstance(data, dict):
        raise ConfigError(path, "", f"expected a mapping of keys at the top level, got a {type(data).__name__}")
    return data


def key_path(loc: tuple, data: Any) -> str:
    """``('teeth', 0, 'D')`` → ``teeth[0].D``, walking ``data`` so pydantic's union tags are dropped."""
    out, node = "", data
    for item in loc:
        if isinstance(node, dict) and item in node:
            out += f".{item}" if out else str(item)
            node = node[item]
        elif isinstance(node, list) and isinstance(item, int) and 0 <= item < len(node):
            out += f"[{item}]"
            node = node[item]
        elif isinstance(item, str) and not any(c in item for c in "[]()'") and node is not None and isinstance(node, dict):
            out += f".{item}" if out else item  # a missing key
            node = None
    return out


def _describe(err: dict, data: Any, errors: list[dict]) -> tuple[str, str]:
    path = key_path(tuple(err["loc"]), data)
    msg = err["msg"]
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, "):]
    if err["type"] == "missing":
        return path, "required key is missing"
    if err["type"] == "extra_forbidden":
        # a misspelt key: suggest the missing sibling it was probably meant to be
        parent = tuple(err["loc"][:-1])
        missing = [str(e["loc"][-1]) for e in errors if e["type"] == "missing" and tuple(e["loc"][:-1]) == parent]
        close = difflib.get_close_matches(str(err["loc"][-1]), missing, n=1, cutoff=0.6)
        hint = f"; did you mean '{close[0]}'?" if close else " (not part of the schema; check its spelling)"
        return path, "unknown key" + hint
    got = err.get("input")
    if not isinstance(got, (dict, list)):
        msg += f", got {got!r}"
    return path, msg


def _rank(err: dict, data: Any) -> tuple:
    """Unknown keys first (a typo explains the 'missing' it causes), then the deepest key."""
    return (err["type"] != "extra_forbidden", -key_path(tuple(err["loc"]), data).count(".")
            - key_path(tuple(err["loc"]), data).count("["))


def validate(model: type[M], data: dict, path: Path) -> M:
    """``model`` from ``data``; the most telling error becomes a ConfigError with its key path."""
    try:
        return model.model_validate(data)
    except ValidationError as e:
        errors = sorted(e.errors(), key=lambda er: _rank(er, data))
        key, problem = _describe(errors[0], data, errors)
        # other problems, not counting the alternatives of a union the first error lies inside
        others = {key_path(tuple(er["loc"]), data) for er in errors} - {key}
        others = {o for o in others if not (key.startswith(o) and key[len(o):len(o) + 1] in ".[")}
        if errors[0]["type"] == "extra_forbidden" and "did you mean" in problem:
            others -= {key.rsplit(".", 1)[0] + "." + problem.split("'")[1]}
        if others:
            problem += f" (and {len(others)} more problem{'s' if len(others) > 1 else ''})"
        raise ConfigError(path, key, problem) from None


def load_design(path: str | Path) -> LoadedDesign:
    """Design and printer profile of a design file; the printer path is relative to the design."""
    path = Path(path)
    data = read_yaml(path)
    kinds = {"wrist": WristDesign, "bennett_butterfly": BennettDesign}
    design = validate(kinds.get(data.get("kind"), Design), data, path)
    printer_path = (path.parent / design.printer).resolve()
    if not printer_path.is_file():
        raise ConfigError(path, "printer", f"no printer profile at {design.printer!r} (looked for {printer_path})")
    printer = validate(Printer, read_yaml(printer_path), printer_path)
    return LoadedDesign(path, design, printer_path, printer)
