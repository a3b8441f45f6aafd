"""Run many pure tasks on a Dask distributed cluster: a ``LocalCluster`` on this machine's cores,
or an existing scheduler by its address.

Tasks are pure functions of their arguments (a design, a seed, a chunk index), so what they return
does not depend on which worker ran them or in what order: the caller keys every result by its
task and combines them in task order. ``run`` hands each result to ``on_result`` as it arrives
(the caller writes it down at once, so an interrupted run keeps what it finished).
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
import time
from typing import Callable, Iterable

from .errors import OptionError

__all__ = ["CONNECT_TIMEOUT_S", "WORKER_MALLOC", "LOCAL_QUIET", "OVERSUBSCRIBE", "cluster", "starting", "run",
           "default_workers", "local_workers", "Counter"]

CONNECT_TIMEOUT_S = 4.0  # an unreachable --scheduler is an error within 10 s (a TCP probe ≤ 2 s, then Dask's protocol ≤ 4 s), never a hang
# glibc malloc settings of a local cluster's worker processes. Dask's nanny sets
# MALLOC_TRIM_THRESHOLD_=64 KiB, and setting it switches off glibc's sliding mmap threshold: every
# array over 128 KiB (a 1,000-sample chunk's draws are 1.4 MB) was then mapped fresh and
# page-faulted in on every task, and a chunk computed in 11-14 ms on a worker against 5.9 ms in a
# plain process. Arrays up to 32 MiB now come from the heap, and up to 32 MiB of free heap stays
# with the worker between tasks (benchmarks/README.md, bench_tolerance.py).
WORKER_MALLOC = {"MALLOC_MMAP_THRESHOLD_": 32 << 20, "MALLOC_TRIM_THRESHOLD_": 32 << 20}
# Dask's housekeeping, slowed for a local cluster of one-thread workers (it has no dashboard to
# feed). Idle, the client's process (scheduler and nannies) used 43 ms of CPU a second and each
# worker 30-37 ms, taken from the tasks on a machine whose every core runs a worker; the workers'
# statistical profiler also samples the running task's stack every 10 ms. Here the profiler is
# off and the event loops' health tick and the system monitor run every 1 and 2 s (not 20 and
# 500 ms): idle, 13-17 and 3-10 ms a second. The memory monitor keeps its 100 ms, so a worker
# that runs away is still stopped in time.
LOCAL_QUIET = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s",
               "distributed.admin.system-monitor.interval": "2s"}


def _reachable(address: str) -> str | None:
    """Why a tcp:// scheduler address cannot be reached (a refused or silent port), or None: a
    quick probe, so a wrong address fails at once instead of after Dask's retries."""
    import socket
    from urllib.parse import urlsplit

    if "://" not in address:
        address = "tcp://" + address
    try:
        u = urlsplit(address)
        if u.scheme not in ("tcp", "tls"):  # inproc:// is one process's; ucx:// needs ucx-py
            return f"partgen connects to a scheduler at tcp:// or tls://, not {u.scheme}://"
        host, port = u.hostname, u.port
    except ValueError as e:  # "tcp://[::1", a port out of range
        return f"not an address: {e}"
    if not host or not port:
        return "give it as tcp://HOST:PORT"
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S / 2):
            return None
    except OSError as e:
        return e.strerror or type(e).__name__


def _within(fn: Callable, seconds: float, name: str) -> dict:
    """Run ``fn()`` in a daemon thread and wait at most ``seconds``: {"value": what it returned} or
    {"error": what it raised}, or {} when it had not finished (it is left to finish alone)."""
    import threading

    got: dict = {}

    def run_it():
        try:
            got["value"] = fn()
        except BaseException as e:  # noqa: BLE001 - handed to the caller
            got["error"] = e
    t = threading.Thread(target=run_it, name=name, daemon=True)
    t.start()
    t.join(seconds)
    return got


def _identify(address: str) -> str | None:
    """Why no Dask scheduler answers at ``address`` (None: one does), asked in Dask's own protocol
    (its handshake, then ``identity``) within CONNECT_TIMEOUT_S and before any Client exists: a port
    that answers in another protocol made the Client read a garbage frame length (a MemoryError
    for 3 EiB) and left a half-made Client whose clean-up hung for 8 s and printed a traceback."""
    import asyncio

    async def ask():
        from distributed.comm import connect
        from distributed.security import Security

        # tls://: the certificates Dask's config names, as the Client would use them
        comm = await connect(address, timeout=CONNECT_TIMEOUT_S, **Security().get_connection_args("client"))
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    got = _within(lambda: asyncio.run(asyncio.wait_for(ask(), CONNECT_TIMEOUT_S)), CONNECT_TIMEOUT_S + 0.5,
                  "partgen-identify")
    if "value" in got:
        reply = got["value"]
        kind = reply.get("type") if isinstance(reply, dict) else None
        if kind == "Scheduler":
            return None
        return f"a Dask {kind} answers there, not a scheduler" if isinstance(kind, str) else \
            "something answers there, but not as a Dask scheduler"
    e = got.get("error")
    if e is None or isinstance(e, (TimeoutError, asyncio.TimeoutError)) or "timed out" in str(e).lower():
        return f"the port takes connections but nothing answered in Dask's protocol within {CONNECT_TIMEOUT_S:g} s"
    return "something answers there, but not in Dask's protocol"


def _connect(Client, address: str):
    """A Client of the scheduler at ``address`` (one ``_identify`` heard), or ``OptionError`` when
    it cannot be made within CONNECT_TIMEOUT_S: the Client is made in a thread and waited for, so
    a scheduler that stops answering in between is an error, not a hang."""
    got = _within(lambda: Client(address, timeout=f"{CONNECT_TIMEOUT_S}s", set_as_default=False),
                  CONNECT_TIMEOUT_S + 0.5, "partgen-connect")
    if "value" in got:
        return got["value"]
    e = got.get("error")
    why = "no answer" if e is None else f"{type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}"
    raise OptionError("--scheduler", address, f"no Dask scheduler answered there within {CONNECT_TIMEOUT_S:g} s ({why})")


def _has_workers(client, address: str) -> None:
    """``OptionError`` on --scheduler when no worker has joined the scheduler within
    CONNECT_TIMEOUT_S (the tasks would wait for one forever, or fail deep inside Dask)."""
    try:
        client.wait_for_workers(1, timeout=CONNECT_TIMEOUT_S)
    except TimeoutError:
        raise OptionError("--scheduler", address, f"the Dask scheduler there has no workers (none joined within "
                          f"{CONNECT_TIMEOUT_S:g} s): start some, e.g. `dask worker {address} --nthreads 1`") from None


def default_workers() -> int:
    """The cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


@contextlib.contextmanager
def cluster(workers: int | None = None, scheduler: str | None = None, processes: bool | None = None):
    """A connected ``distributed.Client``: to ``scheduler`` (an address such as
    ``tcp://10.0.0.5:8786``; ``OptionError`` on --scheduler when it cannot be reached within
    CONNECT_TIMEOUT_S), or to a new ``LocalCluster`` of ``workers`` single-threaded workers
    (``processes``: True, worker processes; False, threads of this process, quick to start; None,
    processes for more than one worker, a thread for one)."""
    if scheduler is None:
        local_workers(workers)
    import dask
    from distributed import Client, LocalCluster

    with dask.config.set({"distributed.comm.timeouts.connect": f"{CONNECT_TIMEOUT_S}s",
                          "distributed.admin.tick.limit": "1h",
                          **{f"distributed.nanny.pre-spawn-environ.{k}": v for k, v in WORKER_MALLOC.items()},
                          **(LOCAL_QUIET if scheduler is None else {})}):
        if scheduler is not None:
            why = _reachable(scheduler)
            if why is not None:
                raise OptionError("--scheduler", scheduler, f"cannot reach a Dask scheduler there ({why})")
            why = _identify(scheduler)
            if why is not None:
                raise OptionError("--scheduler", scheduler, f"no Dask scheduler there ({why})")
            client = _connect(Client, scheduler)
            try:
                _has_workers(client, scheduler)
                yield client
            finally:
                client.close()
            return
        n = local_workers(workers)
        lc = LocalCluster(n_workers=n, threads_per_worker=1, processes=n > 1 if processes is None else processes,
                          # its HTTP server on a free local port: with None it took 8787 and, when a
                          # notebook's cluster had it, warned the user on stderr
                          dashboard_address="127.0.0.1:0",
                          silence_logs=logging.CRITICAL + 1)  # not even the shutdown's comm errors
        client = Client(lc, set_as_default=False)
        try:
            yield client
        finally:
            client.close()
            lc.close()


OVERSUBSCRIBE = 4  # a local cluster has at most this many workers per core


def local_workers(workers: int | None) -> int:
    """The workers of a local cluster: ``workers``, or one per core; ``OptionError`` on --workers
    beyond OVERSUBSCRIBE per core (each is a process of ~100 MB that only waits for a core: 1,024 of
    them would take ~100 GB)."""
    cores = default_workers()
    n = workers or cores
    if n > OVERSUBSCRIBE * cores:
        raise OptionError("--workers", str(n), f"this machine has {cores} core{'s' if cores > 1 else ''}: a local "
                          f"cluster of more than {OVERSUBSCRIBE * cores} workers only waits for them (use --scheduler "
                          "to run on more machines)")
    return n


@contextlib.contextmanager
def starting(workers: int | None = None, scheduler: str | None = None, processes: bool | None = None):
    """``cluster(...)`` that starts while the caller goes on: yields ``get()``, which returns the
    connected client once it is up (and raises what starting it raised). A local cluster starts in
    a thread, so its worker processes spawn while this process builds and checks the kit; an
    existing ``scheduler`` is connected to at once, so a wrong address still fails before any work."""
    if scheduler is not None:
        with cluster(workers, scheduler, processes) as client:
            yield lambda: client
        return
    local_workers(workers)  # a wrong --workers fails now, not after the caller's work
    import threading

    box: dict = {}
    up, done = threading.Event(), threading.Event()

    def hold():
        try:
            with cluster(workers, None, processes) as client:
                box["client"] = client
                up.set()
                done.wait()
        except BaseException as e:  # noqa: BLE001 - raised again by get()
            box["error"] = e
        finally:
            up.set()

    t = threading.Thread(target=hold, name="partgen-cluster", daemon=True)
    t.start()

    def get():
        up.wait()
        if "client" not in box:
            raise box.get("error") or RuntimeError("the local cluster did not start")
        return box["client"]
    try:
        yield get
    finally:
        done.set()
        t.join()
    if "error" in box and "client" in box:  # it started, but closing it failed (and nothing else did)
        raise box["error"]


class Counter:
    """A progress line on stderr (only on a terminal): ``done/total`` with the elapsed time."""

    def __init__(self, label: str, total: int, enabled: bool = True, done: int = 0):
        self.label, self.total, self.done = label, total, done
        self.enabled = enabled and sys.stderr.isatty()
        self.t0 = time.perf_counter()

    def __call__(self, step: int = 1) -> None:
        self.done += step
        if not self.enabled:
            return
        w = 30
        k = int(w * self.done / max(self.total, 1))
        print(f"\r  {self.label} [{'#' * k}{'.' * (w - k)}] {self.done}/{self.total} "
              f"{time.perf_counter() - self.t0:6.1f} s", end="", file=sys.stderr, flush=True)
        if self.done >= self.total:
            print("\r" + " " * 78 + "\r", end="", file=sys.stderr, flush=True)


def run(client, fn: Callable, shared, tasks: Iterable[tuple], on_result: Callable, progress: Callable | None = None,
        label: str = "task") -> None:
    """Submit ``fn(shared, *args)`` for every ``(key, args)`` of ``tasks`` and call
    ``on_result(key, value)`` as each one finishes (in the order they finish). ``shared`` is sent
    to the workers once. A task that raises stops the run with its error."""
    from distributed import as_completed

    tasks = list(tasks)
    if not tasks:
        return
    big = client.scatter(shared, broadcast=True, hash=False) if shared is not None else None
    stamp = time.monotonic_ns()
    keys = [f"{label}-{key}-{stamp}" for key, _ in tasks]
    by_key = {k: key for k, (key, _) in zip(keys, tasks)}
    columns = list(zip(*(args for _, args in tasks)))
    # one call submits them all; results come back in batches as they finish (with_results)
    futures = client.map(fn, [big] * len(tasks), *columns, key=keys, pure=False)
    done = 0
    try:
        for fut, value in as_completed(futures, with_results=True, loop=client.loop):
            on_result(by_key[fut.key], value)
            done += 1
            if progress:
                progress()
    finally:
        if done < len(futures):  # stopped early (an error, ^C): the rest must not run on
            client.cancel(list(futures))
