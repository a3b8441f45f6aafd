"""core.background: a shared map gives the caller the values of the list comprehension, done by
both processes when the caller has time to help; it raises the first failing item's error in
order, leaves no child behind when its results are never asked for, and is finished by the caller
when the child dies; PARTGEN_FORK=0 (or fork=False) keeps it all in the caller."""

import os
import time

import numpy as np
import pytest

from partgen.core.background import SharedMap, can_fork

needs_fork = pytest.mark.skipif(not can_fork(), reason="forks only on Linux with two or more CPUs")


def _square_and_pid(x):
    return x * x, os.getpid()


def _big(x):
    return np.arange(200_000, dtype=np.float64) ** 0.5 + x, os.getpid()  # larger than a pipe's buffer


@needs_fork
def test_a_shared_map_is_the_list_comprehension_done_by_both_processes():
    items = list(range(40))
    with SharedMap(_square_and_pid, items) as job:
        got = job.results()  # the caller has nothing else to do: it helps from the back at once
    assert [v for v, _ in got] == [x * x for x in items]
    pids = {pid for _, pid in got}
    assert os.getpid() in pids and len(pids) == 2  # each process did some of it
    assert got[-1][1] == os.getpid() and got[0][1] != os.getpid()  # the child from the front, the caller the back


@needs_fork
def test_large_values_come_back_whole():
    with SharedMap(_big, range(6)) as job:
        time.sleep(0.2)  # the child finishes all of it before the caller asks
        got = job.results()
    assert all(np.array_equal(v, _big(x)[0]) for x, (v, _) in zip(range(6), got))
    assert got[0][1] != os.getpid()


@pytest.mark.parametrize("fork", [True, False])
def test_a_shared_map_raises_the_first_failing_item_in_order(fork):
    def f(x):
        if x in (3, 37):
            raise ValueError(f"item {x}")
        return x
    with pytest.raises(ValueError, match="item 3$"):
        with SharedMap(f, range(40), fork=fork) as job:
            job.results()


def test_without_fork_the_caller_computes_it_all(monkeypatch):
    with SharedMap(_square_and_pid, range(5), fork=False) as job:
        assert {pid for _, pid in job.results()} == {os.getpid()}
    monkeypatch.setenv("PARTGEN_FORK", "0")
    assert not can_fork()
    with SharedMap(_square_and_pid, range(5)) as job:
        assert {pid for _, pid in job.results()} == {os.getpid()}


@needs_fork
def test_work_never_asked_for_leaves_no_child(tmp_path):
    seen = tmp_path / "pid"

    def slow(x):
        seen.write_text(str(os.getpid()))
        time.sleep(60)
    with pytest.raises(RuntimeError):
        with SharedMap(slow, range(2)):
            for _ in range(500):  # wait until the child has started
                if seen.exists() and seen.read_text():
                    break
                time.sleep(0.01)
            raise RuntimeError("the caller failed first")
    pid = int(seen.read_text())
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)  # killed and reaped: not our child any more
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)


@needs_fork
def test_a_shared_map_whose_child_dies_is_finished_by_the_caller():
    parent = os.getpid()

    def f(x):
        if x == 5 and os.getpid() != parent:
            os._exit(3)  # the child dies on item 5
        return x + 1
    with SharedMap(f, range(30)) as job:
        assert job.results() == [x + 1 for x in range(30)]
