"""Every kind of mechanism partgen builds, each a vertical slice in its own folder (schema, resolver,
kit assembly, checks, trace, report sections, CLI tables) behind the ``core.protocol.Mechanism``
protocol. The registry is this explicit list: a new mechanism is one folder and one name here.
Mechanism folders never import each other."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
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

class _Registry(Mapping):
    """kind -> its ``Mechanism``, in the order of ``KINDS``; a kind's folder is imported the first
    time it is asked for (a command that builds one kind imports only that one)."""

    def __init__(self, kinds: tuple[str, ...], attr: str):
        self._kinds, self._attr, self._got = kinds, attr, {}

    def __getitem__(self, kind: str):
        if kind not in self._kinds:
            raise KeyError(kind)
        if kind not in self._got:
            mech = import_module(f"{__name__}.{kind}").MECHANISM
            self._got[kind] = mech if self._attr == "" else getattr(mech, self._attr)
        return self._got[kind]

    def __iter__(self) -> Iterator[str]:
        return iter(self._kinds)

    def __len__(self) -> int:
        return len(self._kinds)


REGISTRY: Mapping[str, Mechanism] = _Registry(KINDS, "")
_SCHEMAS: Mapping = _Registry(KINDS, "schema")  # kind -> its design schema, for the loader


def get(kind: str) -> Mechanism:
    """The mechanism of ``kind`` (KeyError for an unknown kind: the loader refuses those first)."""
    return REGISTRY[kind]


def kinds() -> list[str]:
    return list(REGISTRY)


def load_design(path: str | Path, over=None) -> LoadedDesign:
    """A design file validated against its kind's schema, with the command line's ``over``rides
    (see ``config.loader.load_design``)."""
    if over is None:
        return _load_design(path, _SCHEMAS)
    return _load_design(path, _SCHEMAS, over)
