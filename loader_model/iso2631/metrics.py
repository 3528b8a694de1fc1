"""Evaluation values of ISO 2631-1:1997 clause 6 for frequency-weighted accelerations.

Inputs are weighted accelerations a_w(t) (m/s², or rad/s² for rotational axes) sampled at a
constant rate, as returned by :func:`loader_model.iso2631.filters.weight_acceleration`.
Integrals are evaluated with the rectangle rule (sum x 1/fs), which is exact for whole periods
of sampled trigonometric signals.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Mapping

import numpy as np

from loader_model.iso2631._checks import as_positive, as_signal, shown
from loader_model.iso2631._digital import SEGMENT_SAMPLES, sos_filter

__all__ = [
    "RUNNING_RMS_METHODS",
    "crest_factor",
    "estimated_vibration_dose_value",
    "maximum_transient_vibration_value",
    "peak_magnitude",
    "running_rms",
    "vibration_dose_value",
    "vibration_total_value",
    "weighted_rms",
]

#: Running r.m.s. integrations of ISO 2631-1 6.3.1.
RUNNING_RMS_METHODS = ("linear", "exponential")


def _segments(signal: np.ndarray) -> Iterator[np.ndarray]:
    """Consecutive views of ``signal`` of :data:`SEGMENT_SAMPLES` samples: the sums below run
    over them so that a long record needs no temporary of its own length."""
    for start in range(0, signal.size, SEGMENT_SAMPLES):
        yield signal[start : start + SEGMENT_SAMPLES]


def _sum_of_powers(signal: np.ndarray, power: int) -> float:
    """Sum of ``signal**power`` (power 2 or 4) by segments; each segment's sum is NumPy's
    pairwise sum, the segments' sums are added exactly (:func:`math.fsum`)."""
    sums = []
    for segment in _segments(signal):
        squared = segment * segment  # (a^2)^2: ten times faster than a**4, which calls pow()
        sums.append(float(np.sum(squared if power == 2 else squared * squared)))
    return math.fsum(sums)


def peak_magnitude(signal: np.ndarray) -> float:
    """max |signal|, without a temporary array of the signal's length."""
    return max(float(np.max(signal)), -float(np.min(signal)))


def _check_non_negative(value: float, name: str) -> None:
    if not isinstance(value, int | float) or not math.isfinite(value) or value < 0.0:
        raise ValueError(f"{name} must be a finite number >= 0; got {shown(value)}")


def weighted_rms(weighted_acceleration: np.ndarray) -> float:
    """Weighted r.m.s. acceleration a_w, paper Eq. 49 / ISO 2631-1 6.1 (basic evaluation method).

    .. math:: a_w = \\left[\\frac{1}{T}\\int_0^T a_w^2(t)\\,dt\\right]^{1/2}

    Parameters
    ----------
    weighted_acceleration : array_like
        Weighted acceleration samples (1-D, finite), m/s² or rad/s².

    Returns
    -------
    float
        a_w in the unit of the input.
    """
    signal = as_signal(weighted_acceleration, "weighted_acceleration")
    return math.sqrt(_sum_of_powers(signal, 2) / signal.size)


def vibration_total_value(
    weighted_rms_by_axis: Mapping[str, float], k_factors: Mapping[str, float]
) -> float:
    """Vibration total value a_v, paper Eq. 50 / ISO 2631-1 6.5 (several directions).

    .. math:: a_v = \\left(\\sum_i k_i^2 a_{wi}^2\\right)^{1/2}

    The paper uses k = 1 for x, y, z and k = 0.4 (m/rad) for the seat pitch.

    Parameters
    ----------
    weighted_rms_by_axis : mapping of str to float
        a_wi per axis, m/s² (rad/s² for rotations); finite and >= 0.
    k_factors : mapping of str to float
        Multiplying factor k_i per axis (finite, >= 0); must cover every axis given.

    Returns
    -------
    float
        a_v in m/s².
    """
    if not weighted_rms_by_axis:
        raise ValueError("weighted_rms_by_axis must name at least one axis; got none")
    total = 0.0
    for axis, value in weighted_rms_by_axis.items():
        if axis not in k_factors:
            raise ValueError(
                f"k_factors has no entry for axis {axis!r}; given axes: {sorted(k_factors)}"
            )
        _check_non_negative(value, f"weighted_rms_by_axis[{axis!r}]")
        _check_non_negative(k_factors[axis], f"k_factors[{axis!r}]")
        total += (k_factors[axis] * value) ** 2
    return math.sqrt(total)


def crest_factor(weighted_acceleration: np.ndarray) -> float:
    """Crest factor max |a_w(t)| / a_w (ISO 2631-1 6.2); the basic method suffices up to 9.

    Returns NaN, undefined, for a signal that is zero everywhere (no vibration).
    """
    signal = as_signal(weighted_acceleration, "weighted_acceleration")
    rms = weighted_rms(signal)
    if rms == 0.0:
        return math.nan
    return peak_magnitude(signal) / rms


def running_rms(
    weighted_acceleration: np.ndarray,
    sample_rate_hz: float,
    *,
    integration_time_s: float = 1.0,
    method: str = "linear",
) -> np.ndarray:
    """Running r.m.s. a_w(t0) of ISO 2631-1 6.3.1 (linear or exponential integration).

    .. math::

        a_w(t_0) = \\left[\\frac{1}{τ}\\int_{t_0-τ}^{t_0} a_w^2(t)\\,dt\\right]^{1/2}
        \\quad\\text{or}\\quad
        \\left[\\frac{1}{τ}\\int_{-∞}^{t_0} a_w^2(t)\\,e^{(t-t_0)/τ}\\,dt\\right]^{1/2}

    Parameters
    ----------
    weighted_acceleration : array_like
        Weighted acceleration, 1-D, finite; at least ``integration_time_s`` long.
    sample_rate_hz : float
        Sample rate in Hz.
    integration_time_s : float
        τ in s; ISO 2631-1 recommends 1 s for MTVV.
    method : {"linear", "exponential"}
        ``"linear"`` returns one value per complete window (the window ending at each sample from
        the ``round(τ fs)``-th on); ``"exponential"`` one value per sample, the integral starting at
        rest at the first sample (exact exponential decay between samples).

    Returns
    -------
    numpy.ndarray
        a_w(t0) in the unit of the input.
    """
    mean_squares = _mean_square_segments(
        weighted_acceleration, sample_rate_hz, integration_time_s, method
    )
    count, segment = next(mean_squares)
    out = np.empty(count)
    start = 0
    for part in itertools.chain([segment], (part for _, part in mean_squares)):
        out[start : start + part.size] = part
        start += part.size
    np.maximum(out, 0.0, out=out)  # >= 0 up to rounding
    return np.sqrt(out, out=out)


def _mean_square_segments(
    weighted_acceleration: np.ndarray, sample_rate_hz: float, integration_time_s: float, method: str
) -> Iterator[tuple[int, np.ndarray]]:
    """Check the arguments of :func:`running_rms` and yield its mean squares a_w(t0)² by
    consecutive segments, each as (number of values in all, segment); the linear integration's
    running sum carries over from segment to segment exactly as one cumulative sum would."""
    signal = as_signal(weighted_acceleration, "weighted_acceleration")
    rate = as_positive(sample_rate_hz, "sample_rate_hz", "Hz")
    tau = as_positive(integration_time_s, "integration_time_s", "s")
    if method not in RUNNING_RMS_METHODS:
        raise ValueError(f"method must be one of {RUNNING_RMS_METHODS}; got {method!r}")
    window = round(tau * rate)
    if window < 1 or window > signal.size:
        raise ValueError(
            f"integration_time_s must span 1 to {signal.size} samples of the signal "
            f"({signal.size / rate:.4g} s at {rate:g} Hz); got {shown(integration_time_s)} s"
        )
    if method == "exponential":
        decay = math.exp(-1.0 / (tau * rate))
        mean_square, _ = sos_filter(
            np.array([[1.0 - decay, 0.0, 0.0, 1.0, -decay, 0.0]]), signal * signal
        )
        yield signal.size, mean_square
        return
    cumulative = np.empty(signal.size + 1)  # sums of the first k squares, k = 0 .. n
    cumulative[0] = 0.0
    for start in range(0, signal.size, SEGMENT_SAMPLES):
        squared = signal[start : start + SEGMENT_SAMPLES] ** 2
        squared[0] += cumulative[start]  # then cumsum adds in the order one cumsum would
        np.cumsum(squared, out=cumulative[start + 1 : start + 1 + squared.size])
    count = signal.size - window + 1
    for start in range(0, count, SEGMENT_SAMPLES):
        stop = min(start + SEGMENT_SAMPLES, count)
        yield count, (cumulative[start + window : stop + window] - cumulative[start:stop]) / window


def maximum_transient_vibration_value(
    weighted_acceleration: np.ndarray,
    sample_rate_hz: float,
    *,
    integration_time_s: float = 1.0,
    method: str = "linear",
) -> float:
    """MTVV, the maximum of the running r.m.s. over t0 (ISO 2631-1 6.3.1); see :func:`running_rms`.

    Evaluated segment by segment, without the running r.m.s. of the whole record in memory.
    """
    largest = max(
        float(np.max(segment))
        for _, segment in _mean_square_segments(
            weighted_acceleration, sample_rate_hz, integration_time_s, method
        )
    )
    return math.sqrt(max(largest, 0.0))


def vibration_dose_value(weighted_acceleration: np.ndarray, sample_rate_hz: float) -> float:
    """Fourth power vibration dose value VDV (ISO 2631-1 6.3.2), in m/s^1.75.

    .. math:: VDV = \\left[\\int_0^T a_w^4(t)\\,dt\\right]^{1/4}
    """
    signal = as_signal(weighted_acceleration, "weighted_acceleration")
    rate = as_positive(sample_rate_hz, "sample_rate_hz", "Hz")
    return (_sum_of_powers(signal, 4) / rate) ** 0.25


def estimated_vibration_dose_value(weighted_rms_m_s2: float, duration_s: float) -> float:
    """Estimated VDV, eVDV = 1.4 a_w T^(1/4) (ISO 2631-1 Annex B.3), in m/s^1.75."""
    duration = as_positive(duration_s, "duration_s", "s")
    _check_non_negative(weighted_rms_m_s2, "weighted_rms_m_s2")
    return 1.4 * float(weighted_rms_m_s2) * duration**0.25
