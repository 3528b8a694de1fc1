"""Worker processes that end with their parent, whichever way it ends.

:func:`worker_pool` gives a :class:`WorkerPool` (a
:class:`~concurrent.futures.ProcessPoolExecutor`) whose workers

- ignore SIGINT, so that Ctrl-C (sent by the terminal to the whole process group) reaches only
  the parent, which reports it in one line (:mod:`loader_model.io.interrupts`), and SIGTERM kills
  them (its default). They are started at once with SIGINT and SIGTERM blocked in the starting
  thread; they inherit the block until their start has set the above (and the parent gets a
  signal that came meanwhile once it lifts its block), so a Ctrl-C while they start or import
  prints no traceback of theirs. (Spawned workers need multiprocessing's resource tracker running
  beforehand: starting it lifts the block of the calling thread.);
- end when the parent ends, SIGKILL included: on Linux the kernel sends them SIGKILL when the
  parent dies (``prctl(PR_SET_PDEATHSIG)``, set when the pool is made in the main thread: the
  signal follows the thread that started the worker); everywhere a watchdog thread polls
  ``os.getppid()`` every :data:`WATCHDOG_POLL_S` and ends the worker once it changes (it runs
  whenever the worker's computation lets go of the GIL);
- are stopped at once when the ``with`` block ends with an exception (an interrupt or an error):
  queued tasks are cancelled and running workers terminated, not waited for.

:meth:`WorkerPool.submit` and :meth:`WorkerPool.completed` (in place of
:func:`~concurrent.futures.as_completed`) hold interrupts back while they hold the pool's locks
(:func:`~loader_model.io.interrupts.deferred_interrupts`), so that an interrupt cannot leave one held,
and raise one that came meanwhile, also one that other code caught
(:func:`~loader_model.io.interrupts.check_interrupt`).
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from typing import Any

from loader_model.io.interrupts import check_interrupt, deferred_interrupts

__all__ = ["WAIT_POLL_S", "WATCHDOG_POLL_S", "WorkerPool", "stop_workers", "worker_pool"]

#: Interval in s at which a worker's watchdog checks that its parent still runs.
WATCHDOG_POLL_S = 0.2
#: Longest wait in s of :meth:`WorkerPool.completed` before a held-back interrupt acts.
WAIT_POLL_S = 0.25
_PR_SET_PDEATHSIG = 1
_STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


class WorkerPool(ProcessPoolExecutor):
    """A process pool whose calls from this process cannot be cut by an interrupt halfway
    (module notes); made by :func:`worker_pool`."""

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future:
        """:meth:`ProcessPoolExecutor.submit` with interrupts held back during the call."""
        with deferred_interrupts():
            future = super().submit(fn, *args, **kwargs)
        check_interrupt()
        return future

    def completed(self, futures: Iterable[Future]) -> Iterator[Future]:
        """The ``futures`` as they complete, like :func:`~concurrent.futures.as_completed`; an
        interrupt acts within :data:`WAIT_POLL_S` while it waits."""
        pending = set(futures)
        while pending:
            waiting = as_completed(pending, timeout=WAIT_POLL_S)  # waits on all: once per round
            try:
                while future := self._next(waiting):
                    pending.discard(future)
                    yield future
            finally:
                with deferred_interrupts():
                    waiting.close()

    @staticmethod
    def _next(waiting: Iterator[Future]) -> Future | None:
        """The next completed future of ``waiting``; None at its end or timeout."""
        with deferred_interrupts():  # as_completed takes the futures' locks
            try:
                future = next(waiting, None)
            except TimeoutError:
                future = None
        check_interrupt()  # also one that code of this process caught meanwhile
        return future


def _set_parent_death_signal() -> bool:
    """Ask Linux to SIGKILL this process when its parent thread ends; False where unavailable."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return int(libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def _watch_parent(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(WATCHDOG_POLL_S)
    os._exit(1)


def _start_worker(
    parent_pid: int,
    death_signal: bool,
    initializer: Callable[..., Any] | None,
    initargs: tuple[Any, ...],
) -> None:
    """Worker start (module notes), then ``initializer(*initargs)``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # a forked worker inherits the parent's handler
    if hasattr(signal, "pthread_sigmask"):  # blocked by _start_workers: pending ones act now
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOP_SIGNALS)
    if death_signal:
        _set_parent_death_signal()
    if os.getppid() != parent_pid:  # the parent died before the death signal was set
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent_pid,), name="watchdog", daemon=True).start()
    if initializer is not None:
        initializer(*initargs)


def _start_workers(pool: WorkerPool, workers: int, forked: bool) -> None:
    """Start the ``workers`` processes now (one no-op task each) with SIGINT and SIGTERM blocked
    in this thread (module notes); :func:`_start_worker` sets the workers' own handling."""
    if not hasattr(signal, "pthread_sigmask"):
        return
    if not forked:
        from multiprocessing import resource_tracker

        resource_tracker.ensure_running()
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
    try:
        for _ in range(workers):
            pool.submit(int)
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def stop_workers(pool: ProcessPoolExecutor, grace_s: float = 2.0) -> None:
    """Cancel the queued tasks of ``pool`` and end its workers: SIGTERM, then SIGKILL for any
    still running after ``grace_s``; returns once they and the pool's thread have ended
    (interrupts held back). Waiting for that thread avoids a race in Python 3.11's exit, which may
    write to the thread's closed wake-up pipe ("Exception ignored ... Bad file descriptor")."""
    with deferred_interrupts():
        processes = list((getattr(pool, "_processes", None) or {}).values())
        manager = getattr(pool, "_executor_manager_thread", None)
        pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            with contextlib.suppress(OSError, ValueError, AttributeError):
                process.terminate()
        deadline = time.monotonic() + grace_s
        for process in processes:
            with contextlib.suppress(OSError, ValueError, AttributeError, AssertionError):
                process.join(max(deadline - time.monotonic(), 0.0))
                if process.is_alive():
                    process.kill()
                    process.join(grace_s)
        if manager is not None:
            manager.join(grace_s)


@contextlib.contextmanager
def worker_pool(
    workers: int,
    *,
    initializer: Callable[..., Any] | None = None,
    initargs: tuple[Any, ...] = (),
    mp_context: Any = None,
    death_signal: bool | None = None,
) -> Iterator[WorkerPool]:
    """A process pool whose workers end with this process (module notes).

    Parameters
    ----------
    workers : int
        Number of worker processes, started at once.
    initializer, initargs
        Run in each worker after its start (a module-level function for spawned workers).
    mp_context : multiprocessing context, optional
        Start method (default: the platform's).
    death_signal : bool, optional
        Use ``PR_SET_PDEATHSIG`` (default: on Linux, when called from the main thread); the
        watchdog thread runs in any case.

    Yields
    ------
    WorkerPool
        Shut down (waiting for its tasks) when the block ends normally; stopped by
        :func:`stop_workers` when it ends with an exception, which then propagates.
    """
    if death_signal is None:
        death_signal = threading.current_thread() is threading.main_thread()
    context = mp_context or multiprocessing.get_context()
    pool = WorkerPool(
        workers,
        mp_context=context,
        initializer=_start_worker,
        initargs=(os.getpid(), bool(death_signal), initializer, tuple(initargs)),
    )
    try:
        _start_workers(pool, workers, context.get_start_method() == "fork")
        yield pool
    except BaseException:
        stop_workers(pool)
        raise
    pool.shutdown(wait=True)
