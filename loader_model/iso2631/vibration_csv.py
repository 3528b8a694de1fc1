"""Vibration records from CSV files: a header row, a ``time`` column in s and axis columns.

The file is streamed in blocks of :data:`CSV_BLOCK_ROWS` rows; each value is held once (a
10-million-row, four-column file evaluates in about 0.55 GB, ``tests/iso2631/test_large_csv.py``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from loader_model.io.files import iter_lines
from loader_model.iso2631.timeseries import (
    _ACCELERATION_REASON,
    AXES,
    MAX_ACCELERATION,
    VibrationRecord,
    axis_unit,
    check_axis_name,
)

__all__ = ["CSV_BLOCK_ROWS", "read_vibration_csv"]

#: Rows parsed at a time by :func:`read_vibration_csv`.
CSV_BLOCK_ROWS = 65536


def _header(lines: Iterator[str], name: str) -> list[str]:
    for line in lines:
        if line.strip() and not line.lstrip().startswith("#"):
            header = [column.strip() for column in line.split(",")]
            break
    else:
        raise ValueError(f"{name}: no header row; expected columns 'time' and some of {AXES}")
    if "" in header:
        raise ValueError(
            f"{name}: header column {header.index('') + 1} has no name; got header {header}"
        )
    duplicates = sorted({column for column in header if header.count(column) > 1})
    if duplicates:
        raise ValueError(f"{name}: duplicate column(s) {duplicates} in header {header}")
    if "time" not in header:
        raise ValueError(f"{name}: header must contain a 'time' column (s); got {header}")
    for column in header:
        if column != "time":
            check_axis_name(column, f"{name}: column name")
    if len(header) < 2:
        raise ValueError(f"{name}: header needs at least one axis column of {AXES}; got {header}")
    return header


def _bad_cell(name: str, header: list[str], line: str, number: int) -> ValueError:
    """The error for the first cell of data line ``number`` that is not a finite number."""
    cells = line.split(",")
    if len(cells) != len(header):
        return ValueError(
            f"{name}: line {number} has {len(cells)} values but the header has "
            f"{len(header)} columns {header}"
        )
    for column, cell in zip(header, cells, strict=True):
        try:
            value = float(cell)
        except ValueError:
            return ValueError(
                f"{name}: line {number}, column {column!r}: {cell.strip()!r} is not a number"
            )
        if not math.isfinite(value):
            return ValueError(
                f"{name}: column {column!r} must be finite; got {value} on line {number}"
            )
    return ValueError(f"{name}: line {number} could not be read as numbers: {line!r}")


def _parse_block(name: str, header: list[str], block: list[tuple[int, str]]) -> np.ndarray:
    try:
        data = np.loadtxt([line for _, line in block], delimiter=",", ndmin=2, dtype=float)
    except ValueError:
        data = None
    if data is None or data.shape[1] != len(header) or not np.all(np.isfinite(data)):
        for number, line in block:
            error = _bad_cell(name, header, line, number)
            if "could not be read" not in str(error):
                raise error
        raise _bad_cell(name, header, block[0][1], block[0][0])
    return data


def _check_magnitudes(name: str, header: list[str], data: np.ndarray, first_line: int) -> None:
    for index, column in enumerate(header):
        if column == "time":
            continue  # any origin (e.g. Unix time stamps): VibrationRecord checks the spacing
        bad = np.flatnonzero(np.abs(data[:, index]) > MAX_ACCELERATION)
        if bad.size:
            unit = axis_unit(column)
            raise ValueError(
                f"{name}: column {column!r} = {data[bad[0], index]:g} {unit} on data row "
                f"{first_line + bad[0]} is implausible; allowed: |value| <= "
                f"{MAX_ACCELERATION:g} {unit} ({_ACCELERATION_REASON})"
            )


def read_vibration_csv(path: str | Path) -> VibrationRecord:
    r"""Read a CSV file with a header row: a ``time`` column in s and axis columns (see :data:`AXES`).

    Lines starting with ``#`` and blank lines are skipped; the delimiter is a comma. The file
    must be UTF-8 text, with or without a byte-order mark, with ``\n`` or ``\r\n`` line
    endings (:func:`loader_model.io.files.iter_lines`). It is read in blocks of
    :data:`CSV_BLOCK_ROWS` rows and each value is held once, 8 bytes (no second copy while
    the record is assembled).
    Accelerations beyond :data:`MAX_ACCELERATION` are refused as implausible; the time column
    may have any origin (e.g. Unix time stamps), see :class:`VibrationRecord`.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.

    Returns
    -------
    VibrationRecord
        The validated record (see its checks).

    Raises
    ------
    ValueError
        Naming the file and, for a bad value, its line and column.
    """
    name = os.fspath(path) if isinstance(path, str | os.PathLike) else repr(path)
    lines = iter_lines(path, "vibration CSV file")
    header = _header(lines, name)
    store = _ColumnStore(len(header), _file_bytes(path))
    block: list[tuple[int, str]] = []
    for number, line in enumerate(lines, start=2):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        block.append((number, line))
        if len(block) == CSV_BLOCK_ROWS:
            _add_block(store, name, header, block)
            block = []
    if block:
        _add_block(store, name, header, block)
    if not store.rows:
        raise ValueError(f"{name}: no data rows below the header {header}")
    columns = dict(zip(header, store.columns(), strict=True))
    time_s = columns.pop("time")
    try:
        return VibrationRecord._adopt(time_s, columns)
    except ValueError as error:
        raise ValueError(f"{name}: {error}") from None


def _file_bytes(path: str | Path) -> int | None:
    try:
        return os.stat(path).st_size
    except (OSError, TypeError, ValueError):
        return None


class _ColumnStore:
    """The columns of a CSV file as they are read, one row of a (columns, capacity) array each.

    The capacity is estimated from the file's size and the first block's bytes per row, with a
    margin, so the file's values are held once (pages beyond the rows read are never touched,
    so they take no memory); if the estimate is passed the array grows by half.
    """

    def __init__(self, column_count: int, file_bytes: int | None) -> None:
        self.file_bytes = file_bytes
        self.data = np.empty((column_count, 0))
        self.rows = 0

    def add(self, values: np.ndarray, text_bytes: int) -> None:
        """Append ``values`` (rows, columns) parsed from ``text_bytes`` bytes of the file."""
        needed = self.rows + values.shape[0]
        if needed > self.data.shape[1]:
            estimate = 0
            if self.file_bytes and not self.rows:
                estimate = int(1.05 * self.file_bytes * values.shape[0] / max(text_bytes, 1))
            capacity = max(needed + CSV_BLOCK_ROWS, estimate, int(1.5 * self.data.shape[1]))
            grown = np.empty((self.data.shape[0], capacity))
            grown[:, : self.rows] = self.data[:, : self.rows]
            self.data = grown
        self.data[:, self.rows : needed] = values.T
        self.rows = needed

    def columns(self) -> list[np.ndarray]:
        """The columns read, views of the store's rows."""
        return list(self.data[:, : self.rows])


def _add_block(
    store: _ColumnStore, name: str, header: list[str], block: list[tuple[int, str]]
) -> None:
    data = _parse_block(name, header, block)
    _check_magnitudes(name, header, data, store.rows + 1)
    store.add(data, sum(len(line) + 1 for _, line in block))
