"""The last traces a process made, kept in memory: `partgen report` traces the kit it checks, and a
process that runs `trace` and then `report` on one kit (a notebook, the test suite, a script over
the CLI) traces it once. A hit needs the very kit object (a kit is frozen; another, even an equal
one, misses), an equal design, the same kind and samples; it hands back a copy of the trace and
writes the figures' bytes the first trace wrote into the new folder. Only for traces that depend on
nothing else (not on ``animate``). Bounded (``KEPT`` entries), nothing on disk."""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path
from typing import Callable

from ..core.protocol import Trace

__all__ = ["remembered", "KEPT"]

KEPT = 2
_TRACES: list[tuple] = []  # (kind, kit, spec, samples, trace, {file: bytes} or None), newest last


def _copy(trace: Trace, files: tuple) -> Trace:
    data = None if trace.data is None else trace.data.copy()
    return dataclasses.replace(trace, stats=copy.deepcopy(trace.stats), data=data, files=files)


def _same(a, b) -> bool:
    try:
        return a is b or bool(a == b)
    except (TypeError, ValueError):  # a design whose equality is not a bool (arrays inside): a miss
        return False


def remembered(kind: str, spec, kit, samples: int | None, out: Path | None,
               compute: Callable[[Path | None], Trace]) -> Trace:
    """``compute(out)``'s trace of ``spec`` (and ``kit``: None when the trace does not read it) at
    ``samples``, from memory when one was made of the same kit object, an equal design and the
    same samples (with its figures, when ``out`` asks for them)."""
    for k, (m_kind, m_kit, m_spec, m_samples, m_trace, m_files) in enumerate(_TRACES):
        if (m_kind == kind and m_kit is kit and m_samples == samples and (m_files is not None or out is None)
                and _same(m_spec, spec)):
            _TRACES.append(_TRACES.pop(k))
            if out is None:
                return _copy(m_trace, ())
            for name, data in m_files.items():
                (out / name).write_bytes(data)
            return _copy(m_trace, tuple(m_files))
    trace = compute(out)
    files = None if out is None else {name: (out / name).read_bytes() for name in trace.files}
    _TRACES.append((kind, kit, spec, samples, _copy(trace, trace.files), files))
    del _TRACES[:-KEPT]
    return trace
