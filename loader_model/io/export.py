"""The one way out for results: checked output paths and atomic writes.

:func:`check_output_path` refuses, before any work is done, an empty path, a suffix the writer
cannot write (naming the allowed ones), a folder, a pipe or device, a missing folder and a
location the user cannot write. :func:`write_atomically` writes into a temporary file beside the
target and renames it over the target only when the write succeeded, so a failed command never
leaves a partial file nor damages a good one. A new file gets the permissions the user's umask
gives (``0o666 & ~umask``, as ``open()`` would); an overwritten file keeps its permissions. The
temporary file is named after its process (:mod:`loader_model.io.staging`), so that the next write of
the same target removes one a killed run left behind.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import numpy as np

from loader_model.io import staging
from loader_model.io.interrupts import check_interrupt

__all__ = ["ARRAY_SUFFIXES", "check_output_path", "save_arrays", "write_atomically"]

#: Suffixes :func:`save_arrays` writes: NumPy ``.npz`` and MATLAB ``.mat``.
ARRAY_SUFFIXES = (".npz", ".mat")


def check_output_path(
    path: str | os.PathLike[str], suffixes: Sequence[str], what: str = "output file"
) -> Path:
    """Return ``path`` as a Path if a file with one of ``suffixes`` can be written there.

    Raises
    ------
    ValueError
        Naming the path and what is wrong with it.
    """
    if not isinstance(path, str | os.PathLike) or not os.fspath(path):
        raise ValueError(
            f"{what} must be a non-empty path ending in one of {list(suffixes)}; got {path!r}"
        )
    target = Path(os.fspath(path))
    name = str(target)
    if target.suffix.lower() not in suffixes:
        raise ValueError(
            f"{what} {name!r} has suffix {target.suffix.lower()!r}; allowed: {list(suffixes)}"
        )
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    except (OSError, ValueError) as error:  # ValueError: a NUL byte in the path
        reason = getattr(error, "strerror", None) or str(error)
        raise ValueError(f"{what} {name!r} cannot be written: {reason}") from None
    if mode is not None and stat.S_ISDIR(mode):
        raise ValueError(f"{what} {name!r} is a folder; give a file name")
    if mode is not None and not stat.S_ISREG(mode):
        raise ValueError(f"{what} {name!r} exists and is not a regular file (a pipe or device)")
    folder = target.parent
    if not folder.is_dir():
        raise ValueError(f"output folder {str(folder)!r} of {what} {name!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{what} {name!r} cannot be written: no permission in {str(folder)!r}")
    if mode is not None and not os.access(target, os.W_OK):
        raise ValueError(f"{what} {name!r} exists and is read-only")
    return target


def write_atomically(
    path: str | os.PathLike[str],
    write: Callable[[Path], None],
    suffixes: Sequence[str],
    what: str = "output file",
    *,
    remove_stale: bool = True,
) -> Path:
    """Call ``write(temporary_path)`` and rename the result to ``path`` only if it succeeded.

    Parameters
    ----------
    path : str or os.PathLike
        Target file, checked by :func:`check_output_path`.
    write : callable
        Writes the complete file to the path it is given.
    suffixes : sequence of str
        Suffixes the caller can write (lower case, with the dot).
    what : str
        What the file is, for messages.
    remove_stale : bool
        First remove the temporary files of ``path`` that killed runs left
        (:func:`loader_model.io.staging.remove_stale`; it lists the folder: a caller writing many
        files into one folder removes them once instead).

    Raises
    ------
    ValueError
        From :func:`check_output_path`, or if the write fails with an OSError (disk full, ...);
        the target is then untouched and no temporary file is left.
    """
    target = check_output_path(path, suffixes, what)
    if remove_stale:
        staging.remove_stale(target.parent, target.name)
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        mode = 0o666 & ~staging.current_umask()
    try:
        handle, temporary = staging.make_staging_file(target)
    except OSError as error:
        raise ValueError(f"{what} {str(target)!r} cannot be written: {error.strerror}") from None
    os.close(handle)
    try:
        write(Path(temporary))
        os.chmod(temporary, mode)
        check_interrupt()  # after an interrupt (caught by code in between) nothing is written
        os.replace(temporary, target)
    except OSError as error:
        raise ValueError(
            f"{what} {str(target)!r} could not be written: {error.strerror or error}; "
            "nothing was written"
        ) from None
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)
    return target


def save_arrays(path: str | Path, arrays: Mapping[str, np.ndarray | list[str]]) -> Path:
    """Save named arrays as ``.npz`` (NumPy) or ``.mat`` (MATLAB, via SciPy), atomically."""
    suffix = Path(path).suffix.lower() if isinstance(path, str | os.PathLike) else ""

    def write(temporary: Path) -> None:
        if suffix == ".npz":
            with open(temporary, "wb") as stream:
                np.savez(stream, **{k: np.asarray(v) for k, v in arrays.items()})
        else:
            from scipy.io import savemat

            savemat(
                temporary,
                {
                    k: np.asarray(v, dtype=object if isinstance(v, list) else None)
                    for k, v in arrays.items()
                },
            )

    return write_atomically(path, write, ARRAY_SUFFIXES, "export file")
