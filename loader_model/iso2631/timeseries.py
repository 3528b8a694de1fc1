"""Labelled multi-axis acceleration records: a time vector and named axis columns, CSV input.

Axis names follow ISO 2631-1 Figure 1 for a seated person: translations ``x`` (fore-aft), ``y``
(lateral), ``z`` (vertical) in m/s² and rotations ``roll`` (about x), ``pitch`` (about y), ``yaw``
(about z) in rad/s². The paper measures x, y, z at the seat and estimates the pitch (section 5.3).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import numpy as np

from loader_model.io.files import iter_lines
from loader_model.iso2631._checks import as_signal

__all__ = [
    "AXES",
    "CSV_BLOCK_ROWS",
    "MAX_ACCELERATION",
    "ROTATIONAL_AXES",
    "TIME_JITTER_TOLERANCE",
    "VibrationRecord",
    "axis_unit",
    "check_axis_name",
    "read_vibration_csv",
]

#: Accepted axis names (ISO 2631-1 Figure 1, seated person).
AXES = ("x", "y", "z", "roll", "pitch", "yaw")
#: Axes measured as angular acceleration in rad/s².
ROTATIONAL_AXES = frozenset({"roll", "pitch", "yaw"})
#: Largest accepted deviation of a sampling interval from the mean interval, as a fraction of it
#: (times rounded when written to CSV stay well inside it). The float64 resolution of the time
#: values is allowed for on top (see :class:`VibrationRecord`).
TIME_JITTER_TOLERANCE = 0.01
#: Largest plausible |acceleration| in m/s² or rad/s² (about 200 g).
MAX_ACCELERATION = 2000.0
#: Rows parsed at a time by :func:`read_vibration_csv`.
CSV_BLOCK_ROWS = 65536
_ACCELERATION_REASON = (
    "about 200 g; whole-body vibration stays below 10 g and shocks on a seat below 50 g"
)


def check_axis_name(axis: object, what: str = "axis") -> str:
    """Return ``axis`` if it is one of :data:`AXES`, else raise ValueError naming ``what``."""
    if not isinstance(axis, str) or axis not in AXES:
        raise ValueError(f"{what} must be one of {AXES}; got {axis!r}")
    return axis


def axis_unit(axis: str) -> str:
    """Unit of the acceleration of ``axis``: ``"m/s²"`` or ``"rad/s²"`` (rotations)."""
    return "rad/s²" if check_axis_name(axis) in ROTATIONAL_AXES else "m/s²"


def _check_spacing(time_s: np.ndarray) -> None:
    """Refuse times that are not strictly increasing with a constant, resolvable interval."""
    with np.errstate(over="ignore"):  # an infinite span is refused below, by name
        interval_s = np.diff(time_s)
    if np.any(interval_s <= 0.0):
        index = int(np.flatnonzero(interval_s <= 0.0)[0])
        raise ValueError(
            f"time_s must be strictly increasing; got {float(time_s[index])!r} then "
            f"{float(time_s[index + 1])!r} at index {index + 1}"
        )
    span_s = float(time_s[-1]) - float(time_s[0])
    if not math.isfinite(span_s):
        raise ValueError(f"time_s must span a finite time; got {time_s[0]:g} s to {time_s[-1]:g} s")
    mean_interval_s = span_s / (time_s.size - 1)
    # Each stamp is the nearest float64 to its time, within half the spacing of floats at
    # its magnitude, so an interval is known to within one spacing at the largest |t|.
    largest_s = float(np.max(np.abs(time_s)))
    resolution_s = float(np.spacing(largest_s))
    if resolution_s > TIME_JITTER_TOLERANCE * mean_interval_s:
        raise ValueError(
            f"time_s cannot resolve its sampling interval: times of {largest_s:.6g} s are "
            f"stored to {resolution_s:.3g} s (float64), more than {TIME_JITTER_TOLERANCE:.0%} "
            f"of the mean interval {mean_interval_s:.6g} s; allowed: a resolution of at most "
            f"{TIME_JITTER_TOLERANCE:.0%} of the interval (write the times relative to the "
            "start of the record)"
        )
    deviation_s = np.abs(interval_s - mean_interval_s)
    allowed_s = TIME_JITTER_TOLERANCE * mean_interval_s + resolution_s
    if np.max(deviation_s) > allowed_s:
        index = int(np.argmax(deviation_s))
        raise ValueError(
            f"time_s must be uniformly sampled (intervals within "
            f"{TIME_JITTER_TOLERANCE:.0%} of the mean {mean_interval_s:.6g} s); got an "
            f"interval of {interval_s[index]:.6g} s at index {index + 1}"
        )


@dataclass(frozen=True)
class VibrationRecord:
    """Uniformly sampled accelerations of several axes (ISO 2631-1 clause 5).

    Parameters
    ----------
    time_s : array_like
        Sample times in s, at least 2, finite and strictly increasing with a constant interval
        (within :data:`TIME_JITTER_TOLERANCE` of the mean interval, plus the float64
        resolution of the times). Any origin is accepted, e.g. Unix time stamps: only the
        spacing is used (the sample rate from the span ``t_last - t_first``), so a record
        evaluates as the same record with ``time_s - time_s[0]``. A float64 time stamp t is
        resolved to ``numpy.spacing(t)`` (2.4e-7 s at 1.7e9 s, a Unix time of 2023); times
        whose resolution exceeds 1 % of the sampling interval (at that magnitude: sampling
        faster than about 42 kHz) are refused, since their spacing cannot be checked.
    axes : mapping of str to array_like
        Axis name (one of :data:`AXES`) to acceleration samples in m/s² or rad/s², each finite and
        as long as ``time_s``. At least one axis.

    The arrays are stored as read-only float copies; ``axes`` becomes a read-only mapping.
    """

    time_s: np.ndarray
    axes: Mapping[str, np.ndarray]

    def __post_init__(self) -> None:
        time_s = as_signal(self.time_s, "time_s").copy()
        if time_s.size < 2:
            raise ValueError(f"time_s must have at least 2 samples; got {time_s.size}")
        _check_spacing(time_s)
        if not isinstance(self.axes, Mapping) or not self.axes:
            raise ValueError(f"axes must map at least one of {AXES} to samples; got {self.axes!r}")
        axes: dict[str, np.ndarray] = {}
        for name, values in self.axes.items():
            check_axis_name(name, "axis name")
            column = as_signal(values, f"axis {name!r}").copy()
            too_large = np.flatnonzero(np.abs(column) > MAX_ACCELERATION)
            if too_large.size:
                raise ValueError(
                    f"axis {name!r} = {column[too_large[0]]:g} {axis_unit(name)} at index "
                    f"{too_large[0]} is implausible; allowed: |value| <= {MAX_ACCELERATION:g} "
                    f"({_ACCELERATION_REASON})"
                )
            if column.size != time_s.size:
                raise ValueError(
                    f"axis {name!r} must have as many samples as time_s ({time_s.size}); "
                    f"got {column.size}"
                )
            column.setflags(write=False)
            axes[name] = column
        time_s.setflags(write=False)
        object.__setattr__(self, "time_s", time_s)
        object.__setattr__(self, "axes", MappingProxyType(axes))

    @property
    def sample_rate_hz(self) -> float:
        """Mean sample rate in Hz, (n - 1) / (t_last - t_first)."""
        return float((self.time_s.size - 1) / (self.time_s[-1] - self.time_s[0]))

    @property
    def duration_s(self) -> float:
        """Measurement duration T = n / fs in s (each sample stands for one interval)."""
        return self.time_s.size / self.sample_rate_hz

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Axis names in column order."""
        return tuple(self.axes)

    @classmethod
    def from_csv(cls, path: str | Path) -> VibrationRecord:
        """Read a record with :func:`read_vibration_csv`."""
        return read_vibration_csv(path)


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
    :data:`CSV_BLOCK_ROWS` rows, so memory stays at about 2 x 8 bytes per value of the file.
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
    blocks: list[np.ndarray] = []
    block: list[tuple[int, str]] = []
    rows = 0
    first_data_line = None
    for number, line in enumerate(lines, start=2):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        first_data_line = first_data_line or number
        block.append((number, line))
        if len(block) == CSV_BLOCK_ROWS:
            blocks.append(_parse_block(name, header, block))
            _check_magnitudes(name, header, blocks[-1], rows + 1)
            rows += len(block)
            block = []
    if block:
        blocks.append(_parse_block(name, header, block))
        _check_magnitudes(name, header, blocks[-1], rows + 1)
        rows += len(block)
    if not rows:
        raise ValueError(f"{name}: no data rows below the header {header}")
    columns = {column: np.empty(rows) for column in header}
    start = 0
    while blocks:
        data = blocks.pop(0)
        for index, column in enumerate(header):
            columns[column][start : start + data.shape[0]] = data[:, index]
        start += data.shape[0]
    time_s = columns.pop("time")
    try:
        return VibrationRecord(time_s=time_s, axes=columns)
    except ValueError as error:
        raise ValueError(f"{name}: {error}") from None
