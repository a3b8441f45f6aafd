"""Work run beside the caller's own, in a forked copy of the process.

manifold3d and most of partgen's numpy hold the GIL, so threads do not overlap them; a forked child
does, and it needs nothing pickled but its results (it starts with the parent's memory: the kit,
its solids and meshes). ``build`` uses it to make a gear chain's clocked gears while it makes the
rest of the kit, and assembly.glb's motion and shaded meshes and each STL's report while it weighs
the parts; a GLB made for `report` shades its meshes with it too. The child computes exactly what the caller would (same code, same inputs), so the results
are the same bytes either way.

``SharedMap(fn, items)`` is ``[fn(x) for x in items]``, the child working from the front while the
caller does its own work; when the caller asks for the results it takes items from the back itself
until the two meet, so neither waits for long whatever the balance of the work.

Where it forks: Linux with more than one CPU for this process, unless ``PARTGEN_FORK=0``. Elsewhere
(macOS and Windows, where forking a process that has imported numpy is unsafe or impossible, or one
CPU) the work runs in the caller when its results are asked for. If the child dies without an
answer, the caller computes what is missing itself; an exception in the work is raised in the
caller (the first failing item's in order, as the list comprehension would). Work whose results are
never asked for (the caller failed first) has its child killed when the ``with`` block ends.
"""

from __future__ import annotations

import itertools
import os
import pickle
import select
import signal
import struct
import sys
import tempfile
import warnings
from typing import Callable, Generic, Sequence, TypeVar

__all__ = ["SharedMap", "can_fork"]

T = TypeVar("T")
_WHERE = struct.Struct("<QQ")  # what the child sends on the pipe: where an object lies in the file, its length


def can_fork() -> bool:
    """Whether work runs in a forked child here (Linux, two or more CPUs, and ``PARTGEN_FORK`` not
    0/off/no/false)."""
    if os.environ.get("PARTGEN_FORK", "1").strip().lower() in ("0", "off", "no", "false"):
        return False
    if not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        return False
    try:
        return len(os.sched_getaffinity(0)) > 1
    except (AttributeError, OSError):  # pragma: no cover - every Linux has it
        return (os.cpu_count() or 1) > 1


class _Child:
    """A forked child running ``work(send)``; ``send(obj)`` passes one object to the caller. The
    objects go through an unlinked temporary file (the child never waits for the caller to read);
    the pipe carries only where each one lies."""

    def __init__(self, work: Callable[[Callable[[object], None]], None]):
        self._file = tempfile.TemporaryFile(prefix="partgen-")
        r, w = os.pipe()
        for stream in (sys.stdout, sys.stderr):  # nothing buffered is written twice
            try:
                stream.flush()
            except (AttributeError, ValueError, OSError):
                pass
        with warnings.catch_warnings():  # Python 3.12+ warns on forking with threads alive (numpy's BLAS
            warnings.simplefilter("ignore", DeprecationWarning)  # pool, which re-forms in the child)
            pid = os.fork()
        if pid == 0:  # the child: work, send, leave without running the parent's exit handlers
            code = 0
            try:
                os.close(r)
                end = 0

                def send(obj) -> None:
                    nonlocal end
                    try:
                        data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
                    except Exception:  # an exception that does not pickle: the caller computes it again
                        return
                    os.pwrite(self._file.fileno(), data, end)
                    os.write(w, _WHERE.pack(end, len(data)))
                    end += len(data)
                work(send)
            except BaseException:  # noqa: BLE001 - the caller computes what did not arrive
                code = 1
            finally:
                os._exit(code)
        os.close(w)
        self.pid, self.fd, self._buf = pid, r, b""

    def receive(self, block: bool) -> list:
        """The objects sent so far and not yet received (waiting for at least one when ``block``,
        unless the child has finished)."""
        out = []
        while self.fd is not None:
            if not block or out:
                ready, _, _ = select.select([self.fd], [], [], 0)
                if not ready:
                    break
            chunk = os.read(self.fd, 1 << 16)
            if not chunk:  # the child has finished (or died)
                os.close(self.fd)
                self.fd = None
                break
            self._buf += chunk
            while len(self._buf) >= _WHERE.size:
                at, n = _WHERE.unpack_from(self._buf)
                self._buf = self._buf[_WHERE.size:]
                out.append(pickle.loads(os.pread(self._file.fileno(), n, at)))
        return out

    def stop(self) -> None:
        """Kill the child (if it still runs) and reap it."""
        if self.pid is not None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:  # pragma: no cover - already gone
                pass
            os.waitpid(self.pid, 0)
            self.pid = None
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None
        self._file.close()


class SharedMap(Generic[T]):
    """``with SharedMap(fn, items) as job: ...; values = job.results()``: ``[fn(x) for x in items]``,
    a forked child working from the front from the ``with`` on, the caller from the back once it asks
    (module docstring); ``fork=False`` computes it all in the caller."""

    def __init__(self, fn: Callable[[object], T], items: Sequence, fork: bool | None = None):
        self._fn, self._items = fn, list(items)
        self._fork = (can_fork() if fork is None else bool(fork and can_fork())) and len(self._items) > 1
        self._child: _Child | None = None

    def __enter__(self) -> "SharedMap[T]":
        if self._fork:
            def work(send):
                for x in self._items:
                    got = _attempt(lambda: self._fn(x))
                    send(got)
                    if not got[0]:
                        return
            self._child = _Child(work)
        return self

    def results(self) -> list[T]:
        """The values in the items' order (raises what the first failing item raised)."""
        child, self._child = self._child, None
        if child is None:
            return [self._fn(x) for x in self._items]
        front: list = []  # the child's answers, in order
        back: dict = {}  # index -> the caller's answer
        hi = len(self._items)  # the caller has done items[hi:]
        try:
            while len(front) < hi:
                front += child.receive(block=False)
                if any(not ok for ok, _ in front) or child.fd is None:
                    break
                if len(front) >= hi - 1:  # the child is on the last one left: wait for it
                    front += child.receive(block=True)
                    continue
                hi -= 1
                back[hi] = _attempt(lambda: self._fn(self._items[hi]))
                if not back[hi][0]:
                    break
        finally:
            child.stop()
        answers = [*front[:hi], *(back[i] for i in range(hi, len(self._items)) if i in back)]
        if len(answers) == len(self._items) and all(ok for ok, _ in answers):
            return [v for _, v in answers]
        # a failure, or a child that died: the child's answers before its first failure are kept, the
        # rest computed here in order, so the first failing item raises
        done = [v for _, v in itertools.takewhile(lambda a: a[0], front[:hi])]
        return [*done, *(self._fn(x) for x in self._items[len(done):])]

    def __exit__(self, *exc) -> None:
        if self._child is not None:  # never asked for: stop the child
            self._child.stop()
            self._child = None


def _attempt(fn: Callable[[], T]) -> tuple[bool, object]:
    try:
        return True, fn()
    except Exception as e:  # noqa: BLE001 - raised again in the caller
        return False, e
