"""The last traces a process made, kept in memory: `partgen report` traces the kit it checks, and a
process that runs `trace` and then `report` on one kit (a notebook, the test suite, a script over
the CLI) traces it once. A hit needs the very kit object (a kit is frozen; another, even an equal
one, misses; None for a trace of the design alone), the same design field by field, the same kind
and samples; it hands back a copy of the trace and writes the figures' bytes the first trace wrote
into the new folder. Only for traces that depend on nothing else (a figure made only on request,
an animation, is named by the caller: ``needs``, ``without``). Bounded (``KEPT`` entries), nothing
on disk."""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path
from typing import Callable

import numpy as np

from ..core.protocol import Trace

__all__ = ["remembered", "KEPT"]

KEPT = 2
_TRACES: list[tuple] = []  # (kind, kit, spec, samples, trace, {file: bytes} or None), newest last


def _copy(trace: Trace, files: tuple) -> Trace:
    data = None if trace.data is None else trace.data.copy()
    return dataclasses.replace(trace, stats=copy.deepcopy(trace.stats), data=data, files=files)


def _same(a, b) -> bool:
    """Whether two designs are the same, field by field: dataclasses by their fields, arrays by their
    bytes, floats by their bits; anything else by ``==`` (an object without one: by identity)."""
    if a is b:
        return True
    if type(a) is not type(b):
        return False
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
    if isinstance(a, float):
        return a.hex() == b.hex()
    if dataclasses.is_dataclass(a):
        return all(_same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return False


def remembered(kind: str, spec, kit, samples: int | None, out: Path | None,
               compute: Callable[[Path | None], Trace], needs: tuple[str, ...] = (),
               without: tuple[str, ...] = ()) -> Trace:
    """``compute(out)``'s trace of ``spec`` (and ``kit``: None when the trace does not read it) at
    ``samples``, from memory when one was made of the same kit object, the same design and the
    same samples (with its figures, when ``out`` asks for them). For a figure made only on request
    (an animation): ``needs`` names the ones this call makes (a trace kept without them misses),
    ``without`` the ones it does not (left out of a kept trace's)."""
    for k, (m_kind, m_kit, m_spec, m_samples, m_trace, m_files) in enumerate(_TRACES):
        if (m_kind == kind and m_kit is kit and m_samples == samples
                and (out is None or (m_files is not None and set(needs) <= set(m_files)))
                and _same(m_spec, spec)):
            _TRACES.append(_TRACES.pop(k))
            if out is None:
                return _copy(m_trace, ())
            names = tuple(n for n in m_files if n not in without)
            for name in names:
                (out / name).write_bytes(m_files[name])
            return _copy(m_trace, names)
    trace = compute(out)
    files = None if out is None else {name: (out / name).read_bytes() for name in trace.files}
    _TRACES.append((kind, kit, spec, samples, _copy(trace, trace.files), files))
    del _TRACES[:-KEPT]
    return trace
