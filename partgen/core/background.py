"""One computation run beside the caller's own work, in a forked copy of the process.

manifold3d and most of partgen's numpy hold the GIL, so threads do not overlap them; a forked child
does, and it needs nothing pickled but its result (it starts with the parent's memory: the kit,
its solids and meshes). ``build`` uses it to make assembly.glb while it verifies and weighs the
parts. The child computes exactly what the caller would (same code, same inputs), so the result is
the same bytes either way.

Where it forks: Linux with more than one CPU for this process, unless ``PARTGEN_FORK=0``. Elsewhere
(macOS and Windows, where forking a process that has imported numpy is unsafe or impossible, or one
CPU) the computation runs in the caller when its result is asked for. If the child dies without an answer, the caller
computes it itself; an exception in the child is raised in the caller. A job whose result is never
asked for (the caller failed first) has its child killed when the ``with`` block ends.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
import warnings
from typing import Callable, Generic, TypeVar

__all__ = ["Background", "can_fork"]

T = TypeVar("T")


def can_fork() -> bool:
    """Whether ``Background`` runs its computation in a forked child here (Linux, two or more CPUs,
    and ``PARTGEN_FORK`` not 0/off/no/false)."""
    if os.environ.get("PARTGEN_FORK", "1").strip().lower() in ("0", "off", "no", "false"):
        return False
    if not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        return False
    try:
        return len(os.sched_getaffinity(0)) > 1
    except (AttributeError, OSError):  # pragma: no cover - every Linux has it
        return (os.cpu_count() or 1) > 1


class Background(Generic[T]):
    """``with Background(fn) as job: ...; value = job.result()``: ``fn()`` runs in a forked child
    from the ``with`` until ``result()`` (module docstring); ``fork=False`` runs it in the caller."""

    def __init__(self, fn: Callable[[], T], fork: bool | None = None):
        self._fn = fn
        self._fork = can_fork() if fork is None else bool(fork and can_fork())
        self._pid = None
        self._read = None

    def __enter__(self) -> "Background[T]":
        if not self._fork:
            return self
        r, w = os.pipe()
        for stream in (sys.stdout, sys.stderr):  # nothing buffered is written twice
            try:
                stream.flush()
            except (AttributeError, ValueError, OSError):
                pass
        with warnings.catch_warnings():  # Python 3.12+ warns on forking with threads alive (numpy's BLAS
            warnings.simplefilter("ignore", DeprecationWarning)  # pool, which re-forms in the child)
            pid = os.fork()
        if pid == 0:  # the child: compute, send, leave without running the parent's exit handlers
            code = 0
            try:
                os.close(r)
                try:
                    payload = pickle.dumps((True, self._fn()), protocol=pickle.HIGHEST_PROTOCOL)
                except BaseException as e:  # noqa: BLE001 - every failure goes back to the caller
                    try:
                        payload = pickle.dumps((False, e), protocol=pickle.HIGHEST_PROTOCOL)
                    except Exception:  # an exception that does not pickle: the caller computes it again
                        payload = b""
                with os.fdopen(w, "wb") as f:
                    f.write(payload)
            except BaseException:  # noqa: BLE001
                code = 1
            finally:
                os._exit(code)
        os.close(w)
        self._pid, self._read = pid, r
        return self

    def result(self) -> T:
        """``fn()``'s value (raises what ``fn`` raised)."""
        if self._pid is None:
            return self._fn()
        with os.fdopen(self._read, "rb") as f:
            data = f.read()
        self._read = None
        os.waitpid(self._pid, 0)
        self._pid = None
        if not data:  # the child died without an answer: compute it here
            return self._fn()
        ok, value = pickle.loads(data)
        if ok:
            return value
        raise value

    def __exit__(self, *exc) -> None:
        if self._pid is not None:  # never asked for: stop the child
            try:
                os.kill(self._pid, signal.SIGKILL)
            except ProcessLookupError:  # pragma: no cover - already gone
                pass
            os.waitpid(self._pid, 0)
            self._pid = None
        if self._read is not None:
            os.close(self._read)
            self._read = None
