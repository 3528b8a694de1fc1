"""Interrupts that end a command cleanly: Ctrl-C (SIGINT) and SIGTERM as one line for the user.

Within :func:`command_interrupts` (the run of a command, :func:`loader_model.cli.main`), SIGINT and
SIGTERM raise :class:`Interrupted`, a :class:`KeyboardInterrupt`, and are remembered: library code
may catch the exception (CasADi's integrators turn a KeyboardInterrupt in their right-hand side
into a RuntimeError "CV_RHSFUNC_FAIL"), so :func:`check_interrupt` raises it again where results
are collected or written, and :func:`keeping` turns any exception raised after an interrupt into
the interrupt, with what the command kept. A signal that comes while an interrupt is being
handled (a second Ctrl-C during the clean-up) is remembered, not raised; one raised in a
finaliser, which Python drops, is raised again right after. The command line prints
:func:`interrupt_message` and exits with 128 + the signal's number (130 for SIGINT, 143 for
SIGTERM), as shells do.

An interrupt is raised between any two bytecodes, also just after code of the standard library
took a lock and before it could arrange to release it; a lock of a process pool's queues left
held that way blocks the pool's thread and with it the exit of the program (seen twice in 31
Ctrl-C sent 0 to 0.3 s after a ``robustness`` run's pool started, while it submitted 5000
tasks). :func:`deferred_interrupts` holds SIGINT and SIGTERM back over such calls and lets them
act right after.
"""

from __future__ import annotations

import _thread
import contextlib
import signal
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import Any

__all__ = [
    "Interrupted",
    "check_interrupt",
    "command_interrupts",
    "deferred_interrupts",
    "files_note",
    "interrupt_message",
    "keeping",
    "requested",
]

_STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
#: Signals received within :func:`command_interrupts`, first first.
_REQUESTED: list[int] = []


class Interrupted(KeyboardInterrupt):
    """An interrupt by ``signal_number`` (SIGINT or SIGTERM); ``kept`` says what the
    interrupted command left in place, for the user (empty: nothing to say)."""

    def __init__(self, signal_number: int = signal.SIGINT, kept: str = "") -> None:
        super().__init__(signal_number, kept)
        self.signal_number = int(signal_number)
        self.kept = kept


def requested() -> int | None:
    """The first SIGINT or SIGTERM received within :func:`command_interrupts`, if any."""
    return _REQUESTED[0] if _REQUESTED else None


def check_interrupt() -> None:
    """Raise :class:`Interrupted` if an interrupt came within :func:`command_interrupts` (also
    one that library code caught); call it before collecting or writing results."""
    if _REQUESTED:
        raise Interrupted(_REQUESTED[0])


@contextlib.contextmanager
def keeping(kept: Callable[[], str]) -> Iterator[None]:
    """An interrupt out of the block, or any exception after one was requested (module notes),
    leaves it as :class:`Interrupted` with ``kept()``: what the command kept."""
    try:
        yield
    except BaseException as error:
        if isinstance(error, KeyboardInterrupt):
            number: int | None = getattr(error, "signal_number", signal.SIGINT)
        else:
            number = requested()
        if number is None:
            raise
        raise Interrupted(number, kept()) from None


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


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def _handling_interrupt() -> bool:
    return isinstance(sys.exc_info()[1], KeyboardInterrupt)


@contextlib.contextmanager
def command_interrupts() -> Iterator[None]:
    """Within the block, SIGINT and SIGTERM raise :class:`Interrupted` in the main thread and are
    remembered (module notes); elsewhere nothing changes. The previous handlers are restored."""
    if not _main_thread():
        yield
        return

    def handler(number: int, frame: Any) -> None:
        _REQUESTED.append(number)
        if not _handling_interrupt():
            raise Interrupted(number)

    def unraisable(info: Any) -> None:
        """An interrupt raised in a finaliser or weakref callback is dropped by Python (with
        "Exception ignored in ..."): quietly raise it again once this hook has returned (a
        signal tripped in here would be handled in here)."""
        if isinstance(info.exc_value, Interrupted):
            timer = threading.Timer(0.01, _thread.interrupt_main, (info.exc_value.signal_number,))
            timer.daemon = True
            timer.start()
        else:
            hook(info)

    previous = {n: signal.getsignal(n) for n in _STOP_SIGNALS}
    hook, sys.unraisablehook = sys.unraisablehook, unraisable
    _REQUESTED.clear()
    try:
        for number in _STOP_SIGNALS:
            signal.signal(number, handler)
        yield
    finally:
        for number, handler_before in previous.items():
            signal.signal(number, signal.SIG_DFL if handler_before is None else handler_before)
        sys.unraisablehook = hook
        _REQUESTED.clear()


@contextlib.contextmanager
def deferred_interrupts() -> Iterator[None]:
    """SIGINT and SIGTERM arriving within the block act when it ends, through the handlers of
    before (re-raised); in the main thread only, where Python runs signal handlers."""
    if not _main_thread():
        yield
        return
    caught: list[int] = []

    def hold(number: int, frame: Any) -> None:
        caught.append(number)

    previous = {n: signal.getsignal(n) for n in _STOP_SIGNALS}
    held = [n for n, handler in previous.items() if handler is not None]  # None: set from C
    try:
        for number in held:
            signal.signal(number, hold)
        yield
    finally:
        for number in held:
            signal.signal(number, previous[number])
        for number in dict.fromkeys(caught):
            signal.raise_signal(number)
