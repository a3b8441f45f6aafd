"""Helpers the test files share (``from helpers import modified``; tests/ is on sys.path, as for
tests/viewer_probe.py)."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"

_KEY = re.compile(r"[^.\[\]]+(\[-?\d+\])*(\.[^.\[\]]+(\[-?\d+\])*)*")
_STEP = re.compile(r"([^.\[\]]+)|\[(-?\d+)\]")


def design_path(design: str | Path) -> Path:
    """A design by name: a shipped config's name (``"gear_pair"``: configs/gear_pair.yaml), a path
    from the project's root (``"tests/designs/bennett_fixed.yaml"``) or any path."""
    p = Path(design)
    if p.is_absolute():
        return p
    if p.suffix in (".yaml", ".yml"):
        return ROOT / p
    return CONFIGS / f"{design}.yaml"


def _steps(key: str) -> list[str | int]:
    """``"teeth[2].D"`` -> ``["teeth", 2, "D"]``."""
    if not _KEY.fullmatch(key):
        raise ValueError(f"not a key path: {key!r}")
    return [m[1] if m[1] is not None else int(m[2]) for m in _STEP.finditer(key)]


def _key(node, step):
    """A step as ``node`` holds it: a number written as a mapping's key in the YAML (``cos: {2: 4.0}``)
    is that number (``curve.polar.cos.2``)."""
    if isinstance(node, dict) and isinstance(step, str) and step not in node and re.fullmatch(r"-?\d+", step) \
            and (int(step) in node or any(isinstance(k, int) for k in node)):
        return int(step)
    return step


def _parent(doc, steps: list, make: bool):
    node = doc
    for step, nxt in zip(steps, steps[1:]):
        step = _key(node, step)
        if isinstance(step, str) and make and not isinstance(node.get(step), (dict, list)):
            node[step] = {} if isinstance(nxt, str) else []
        node = node[step]
    return node


def _data_files(doc, base: Path) -> set[Path]:
    """The files ``doc`` names by a path relative to its folder ``base`` (a drawing, a printer profile)."""
    found: set[Path] = set()
    stack = [doc]
    while stack:
        node = stack.pop()
        if isinstance(node, dict):
            stack.extend(node.values())
        elif isinstance(node, list):
            stack.extend(node)
        elif isinstance(node, str) and node and len(node) < 300 and "\0" not in node:
            rel = Path(node)
            if not rel.is_absolute() and ".." not in rel.parts and (base / rel).is_file():
                found.add(rel)
    return found


def modified(design: str | Path, tmp_path: Path, changes: dict | None = None, drop=(), name: str | None = None) -> Path:
    """A copy of ``design`` (see ``design_path``) with ``changes`` made, written as ``tmp_path/name``
    (default: the design's file name); returns its path.

    ``drop``: key paths removed first; then ``changes``: key path -> value, the key paths partgen's
    messages give (``"gears.backlash_per_gear_mm"``, ``"teeth[2].D"``, ``"name"``; a whole section:
    ``"planetary"``; ``"curve.polar.sin.7"`` for a key the YAML writes as a number), a mapping
    missing on the way made.
    The files the design names relative to its folder (``curve.points: drawings/star.csv``, a
    printer profile) are copied beside the copy, so it builds as the original does. Comments and the
    original layout are not kept (YAML load and dump, keys in their order)."""
    src = design_path(design)
    doc = yaml.safe_load(src.read_text(encoding="utf-8"))
    tmp_path.mkdir(parents=True, exist_ok=True)
    for rel in _data_files(doc, src.parent):
        if not (tmp_path / rel).exists():
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src.parent / rel, tmp_path / rel)
    for key in drop:
        steps = _steps(key)
        parent = _parent(doc, steps, make=False)
        del parent[_key(parent, steps[-1])]
    for key, value in (changes or {}).items():
        steps = _steps(key)
        parent = _parent(doc, steps, make=True)
        parent[_key(parent, steps[-1])] = value
    out = tmp_path / (name or src.name)
    out.write_text(yaml.safe_dump(doc, sort_keys=False, allow_unicode=True), encoding="utf-8")
    return out
