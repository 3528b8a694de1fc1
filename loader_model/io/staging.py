"""Staging entries beside an output: their names, their permissions, and the removal of those a
killed run left behind.

A command writes a result ``NAME`` into a staging file or folder beside it and renames it into
place when complete (:func:`loader_model.io.export.write_atomically`,
:func:`loader_model.experiments.report.write_report`). A run killed with SIGKILL cannot remove its
staging entry, so the entry carries its owner: ``.NAME.tmp-HOST-PID-TOKEN[SUFFIX]`` (``tmp``: being
built; ``old``: a replaced report on its way out), with HOST the first 8 hex digits of the SHA-256
of the host name, PID the writing process and TOKEN 8 random characters. An entry is *stale* when
this host made it and its process no longer runs (or is a zombie); :func:`remove_stale` removes
those and nothing else: never the entry of a running process (a concurrent run, whatever its
age), nor one made on another host sharing the folder (whose processes this host cannot see). A
reused PID keeps a stale entry until that process ends, which errs on the safe side.

Folders and files get the permissions the user's umask gives (``0o777 & ~umask``,
``0o666 & ~umask``), as ``mkdir`` and ``open`` would; :func:`current_umask` reads the umask
without changing it where the system allows (``/proc/self/status`` on Linux).
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import re
import shutil
import socket
import tempfile
from pathlib import Path

__all__ = [
    "current_umask",
    "is_stale",
    "make_staging_file",
    "make_staging_folder",
    "remove_stale",
    "staging_prefix",
]

_KINDS = ("tmp", "old")
#: ``.NAME.KIND-HOST-PID-TOKEN[SUFFIX]``, NAME filled in by :func:`is_stale`.
_PATTERN = (
    r"\.(?P<name>{name})\.(?:tmp|old)-(?P<host>[0-9a-f]{{8}})-(?P<pid>[0-9]{{1,10}})"
    r"-[a-z0-9_]{{8}}(?:\.[^.]+)?"
)


def _host_tag() -> str:
    return hashlib.sha256(socket.gethostname().encode()).hexdigest()[:8]


def staging_prefix(name: str, kind: str = "tmp") -> str:
    """The start of a staging entry's name for the result ``name`` (module notes).

    Parameters
    ----------
    name : str
        File or folder name of the result (no folder part).
    kind : str
        ``"tmp"`` (being built) or ``"old"`` (a replaced result being removed).

    Returns
    -------
    str
        ``.NAME.KIND-HOST-PID-``; 8 random characters (and the suffix) complete it.
    """
    if kind not in _KINDS:
        raise ValueError(f"kind must be one of {list(_KINDS)}; got {kind!r}")
    return f".{name}.{kind}-{_host_tag()}-{os.getpid()}-"


def current_umask() -> int:
    """The process's umask; read from ``/proc/self/status`` where it exists (thread-safe),
    else set and restored at once."""
    with contextlib.suppress(OSError, ValueError):
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def make_staging_folder(destination: str | os.PathLike[str]) -> Path:
    """Create an empty staging folder beside ``destination`` with the umask's permissions.

    Returns
    -------
    pathlib.Path
        ``.NAME.tmp-HOST-PID-TOKEN`` in the destination's parent, mode ``0o777 & ~umask``.
    """
    destination = Path(destination)
    folder = Path(tempfile.mkdtemp(prefix=staging_prefix(destination.name), dir=destination.parent))
    try:
        os.chmod(folder, 0o777 & ~current_umask())
    except BaseException:
        folder.rmdir()
        raise
    return folder


def make_staging_file(target: str | os.PathLike[str]) -> tuple[int, Path]:
    """Create an empty staging file beside ``target`` (mode 0600 until the caller sets it).

    Returns
    -------
    tuple of (int, pathlib.Path)
        The open descriptor and the path ``.NAME.tmp-HOST-PID-TOKEN.SUFFIX``.
    """
    target = Path(target)
    handle, path = tempfile.mkstemp(
        prefix=staging_prefix(target.name), suffix=target.suffix, dir=target.parent
    )
    return handle, Path(path)


def _owner_gone(pid: int) -> bool:
    if pid <= 0 or pid == os.getpid():
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except (OSError, OverflowError):  # PermissionError: another user's live process
        return False
    with contextlib.suppress(OSError, IndexError):  # a zombie has ended: it only waits to be reaped
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] == "Z"
    return False


def is_stale(entry_name: str, name: str | None = None) -> bool:
    """Whether ``entry_name`` is a staging entry (of result ``name``, or of any result when
    ``None``) that a process of this host left behind and that no longer runs."""
    pattern = _PATTERN.format(name=".+" if name is None else re.escape(name))
    match = re.fullmatch(pattern, entry_name)
    if match is None or match["host"] != _host_tag():
        return False
    return _owner_gone(int(match["pid"]))


def remove_stale(folder: str | os.PathLike[str], name: str | None = None) -> list[Path]:
    """Remove the stale staging entries in ``folder`` (module notes); never follow a link.

    Parameters
    ----------
    folder : str or os.PathLike
        Folder holding the results (a missing or unreadable folder has nothing to remove).
    name : str, optional
        Only the staging entries of this result; default: of every result.

    Returns
    -------
    list of pathlib.Path
        The entries removed (one that vanished meanwhile, or cannot be removed, is left out).
    """
    start = "." if name is None else f".{name}."
    removed = []
    try:
        entries = [e for e in os.scandir(folder) if e.name.startswith(start)]
    except OSError:
        return []
    for entry in entries:
        if not is_stale(entry.name, name):
            continue
        try:
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)
        except OSError:
            continue
        removed.append(Path(entry.path))
    return removed
