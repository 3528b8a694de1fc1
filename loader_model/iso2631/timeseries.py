"""Labelled multi-axis acceleration records: a time vector and named axis columns, CSV input.

Axis names follow ISO 2631-1 Figure 1 for a seated person: translations ``x`` (fore-aft), ``y``
(lateral), ``z`` (vertical) in m/s² and rotations ``roll`` (about x), ``pitch`` (about y), ``yaw``
(about z) in rad/s². The paper measures x, y, z at the seat and estimates the pitch (section 5.3).
"""

from __future__ import annotations

import io
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import numpy as np

from loader_model.iso2631._checks import as_signal

__all__ = [
    "AXES",
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
#: (times rounded when written to CSV stay well inside it).
TIME_JITTER_TOLERANCE = 0.01


def check_axis_name(axis: object, what: str = "axis") -> str:
    """Return ``axis`` if it is one of :data:`AXES`, else raise ValueError naming ``what``."""
    if not isinstance(axis, str) or axis not in AXES:
        raise ValueError(f"{what} must be one of {AXES}; got {axis!r}")
    return axis


def axis_unit(axis: str) -> str:
    """Unit of the acceleration of ``axis``: ``"m/s²"`` or ``"rad/s²"`` (rotations)."""
    return "rad/s²" if check_axis_name(axis) in ROTATIONAL_AXES else "m/s²"


@dataclass(frozen=True)
class VibrationRecord:
    """Uniformly sampled accelerations of several axes (ISO 2631-1 clause 5).

    Parameters
    ----------
    time_s : array_like
        Sample times in s, strictly increasing with constant interval (within
        :data:`TIME_JITTER_TOLERANCE`), at least 2 samples.
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
        interval_s = np.diff(time_s)
        if np.any(interval_s <= 0.0):
            index = int(np.flatnonzero(interval_s <= 0.0)[0])
            raise ValueError(
                f"time_s must be strictly increasing; got {time_s[index]:.9g} then "
                f"{time_s[index + 1]:.9g} at index {index + 1}"
            )
        mean_interval_s = (time_s[-1] - time_s[0]) / (time_s.size - 1)
        deviation = np.abs(interval_s - mean_interval_s) / mean_interval_s
        if np.max(deviation) > TIME_JITTER_TOLERANCE:
            index = int(np.argmax(deviation))
            raise ValueError(
                f"time_s must be uniformly sampled (intervals within "
                f"{TIME_JITTER_TOLERANCE:.0%} of the mean {mean_interval_s:.6g} s); got an "
                f"interval of {interval_s[index]:.6g} s at index {index + 1}"
            )
        if not isinstance(self.axes, Mapping) or not self.axes:
            raise ValueError(f"axes must map at least one of {AXES} to samples; got {self.axes!r}")
        axes: dict[str, np.ndarray] = {}
        for name, values in self.axes.items():
            check_axis_name(name, "axis name")
            column = as_signal(values, f"axis {name!r}").copy()
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


def read_vibration_csv(path: str | Path) -> VibrationRecord:
    """Read a CSV file with a header row: a ``time`` column in s and axis columns (see :data:`AXES`).

    Lines starting with ``#`` and blank lines are skipped; the delimiter is a comma.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.

    Returns
    -------
    VibrationRecord
        The validated record (see its checks).
    """
    path = Path(path)
    lines = [
        line
        for line in path.read_text(encoding="utf-8").splitlines()
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not lines:
        raise ValueError(f"{path}: no header row; expected columns 'time' and some of {AXES}")
    header = [name.strip() for name in lines[0].split(",")]
    duplicates = sorted({name for name in header if header.count(name) > 1})
    if duplicates:
        raise ValueError(f"{path}: duplicate column(s) {duplicates} in header {header}")
    if "time" not in header:
        raise ValueError(f"{path}: header must contain a 'time' column (s); got {header}")
    for name in header:
        if name != "time":
            check_axis_name(name, f"{path}: column name")
    if len(header) < 2:
        raise ValueError(f"{path}: header needs at least one axis column of {AXES}; got {header}")
    if len(lines) < 2:
        raise ValueError(f"{path}: no data rows below the header {header}")
    try:
        data = np.loadtxt(io.StringIO("\n".join(lines[1:])), delimiter=",", ndmin=2)
    except ValueError as error:
        raise ValueError(f"{path}: could not read the data rows as numbers: {error}") from None
    if data.shape[1] != len(header):
        raise ValueError(
            f"{path}: rows have {data.shape[1]} values but the header has {len(header)} columns"
        )
    columns = {name: data[:, index] for index, name in enumerate(header)}
    for name, column in columns.items():
        bad = np.flatnonzero(~np.isfinite(column))
        if bad.size:
            raise ValueError(
                f"{path}: column {name!r} must be finite; got {column[bad[0]]} in data row "
                f"{bad[0] + 1}"
            )
    time_s = columns.pop("time")
    return VibrationRecord(time_s=time_s, axes=columns)
