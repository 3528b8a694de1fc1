"""Worker processes that end with their parent, and interrupts that end a command cleanly.

:func:`worker_pool` is a :class:`~concurrent.futures.ProcessPoolExecutor` whose workers

- ignore SIGINT, so that Ctrl-C (sent by the terminal to the whole process group) reaches only
  the parent, which reports it in one line, and SIGTERM kills them (its default);
- end when the parent ends, however it ends, SIGKILL included: on Linux the kernel sends them
  SIGKILL when the parent dies (``prctl(PR_SET_PDEATHSIG)``, set when the pool is made in the main
  thread: the signal follows the thread that started the worker); everywhere a watchdog thread
  polls ``os.getppid()`` every :data:`WATCHDOG_POLL_S` and ends the worker once it changes (it runs
  whenever the worker's simulation releases the GIL);
- are stopped at once when the ``with`` block ends with an exception (an interrupt or an error):
  queued tasks are cancelled and running workers terminated, not waited for.

:class:`Interrupted` is the :class:`KeyboardInterrupt` a command raises with what it kept (e.g.
"the finished batches are saved"); :func:`sigterm_interrupts` turns SIGTERM into one for the
duration of a command, so that ``kill`` ends it like Ctrl-C. The command line
(:func:`loader_model.cli.main`) prints :func:`interrupt_message` and exits with 128 + the signal's
number (130 for SIGINT, 143 for SIGTERM), as shells do.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import Any

__all__ = [
    "WATCHDOG_POLL_S",
    "Interrupted",
    "files_note",
    "interrupt_message",
    "interrupted",
    "sigterm_interrupts",
    "stop_workers",
    "worker_pool",
]

#: Interval in s at which a worker's watchdog checks that its parent still runs.
WATCHDOG_POLL_S = 0.2
_PR_SET_PDEATHSIG = 1


class Interrupted(KeyboardInterrupt):
    """An interrupt by ``signal_number`` (SIGINT or SIGTERM); ``kept`` says what the
    interrupted command left in place, for the user (empty: nothing to say)."""

    def __init__(self, signal_number: int = signal.SIGINT, kept: str = "") -> None:
        super().__init__(signal_number, kept)
        self.signal_number = int(signal_number)
        self.kept = kept


def interrupted(error: KeyboardInterrupt, kept: str) -> Interrupted:
    """The interrupt ``error`` (of whichever signal) with ``kept`` as what was kept."""
    return Interrupted(getattr(error, "signal_number", signal.SIGINT), kept)


def files_note(wanted: Sequence[str | None], written: Sequence[str]) -> str:
    """What an interrupted command kept of the files ``wanted`` (None: not asked for), given
    those ``written``: ``"wrote 'a'; nothing written to 'b'"``."""
    missing = [repr(path) for path in wanted if path is not None and path not in written]
    parts = [f"wrote {', '.join(map(repr, written))}"] if written else []
    parts += [f"nothing written to {', '.join(missing)}"] if missing else []
    return "; ".join(parts) or "nothing written"


def interrupt_message(error: KeyboardInterrupt) -> tuple[str, int]:
    """One line for the user and the exit code (128 + signal number) of an interrupt."""
    number = int(getattr(error, "signal_number", signal.SIGINT))
    kept = getattr(error, "kept", "") or "no partial file was left"
    what = "interrupted" if number == signal.SIGINT else f"stopped by {signal.Signals(number).name}"
    return f"{what}; {kept}", 128 + number


@contextlib.contextmanager
def sigterm_interrupts() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Interrupted` in the main thread (elsewhere, or
    where signals cannot be handled, nothing changes); the previous handler is restored."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(number: int, frame: Any) -> None:
        raise Interrupted(number)

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


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
    if death_signal:
        _set_parent_death_signal()
    if os.getppid() != parent_pid:  # the parent died before the death signal was set
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent_pid,), name="watchdog", daemon=True).start()
    if initializer is not None:
        initializer(*initargs)


def stop_workers(pool: ProcessPoolExecutor, grace_s: float = 2.0) -> None:
    """Cancel the queued tasks of ``pool`` and end its workers: SIGTERM, then SIGKILL for any
    still running after ``grace_s``; returns once they have ended."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
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


@contextlib.contextmanager
def worker_pool(
    workers: int,
    *,
    initializer: Callable[..., Any] | None = None,
    initargs: tuple[Any, ...] = (),
    mp_context: Any = None,
    death_signal: bool | None = None,
) -> Iterator[ProcessPoolExecutor]:
    """A process pool whose workers end with this process (module notes).

    Parameters
    ----------
    workers : int
        Number of worker processes.
    initializer, initargs
        Run in each worker after its start (a module-level function for spawned workers).
    mp_context : multiprocessing context, optional
        Start method (default: the platform's).
    death_signal : bool, optional
        Use ``PR_SET_PDEATHSIG`` (default: on Linux, when called from the main thread); the
        watchdog thread runs in any case.

    Yields
    ------
    concurrent.futures.ProcessPoolExecutor
        Shut down (waiting for its tasks) when the block ends normally; stopped by
        :func:`stop_workers` when it ends with an exception, which then propagates.
    """
    if death_signal is None:
        death_signal = threading.current_thread() is threading.main_thread()
    pool = ProcessPoolExecutor(
        workers,
        mp_context=mp_context,
        initializer=_start_worker,
        initargs=(os.getpid(), bool(death_signal), initializer, tuple(initargs)),
    )
    try:
        yield pool
    except BaseException:
        stop_workers(pool)
        raise
    pool.shutdown(wait=True)
