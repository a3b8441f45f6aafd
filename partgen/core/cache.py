"""Decisions partgen remembers between runs: a small JSON file per decision in partgen's own cache
folder, under a key that changes with everything the decision depends on.

A decision (what ``backlash_per_gear_mm: auto`` chose and the P(jam) it reaches, a layout a
mechanism's search chose) is stored under the sha256 of: what it was computed from (the caller's
bytes, e.g. the pickled resolved design), the source of every partgen module, and the Python, numpy, manifold3d, shapely, trimesh
and scipy versions. So a remembered answer is the one the computation would give now: any change
to the design, to partgen or to a library is another key, and the decision is computed again.

The folder is ``$PARTGEN_CACHE_DIR``, else ``$XDG_CACHE_HOME/partgen``, else
``~/.cache/partgen``; partgen creates it, writes only its own ``*.json`` files there (atomically:
a temporary file renamed into place) and never reads anything else from it. ``PARTGEN_CACHE=0``
turns it off. A cache that cannot be read or written is no error: the decision is computed.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
from functools import lru_cache
from importlib import metadata
from pathlib import Path

__all__ = ["cache_dir", "code_fingerprint", "recall", "remember"]

LIBRARIES = ("numpy", "manifold3d", "shapely", "trimesh", "scipy")
_PACKAGE = Path(__file__).resolve().parents[1]


def cache_dir() -> Path | None:
    """partgen's cache folder, or None when the cache is turned off."""
    if os.environ.get("PARTGEN_CACHE", "1").strip().lower() in ("0", "off", "no", "false"):
        return None
    if os.environ.get("PARTGEN_CACHE_DIR"):
        return Path(os.environ["PARTGEN_CACHE_DIR"])
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "partgen"


@lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """sha256 over every partgen module's source and the libraries' versions (hex)."""
    h = hashlib.sha256(sys.version.encode())
    for name in LIBRARIES:
        try:
            h.update(f"{name} {metadata.version(name)}".encode())
        except metadata.PackageNotFoundError:
            h.update(f"{name} -".encode())
    for path in sorted(_PACKAGE.rglob("*.py")):
        h.update(str(path.relative_to(_PACKAGE)).encode() + b"\0" + path.read_bytes())
    return h.hexdigest()


def _path(namespace: str, what: bytes) -> Path | None:
    root = cache_dir()
    if root is None:
        return None
    key = hashlib.sha256(namespace.encode() + b"\0" + code_fingerprint().encode() + b"\0" + what).hexdigest()
    return root / namespace / f"{key[:32]}.json"


def recall(namespace: str, what: bytes):
    """The decision remembered under (``namespace``, ``what``), or None."""
    path = _path(namespace, what)
    if path is None or not path.is_file():
        return None
    try:
        return json.loads(path.read_text())["value"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def remember(namespace: str, what: bytes, value) -> None:
    """Keep ``value`` (JSON) under (``namespace``, ``what``); quietly nothing when it cannot."""
    path = _path(namespace, what)
    if path is None:
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=path.parent)
        with os.fdopen(fd, "w") as f:
            json.dump({"value": value}, f)
        os.replace(tmp, path)
    except (OSError, TypeError, ValueError):
        try:
            os.unlink(tmp)  # noqa: F821 - only bound once mkstemp succeeded
        except (OSError, NameError):
            pass
