"""Every kind of mechanism partgen builds, each a vertical slice in its own folder (schema, resolver,
kit assembly, checks, trace, report sections, CLI tables) behind the ``core.protocol.Mechanism``
protocol. The registry is this explicit list: a new mechanism is one folder and one name here.
Mechanism folders never import each other."""

from __future__ import annotations

from importlib import import_module
from pathlib import Path

from ..config.loader import LoadedDesign
from ..config.loader import load_design as _load_design
from ..core.protocol import Mechanism

__all__ = ["REGISTRY", "get", "kinds", "load_design"]

KINDS = (
    "gear_chain",
    "wrist",
    "bennett_butterfly",
    "gear_pair",
    "gear_train",
    "crossed_helical",
    "bevel",
)

REGISTRY: dict[str, Mechanism] = {kind: import_module(f"{__name__}.{kind}").MECHANISM for kind in KINDS}


def get(kind: str) -> Mechanism:
    """The mechanism of ``kind`` (KeyError for an unknown kind: the loader refuses those first)."""
    return REGISTRY[kind]


def kinds() -> list[str]:
    return list(REGISTRY)


def load_design(path: str | Path, over=None) -> LoadedDesign:
    """A design file validated against its kind's schema, with the command line's ``over``rides
    (see ``config.loader.load_design``)."""
    if over is None:
        return _load_design(path, {k: m.schema for k, m in REGISTRY.items()})
    return _load_design(path, {k: m.schema for k, m in REGISTRY.items()}, over)
