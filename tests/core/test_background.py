"""core.background: a computation run in a forked child gives the caller the same value, raises
the same error, and leaves no child behind when its result is never asked for."""

import os

import numpy as np
import pytest

from partgen.core.background import Background, can_fork

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
