"""core.background: work run in a forked child gives the caller the same values, raises the same
error (for a shared map, the first failing item's, as the list comprehension would), leaves no
child behind when its results are never asked for, and is computed by the caller when the child
dies; a shared map's items are done by both processes when the caller has time to help."""

import os

import numpy as np
import pytest

from partgen.core.background import Background, SharedMap, can_fork

needs_fork = pytest.mark.skipif(not can_fork(), reason="forks only on Linux with two or more CPUs")


def _child_pid_and_array():
    return os.getpid(), np.arange(200_000, dtype=np.float64) ** 0.5  # larger than a pipe's buffer


@needs_fork
def test_the_child_computes_what_the_caller_would():
    with Background(_child_pid_and_array) as job:
        pid, arr = job.result()
    assert pid != os.getpid()  # it ran in another process
    assert np.array_equal(arr, _child_pid_and_array()[1])


def test_without_fork_it_runs_in_the_caller():
    with Background(_child_pid_and_array, fork=False) as job:
        pid, _ = job.result()
    assert pid == os.getpid()


@pytest.mark.parametrize("fork", [True, False])
def test_an_error_in_the_computation_is_raised_in_the_caller(fork):
    def bad():
        raise ValueError("no such gear")
    with pytest.raises(ValueError, match="no such gear"):
        with Background(bad, fork=fork) as job:
            job.result()


@needs_fork
def test_a_job_never_asked_for_leaves_no_child(tmp_path):
    seen = tmp_path / "pid"

    def slow():
        seen.write_text(str(os.getpid()))
        import time
        time.sleep(60)
    with pytest.raises(RuntimeError):
        with Background(slow):
            for _ in range(500):  # wait until the child has started
                if seen.exists() and seen.read_text():
                    break
                __import__("time").sleep(0.01)
            raise RuntimeError("the caller failed first")
    pid = int(seen.read_text())
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)  # killed and reaped: not our child any more
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)


@needs_fork
def test_a_child_that_dies_is_computed_again_in_the_caller():
    calls = []

    def dies_in_the_child():
        if calls == []:  # the child sees the parent's list as it was at the fork
            os._exit(3)
        return "computed here"
    with Background(dies_in_the_child) as job:
        calls.append("parent")
        assert job.result() == "computed here"


def test_partgen_fork_0_turns_it_off(monkeypatch):
    monkeypatch.setenv("PARTGEN_FORK", "0")
    assert not can_fork()
    with Background(_child_pid_and_array) as job:
        assert job.result()[0] == os.getpid()


def _square_and_pid(x):
    return x * x, os.getpid()


@needs_fork
def test_a_shared_map_is_the_list_comprehension_done_by_both_processes():
    items = list(range(40))
    with SharedMap(_square_and_pid, items) as job:
        got = job.results()  # the caller has nothing else to do: it helps from the back at once
    assert [v for v, _ in got] == [x * x for x in items]
    pids = {pid for _, pid in got}
    assert os.getpid() in pids and len(pids) == 2  # each process did some of it
    assert got[-1][1] == os.getpid()  # the caller started from the back


@pytest.mark.parametrize("fork", [True, False])
def test_a_shared_map_raises_the_first_failing_item_in_order(fork):
    def f(x):
        if x in (3, 37):
            raise ValueError(f"item {x}")
        return x
    with pytest.raises(ValueError, match="item 3$"):
        with SharedMap(f, range(40), fork=fork) as job:
            job.results()


@needs_fork
def test_a_shared_map_whose_child_dies_is_finished_by_the_caller():
    parent = os.getpid()

    def f(x):
        if x == 5 and os.getpid() != parent:
            os._exit(3)  # the child dies on item 5
        return x + 1
    with SharedMap(f, range(30)) as job:
        assert job.results() == [x + 1 for x in range(30)]
