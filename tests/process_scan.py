"""Linux /proc helpers of the interrupt tests: the processes of a process group, whether one runs
and whether it ignores SIGINT (read from ``/proc/PID/status``), and waiting for a condition."""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Callable
from pathlib import Path

__all__ = ["command_line", "group_members", "ignores_sigint", "running", "wait_until"]


def _stat_fields(pid: int) -> list[str] | None:
    """Fields after the command name of ``/proc/PID/stat`` (state first), None if gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text(encoding="ascii", errors="replace")
    except OSError:
        return None
    return text.rsplit(")", 1)[1].split()


def running(pid: int) -> bool:
    """Whether ``pid`` is a process that has not ended (a zombie has ended)."""
    fields = _stat_fields(pid)
    return fields is not None and fields[0] != "Z"


def group_members(pgid: int) -> list[int]:
    """Running processes of process group ``pgid`` other than its leader."""
    members = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == pgid:
            continue
        fields = _stat_fields(int(entry))
        if fields is not None and fields[0] != "Z" and int(fields[2]) == pgid:
            members.append(int(entry))
    return members


def ignores_sigint(pid: int) -> bool:
    """Whether ``pid`` ignores SIGINT (bit of ``SigIgn`` in ``/proc/PID/status``)."""
    try:
        lines = Path(f"/proc/{pid}/status").read_text(encoding="ascii").splitlines()
    except OSError:
        return False
    mask = next((int(line.split()[1], 16) for line in lines if line.startswith("SigIgn:")), 0)
    return bool(mask & (1 << (signal.SIGINT - 1)))


def command_line(pid: int) -> str:
    """The command line of ``pid`` (empty if gone)."""
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    except OSError:
        return ""


def wait_until(condition: Callable[[], object], bound_s: float, what: str) -> object:
    """Poll ``condition`` every 50 ms until it is truthy and return its value; fail with
    ``what`` after ``bound_s`` (a bound against hanging, not a measurement)."""
    deadline = time.monotonic() + bound_s
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"not within {bound_s:g} s: {what}")
        time.sleep(0.05)
