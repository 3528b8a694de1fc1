"""Labelled multi-axis acceleration records: a time vector and named axis columns.

Axis names follow ISO 2631-1 Figure 1 for a seated person: translations ``x`` (fore-aft), ``y``
(lateral), ``z`` (vertical) in m/s² and rotations ``roll`` (about x), ``pitch`` (about y), ``yaw``
(about z) in rad/s². The paper measures x, y, z at the seat and estimates the pitch (section 5.3).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import numpy as np

from loader_model.iso2631._checks import as_signal

__all__ = [
    "AXES",
    "MAX_ACCELERATION",
    "ROTATIONAL_AXES",
    "TIME_JITTER_TOLERANCE",
    "VibrationRecord",
    "axis_unit",
    "check_axis_name",
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
    largest_s = max(abs(float(time_s[0])), abs(float(time_s[-1])))  # increasing: at an end
    resolution_s = float(np.spacing(largest_s))
    if resolution_s > TIME_JITTER_TOLERANCE * mean_interval_s:
        raise ValueError(
            f"time_s cannot resolve its sampling interval: times of {largest_s:.6g} s are "
            f"stored to {resolution_s:.3g} s (float64), more than {TIME_JITTER_TOLERANCE:.0%} "
            f"of the mean interval {mean_interval_s:.6g} s; allowed: a resolution of at most "
            f"{TIME_JITTER_TOLERANCE:.0%} of the interval (write the times relative to the "
            "start of the record)"
        )
    deviation_s = interval_s  # in place: a long record needs no second temporary
    deviation_s -= mean_interval_s
    np.abs(deviation_s, out=deviation_s)
    allowed_s = TIME_JITTER_TOLERANCE * mean_interval_s + resolution_s
    if np.max(deviation_s) > allowed_s:
        index = int(np.argmax(deviation_s))
        interval = float(time_s[index + 1]) - float(time_s[index])
        raise ValueError(
            f"time_s must be uniformly sampled (intervals within "
            f"{TIME_JITTER_TOLERANCE:.0%} of the mean {mean_interval_s:.6g} s); got an "
            f"interval of {interval:.6g} s at index {index + 1}"
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
        self._store(copy=True)

    @classmethod
    def _adopt(cls, time_s: np.ndarray, axes: dict[str, np.ndarray]) -> VibrationRecord:
        """The record of arrays that nobody else holds (:func:`read_vibration_csv`'s own):
        checked as the constructor checks them and made read-only, not copied."""
        record = cls.__new__(cls)
        object.__setattr__(record, "time_s", time_s)
        object.__setattr__(record, "axes", axes)
        record._store(copy=False)
        return record

    def _store(self, *, copy: bool) -> None:
        """Check the fields and store them read-only (copies if ``copy``)."""
        time_s = as_signal(self.time_s, "time_s")
        time_s = time_s.copy() if copy else time_s
        if time_s.size < 2:
            raise ValueError(f"time_s must have at least 2 samples; got {time_s.size}")
        _check_spacing(time_s)
        if not isinstance(self.axes, Mapping) or not self.axes:
            raise ValueError(f"axes must map at least one of {AXES} to samples; got {self.axes!r}")
        axes: dict[str, np.ndarray] = {}
        for name, values in self.axes.items():
            check_axis_name(name, "axis name")
            column = as_signal(values, f"axis {name!r}")
            column = column.copy() if copy else column
            too_large = np.flatnonzero((column > MAX_ACCELERATION) | (column < -MAX_ACCELERATION))
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
        """Read a record with :func:`~loader_model.iso2631.vibration_csv.read_vibration_csv`."""
        from loader_model.iso2631.vibration_csv import read_vibration_csv

        return read_vibration_csv(path)
