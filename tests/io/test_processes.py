"""Worker pools whose workers end with their parent (issue 19) and are stopped, not waited for.

The parent-death tests run a small driver script as a real process, SIGKILL it and check that its
workers are gone within 5 s (a bound against hanging, polled; no timing is asserted).
"""

from __future__ import annotations

import ctypes
import os
import signal
import subprocess
import sys
import textwrap
import time
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

import pytest

from loader_model.io.processes import WorkerPool, worker_pool
from tests.process_scan import running, wait_until

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")

DRIVER = """
import os, sys, time
from loader_model.io.processes import worker_pool

def pid_after(delay_s):
    time.sleep(delay_s)
    return os.getpid()

def busy():
    while True:  # Python bytecode: the GIL passes to the watchdog between them
        pass

if __name__ == "__main__":
    with worker_pool(2, death_signal={death_signal}) as pool:
        for future in [pool.submit(pid_after, 0.3) for _ in range(2)]:
            future.result()  # the workers have started (initializer run)
        print(*pool._processes, flush=True)
        pool.submit(time.sleep, 600)
        pool.submit(busy)
        time.sleep(600)
"""


@pytest.mark.parametrize("death_signal", [True, False], ids=["pdeathsig", "watchdog"])
def test_workers_end_when_the_parent_is_killed(tmp_path, death_signal: bool) -> None:
    script = tmp_path / "driver.py"
    script.write_text(textwrap.dedent(DRIVER.format(death_signal=death_signal)))
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    workers: list[int] = []
    try:
        workers += [int(pid) for pid in parent.stdout.readline().split()]
        assert len(workers) == 2 and all(running(pid) for pid in workers)
        parent.kill()
        parent.wait()
        wait_until(lambda: not any(running(pid) for pid in workers), 5.0, "workers ended")
    finally:
        parent.kill()
        parent.wait()
        parent.stdout.close()
        for pid in workers:  # a failed test leaves none behind
            if running(pid):
                os.kill(pid, signal.SIGKILL)


def _death_signal() -> int:
    """The signal Linux sends this process when its parent ends (PR_GET_PDEATHSIG; 0: none)."""
    value = ctypes.c_int()
    ctypes.CDLL(None).prctl(2, ctypes.byref(value), 0, 0, 0)
    return value.value


@pytest.mark.parametrize("death_signal", [None, False])
def test_workers_ignore_sigint_die_on_sigterm_and_on_parent_death(death_signal) -> None:
    with worker_pool(1, death_signal=death_signal) as pool:
        assert pool.submit(signal.getsignal, signal.SIGINT).result() == signal.SIG_IGN
        assert pool.submit(signal.getsignal, signal.SIGTERM).result() == signal.SIG_DFL
        expected = signal.SIGKILL if death_signal is None else 0  # made in the main thread
        assert pool.submit(_death_signal).result() == expected


def test_an_exception_in_the_block_stops_running_workers_at_once() -> None:
    with pytest.raises(KeyboardInterrupt), worker_pool(2) as pool:
        futures = [pool.submit(time.sleep, 60) for _ in range(3)]
        wait_until(lambda: sum(f.running() for f in futures) >= 1, 30.0, "a task running")
        processes, manager = list(pool._processes.values()), pool._executor_manager_thread
        raise KeyboardInterrupt
    assert processes and not any(p.is_alive() for p in processes)
    assert not manager.is_alive()  # the pool's thread has ended too
    for future in futures:  # cancelled if queued, broken if it was running: none finished
        assert future.cancelled() or isinstance(future.exception(timeout=30), BrokenProcessPool)


def test_a_normal_end_waits_for_the_results() -> None:
    with worker_pool(2) as pool:
        futures = [pool.submit(pow, 2, n) for n in range(5)]
    assert [f.result() for f in futures] == [1, 2, 4, 8, 16]


def test_completed_yields_every_future_once() -> None:
    with worker_pool(2) as pool:
        futures = [pool.submit(pow, 3, n) for n in range(6)]
        assert sorted(f.result() for f in pool.completed(futures)) == [3**n for n in range(6)]


@pytest.mark.usefixtures("python_sigint")
def test_an_interrupt_during_submit_acts_after_it(monkeypatch) -> None:
    original = ProcessPoolExecutor.submit

    def interrupted_submit(self, *args, **kwargs):
        signal.raise_signal(signal.SIGINT)  # inside the pool's own code, where locks are held
        return original(self, *args, **kwargs)

    with worker_pool(1) as pool:
        monkeypatch.setattr(ProcessPoolExecutor, "submit", interrupted_submit)
        queued = pool._queue_count
        with pytest.raises(KeyboardInterrupt):
            pool.submit(pow, 2, 3)
        assert pool._queue_count == queued + 1  # the submission ran to its end, then the interrupt
        monkeypatch.setattr(ProcessPoolExecutor, "submit", original)
        assert pool.submit(pow, 2, 5).result() == 32  # the pool still works
    assert isinstance(pool, WorkerPool)
