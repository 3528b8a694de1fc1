"""The one way in for user files: a readable regular file of UTF-8 text, named in every error.

:func:`check_readable_file` checks that a path exists, is a regular file (not a folder, a named
pipe or a device, which would block or fail later) and is readable. :func:`read_text` reads it as
UTF-8 with or without a byte-order mark; :func:`open_text` streams it line by line. Every
failure is a :class:`ValueError` whose message starts with the file's name and what it was for.
"""

from __future__ import annotations

import codecs
import os
import stat
from collections.abc import Iterator
from pathlib import Path

__all__ = ["check_readable_file", "iter_lines", "read_text"]


def check_readable_file(path: str | os.PathLike[str], what: str = "input file") -> Path:
    """Return ``path`` as a :class:`~pathlib.Path` if it is a readable regular file.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    what : str
        What the file is for, used in messages (``"loader parameter file"``).

    Raises
    ------
    ValueError
        If the path is empty, does not exist, is not a regular file or cannot be read.
    """
    if not isinstance(path, str | os.PathLike):
        raise ValueError(f"{what} must be a path; got {path!r}")
    text = os.fspath(path)
    if not isinstance(text, str) or not text:
        raise ValueError(f"{what} must be a non-empty path; got {path!r}")
    try:
        mode = os.stat(text).st_mode
    except FileNotFoundError:
        raise ValueError(f"{what} {text!r} does not exist") from None
    except (OSError, ValueError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise ValueError(f"{what} {text!r} cannot be read: {reason}") from None
    if stat.S_ISDIR(mode):
        raise ValueError(f"{what} {text!r} is a folder, not a file")
    if not stat.S_ISREG(mode):
        raise ValueError(f"{what} {text!r} is not a regular file (a pipe, socket or device)")
    if not os.access(text, os.R_OK):
        raise ValueError(f"{what} {text!r} cannot be read: permission denied")
    return Path(text)


def _decode_error(path: Path, what: str, error: UnicodeDecodeError, offset: int) -> ValueError:
    return ValueError(
        f"{what} {str(path)!r} is not UTF-8 text: byte 0x{error.object[error.start]:02x} at "
        f"offset {offset + error.start} cannot be decoded (save it as UTF-8)"
    )


def read_text(path: str | os.PathLike[str], what: str = "input file") -> str:
    """Return the text of a readable UTF-8 file (a leading byte-order mark is dropped).

    Line endings are kept as they are (TOML and CSV parsers accept ``\\r\\n``).

    Raises
    ------
    ValueError
        See :func:`check_readable_file`; also if the bytes are not UTF-8.
    """
    checked = check_readable_file(path, what)
    try:
        data = checked.read_bytes()
    except OSError as error:
        raise ValueError(f"{what} {str(checked)!r} cannot be read: {error.strerror}") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise _decode_error(checked, what, error, 0) from None


def iter_lines(
    path: str | os.PathLike[str], what: str = "input file", chunk_bytes: int = 1 << 20
) -> Iterator[str]:
    """Yield the lines of a readable UTF-8 file without their line endings, streaming.

    Memory stays at about ``chunk_bytes`` whatever the file's size. A leading byte-order mark is
    dropped; ``\\n``, ``\\r\\n`` and ``\\r`` all end a line.

    Raises
    ------
    ValueError
        See :func:`read_text`; raised when the offending part of the file is reached.
    """
    checked = check_readable_file(path, what)
    decoder = codecs.getincrementaldecoder("utf-8-sig")()
    offset, rest = 0, ""
    try:
        with open(checked, "rb") as stream:
            while True:
                block = stream.read(chunk_bytes)
                try:
                    text = decoder.decode(block, final=not block)
                except UnicodeDecodeError as error:
                    raise _decode_error(checked, what, error, offset) from None
                offset += len(block)
                lines = (rest + text).splitlines(keepends=True)
                rest = lines.pop() if lines and block and not lines[-1].endswith("\n") else ""
                for line in lines:
                    yield line.rstrip("\r\n")
                if not block:
                    if rest:
                        yield rest.rstrip("\r\n")
                    return
    except OSError as error:
        raise ValueError(f"{what} {str(checked)!r} cannot be read: {error.strerror}") from None
