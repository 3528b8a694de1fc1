"""Shared fixtures of the interrupt tests."""

from __future__ import annotations

import signal
from collections.abc import Iterator

import pytest


@pytest.fixture
def python_sigint() -> Iterator[None]:
    """SIGINT as a fresh Python process has it (the default handler, not blocked in this thread)
    for the test's duration, whatever an earlier test in the same worker left; restored after.
    A fresh clone's fast suite saw an xdist worker reach these tests with SIGINT no longer
    raising KeyboardInterrupt (not reproduced alone); the tests check the deferral, not that."""
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    mask = signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        signal.signal(signal.SIGINT, handler)
