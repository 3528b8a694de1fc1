"""Write results atomically: a failed command leaves no partial file behind."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np

__all__ = ["save_arrays", "write_atomically"]

_FORMATS = (".npz", ".mat")


def write_atomically(path: str | Path, write: Callable[[Path], None]) -> Path:
    """Call ``write(temporary_path)`` and move the result to ``path`` only if it succeeded."""
    path = Path(path)
    if not path.parent.is_dir():
        raise ValueError(f"output folder {str(path.parent)!r} does not exist")
    handle, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.name}.", suffix=path.suffix
    )
    os.close(handle)
    try:
        write(Path(temporary))
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)
    return path


def save_arrays(path: str | Path, arrays: Mapping[str, np.ndarray | list[str]]) -> Path:
    """Save named arrays as ``.npz`` (NumPy) or ``.mat`` (MATLAB, via SciPy), atomically."""
    suffix = Path(path).suffix.lower()
    if suffix not in _FORMATS:
        raise ValueError(
            f"export file {str(path)!r} has suffix {suffix!r}; allowed: {list(_FORMATS)}"
        )

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

    return write_atomically(path, write)
