"""Road profiles from and to CSV files: two columns, distance and height, with units in the header.

Format::

    # optional comment lines start with '#'
    distance [m],height [mm]
    0.0,0.0
    0.5,1.2
    ...

The header names the columns ``distance`` and ``height``, each with a unit in square brackets:
``m``, ``cm`` or ``mm``. Values are converted to m. Distances must be strictly increasing (a
vertical edge is a steep segment in a file) and every value finite; at least two rows. Every
mistake raises :class:`RoadFileError` (a ValueError) naming the file, row, column and value; row
numbers count lines of the file from 1.
"""

from __future__ import annotations

import csv
import math
import os
import tempfile
from pathlib import Path

import numpy as np

from loader_model.simulation.roads import RoadProfile

__all__ = ["LENGTH_UNITS_M", "RoadFileError", "read_road_csv", "write_road_csv"]

#: Accepted length units and their size in m.
LENGTH_UNITS_M = {"m": 1.0, "cm": 0.01, "mm": 0.001}
_COLUMNS = ("distance", "height")


class RoadFileError(ValueError):
    """A road CSV file that cannot be read; the message names file, row, column and value."""


def _parse_header(cells: list[str], where: str) -> tuple[float, float]:
    expected = "'distance [m]', 'height [m]' (units m, cm or mm)"
    if len(cells) != 2:
        raise RoadFileError(f"{where}: header must have 2 columns {expected}; got {cells!r}")
    scales = []
    for cell, column in zip(cells, _COLUMNS, strict=True):
        text = cell.strip()
        name, _, rest = text.partition("[")
        unit = rest[:-1].strip() if rest.endswith("]") else None
        if name.strip().lower() != column:
            raise RoadFileError(f"{where}: header column {column!r} expected; got {text!r}")
        if unit is None:
            raise RoadFileError(
                f"{where}: header column {text!r} needs a unit in brackets, e.g. '{column} [m]'"
            )
        if unit not in LENGTH_UNITS_M:
            raise RoadFileError(
                f"{where}: unit {unit!r} of column {column!r} must be one of "
                f"{tuple(LENGTH_UNITS_M)}"
            )
        scales.append(LENGTH_UNITS_M[unit])
    return scales[0], scales[1]


def read_road_csv(path: str | Path, *, name: str | None = None) -> RoadProfile:
    """Read a road profile from ``path`` (format in the module notes).

    Parameters
    ----------
    path : str or pathlib.Path
        CSV file.
    name : str, optional
        Profile label; default the file name.

    Returns
    -------
    RoadProfile
        Distances and heights in m.

    Raises
    ------
    RoadFileError
        On any unreadable file or bad content, with file, row, column and value.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise RoadFileError(f"road file not found: {str(path)!r}") from None
    except (OSError, UnicodeDecodeError) as error:
        raise RoadFileError(f"cannot read road file {str(path)!r}: {error}") from None
    scales: tuple[float, float] | None = None
    columns: list[str] = []
    distance: list[float] = []
    height: list[float] = []
    for row_number, cells in enumerate(csv.reader(text.splitlines()), start=1):
        where = f"{path.name}, row {row_number}"
        if not cells or not "".join(cells).strip() or cells[0].lstrip().startswith("#"):
            continue
        if scales is None:
            scales = _parse_header(cells, where)
            columns = [cell.strip() for cell in cells]
            continue
        if len(cells) != 2:
            raise RoadFileError(f"{where}: expected 2 values ({', '.join(columns)}); got {cells!r}")
        values = []
        for cell, column, scale in zip(cells, columns, scales, strict=True):
            try:
                value = float(cell)
            except ValueError:
                raise RoadFileError(
                    f"{where}, column {column!r}: {cell.strip()!r} is not a number"
                ) from None
            if not math.isfinite(value):
                raise RoadFileError(f"{where}, column {column!r}: {cell.strip()!r} is not finite")
            values.append(value * scale)
        if distance and values[0] <= distance[-1]:
            raise RoadFileError(
                f"{where}, column {columns[0]!r}: distance must increase; got "
                f"{cells[0].strip()!r} after {distance[-1] / scales[0]:.9g}"
            )
        distance.append(values[0])
        height.append(values[1])
    if scales is None:
        raise RoadFileError(
            f"{path.name}: no header; the first line must be 'distance [m],height [m]'"
        )
    if len(distance) < 2:
        raise RoadFileError(f"{path.name}: at least 2 data rows needed; got {len(distance)}")
    return RoadProfile(np.array(distance), np.array(height), name=name or path.name)


def write_road_csv(profile: RoadProfile, path: str | Path) -> Path:
    """Write ``profile`` to ``path`` in m (atomically); vertical edges are refused by the format.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    if not isinstance(profile, RoadProfile):
        raise ValueError(f"profile must be a RoadProfile; got {type(profile).__name__}")
    if np.any(np.diff(profile.distance_m) <= 0.0):
        raise ValueError(
            "profile has a vertical edge (repeated distance), which a road CSV cannot hold"
        )
    path = Path(path)
    if not path.parent.is_dir():
        raise ValueError(f"road file folder does not exist: {str(path.parent)!r}")
    lines = [f"# {profile.name}", "distance [m],height [m]"]
    lines += [
        f"{s!r},{h!r}"
        for s, h in zip(profile.distance_m.tolist(), profile.height_m.tolist(), strict=True)
    ]
    handle, temporary = tempfile.mkstemp(suffix=".csv", dir=path.parent, prefix=".tmp-")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write("\n".join(lines) + "\n")
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path
