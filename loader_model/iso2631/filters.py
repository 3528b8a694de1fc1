"""Causal discrete ISO 2631-1 frequency weightings for sampled accelerations at any usable rate.

Design (per weighting and sample rate ``fs``, cached):

1. **Matched poles and zeros.** Every pole and finite zero ``p`` of the exact Annex A.2 factors
   (:mod:`loader_model.iso2631.weightings`) maps to ``exp(p / fs)``; the double zero of the
   band-limiting high-pass lands exactly on ``z = 1`` (no response to a constant offset). Zeros
   at infinity (the relative degree) are placed at ``z = 0``, one second-order section per
   factor. This part M(z) is exact in pole and zero position, so it has no frequency warping,
   unlike the bilinear transform, whose 1/f slopes end up several dB wrong near ``fs/2``.
2. **Causal FIR correction.** A 16-tap FIR ``C(z)`` is fitted so that ``C · M / W - 1`` is
   small in magnitude and phase over the band from half its lowest frequency to
   ``min(0.4 fs,`` its highest frequency ``)``, by linear least squares followed by Lawson's
   iteratively reweighted least squares (towards the min-max error); from there to fs/2 a
   lightly weighted absolute-error term keeps the gain bounded.

The result meets the ISO 8041 tolerances used here (±1 dB magnitude, ±6° phase against the exact
continuous response) over the band :data:`~loader_model.iso2631.weightings.NOMINAL_BAND_HZ`
(0.1 Hz to 80 Hz; Wf 0.02 Hz to 4 Hz) whenever ``fs >= 2.5 x`` its upper edge, i.e. 200 Hz
(10 Hz for Wf); lower rates are refused. Each design records the errors it achieves on a dense
grid of that band (:attr:`DiscreteWeighting.max_magnitude_error_db`,
:attr:`DiscreteWeighting.max_phase_error_deg`).

ISO 8041's ±1 dB is 12 % in a_w. Measured against exact causal Annex A filtering
(``python -m tests.iso_accuracy``), this design alone reads a_w 6.3 % high for Wj and 0.5-1 %
high for the others at 200 Hz, and agrees to 3e-4 from 1 kHz on. :func:`weight_acceleration`
therefore weights records sampled below 1 kHz at an integer multiple of their rate
(:mod:`loader_model.iso2631.upsampling`): at 200 Hz, the lowest accepted rate, every weighting
then reads sines of 0.5-31.5 Hz (Wf: 0.1-4 Hz) within 0.05 % and shocks within 0.6 %. At Wf's
lowest rate of 10 Hz the top of its band (4 Hz, 0.4 fs) reads 1.4 % low, within ISO 8041.

The filters run on NumPy (:mod:`loader_model.iso2631._digital`), not scipy.signal, whose import
alone took longer than a whole ``loader-model simulate``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from loader_model.iso2631._checks import as_positive, as_signal, shown
from loader_model.iso2631._digital import (
    dc_gain,
    fir_filter,
    fir_response,
    least_squares,
    sos_filter,
    sos_response,
    sos_steady_state,
)
from loader_model.iso2631.upsampling import upsampling_factor, weight_upsampled
from loader_model.iso2631.weightings import (
    NOMINAL_BAND_HZ,
    WEIGHTINGS,
    check_weighting_name,
    settling_time_s,
    weighting_response,
    weighting_sections,
)

__all__ = [
    "INITIAL_STATES",
    "MAGNITUDE_TOLERANCE_DB",
    "MINIMUM_SAMPLE_RATE_HZ",
    "PHASE_TOLERANCE_DEG",
    "SAMPLE_RATE_TO_BAND_RATIO",
    "DiscreteWeighting",
    "design_weighting_filter",
    "weight_acceleration",
]

#: Tolerances of ISO 8041 used for the design check: magnitude (dB) and phase (degrees).
MAGNITUDE_TOLERANCE_DB = 1.0
PHASE_TOLERANCE_DEG = 6.0

#: The design is accurate up to ``fs / SAMPLE_RATE_TO_BAND_RATIO`` (= 0.4 fs).
SAMPLE_RATE_TO_BAND_RATIO = 2.5

#: Lowest accepted sample rate per weighting: 2.5 x the upper edge of its nominal band.
MINIMUM_SAMPLE_RATE_HZ: Mapping[str, float] = MappingProxyType(
    {name: SAMPLE_RATE_TO_BAND_RATIO * NOMINAL_BAND_HZ[name][1] for name in WEIGHTINGS}
)

#: How a filter starts: ``"steady"`` = steady state for a constant input equal to the first
#: sample (an offset such as gravity gives no start transient), ``"rest"`` = all states zero.
INITIAL_STATES = ("steady", "rest")

_FIR_TAPS = 16
_LAWSON_ITERATIONS = 10
_FIT_POINTS = 400
_GUARD_POINTS = 50
_GUARD_WEIGHT = 0.01


def _delays(frequency_hz: np.ndarray, sample_rate_hz: float) -> np.ndarray:
    """Matrix of z^-n at z = exp(j 2π f / fs) for the FIR taps n = 0 .. _FIR_TAPS - 1."""
    return np.exp(-2j * np.pi * np.outer(frequency_hz, np.arange(_FIR_TAPS)) / sample_rate_hz)


@dataclass(frozen=True)
class DiscreteWeighting:
    """A causal discrete realization of one ISO 2631-1 weighting at one sample rate.

    The filter is the cascade of second-order sections :attr:`sos` (matched poles and zeros) and
    the FIR :attr:`fir`; use :meth:`apply` or :func:`weight_acceleration`.
    """

    weighting: str
    sample_rate_hz: float
    sos: np.ndarray
    fir: np.ndarray
    band_hz: tuple[float, float]
    max_magnitude_error_db: float
    max_phase_error_deg: float
    settling_time_s: float

    def frequency_response(self, frequency_hz: np.ndarray | float) -> np.ndarray:
        """Complex response of the discrete filter at ``frequency_hz`` (Hz, below fs/2)."""
        frequency = np.atleast_1d(np.asarray(frequency_hz, dtype=float))
        response = sos_response(self.sos, frequency, self.sample_rate_hz) * fir_response(
            self.fir, frequency, self.sample_rate_hz
        )
        return np.reshape(response, np.shape(frequency_hz))

    def apply(self, acceleration: np.ndarray, *, initial_state: str = "steady") -> np.ndarray:
        """Weighted acceleration a_w(t) of ISO 2631-1 6.3 for samples at :attr:`sample_rate_hz`.

        Parameters
        ----------
        acceleration : array_like
            Unweighted acceleration, 1-D, finite, in m/s² (rad/s² for rotations); at least
            :attr:`settling_time_s` long.
        initial_state : {"steady", "rest"}
            See :data:`INITIAL_STATES`.

        Returns
        -------
        numpy.ndarray
            The weighted acceleration, same length and unit.
        """
        signal = self.check(acceleration, initial_state)
        sos_state, fir_history = self.initial_state(signal[0], initial_state == "steady")
        intermediate, _ = sos_filter(self.sos, signal, sos_state)
        weighted, _ = fir_filter(self.fir, intermediate, fir_history)
        return weighted

    def initial_state(self, value: float, steady: bool) -> tuple[np.ndarray, np.ndarray]:
        """States of the sections and the FIR's input history: at rest, or (``steady``) in
        the steady state of the constant input ``value``."""
        if not steady:
            return np.zeros(2 * self.sos.shape[0]), np.zeros(self.fir.size - 1)
        history = np.full(self.fir.size - 1, dc_gain(self.sos) * value)
        return sos_steady_state(self.sos, value), history

    def check(self, acceleration: np.ndarray, initial_state: str) -> np.ndarray:
        """Return the checked signal; refuse a bad initial state or a record that is too short."""
        signal = as_signal(acceleration, "acceleration")
        if initial_state not in INITIAL_STATES:
            raise ValueError(
                f"initial_state must be one of {INITIAL_STATES}; got {initial_state!r}"
            )
        duration_s = signal.size / self.sample_rate_hz
        if duration_s < self.settling_time_s:
            raise ValueError(
                f"acceleration is too short for weighting {self.weighting}: {signal.size} samples"
                f" = {duration_s:.4g} s at {self.sample_rate_hz:g} Hz; the filter needs at least"
                f" its settling time {self.settling_time_s:.4g} s"
            )
        return signal


def _check_sample_rate(weighting: str, sample_rate_hz: float) -> float:
    rate = as_positive(sample_rate_hz, "sample_rate_hz", "Hz")
    minimum = MINIMUM_SAMPLE_RATE_HZ[weighting]
    if rate < minimum:
        raise ValueError(
            f"sample_rate_hz must be at least {minimum:g} Hz for weighting {weighting} "
            f"(±{MAGNITUDE_TOLERANCE_DB:g} dB / ±{PHASE_TOLERANCE_DEG:g}° up to "
            f"{NOMINAL_BAND_HZ[weighting][1]:g} Hz needs {SAMPLE_RATE_TO_BAND_RATIO:g} x that); "
            f"got {shown(sample_rate_hz)} Hz"
        )
    return rate


def _errors(ratio: np.ndarray) -> tuple[float, float]:
    """Worst magnitude error (dB) and phase error (degrees) of a complex response ratio."""
    magnitude_db = float(np.max(np.abs(20.0 * np.log10(np.abs(ratio)))))
    phase_deg = float(np.max(np.abs(np.angle(ratio, deg=True))))
    return magnitude_db, phase_deg


def design_weighting_filter(weighting: str, sample_rate_hz: float) -> DiscreteWeighting:
    """Design the causal discrete filter of ``weighting`` at ``sample_rate_hz`` (see module doc).

    Parameters
    ----------
    weighting : str
        One of :data:`~loader_model.iso2631.weightings.WEIGHTING_NAMES`.
    sample_rate_hz : float
        Sample rate in Hz, at least :data:`MINIMUM_SAMPLE_RATE_HZ` of the weighting.

    Returns
    -------
    DiscreteWeighting
        The filter (cached per weighting and rate; its arrays are read-only).
    """
    check_weighting_name(weighting)
    return _design(weighting, _check_sample_rate(weighting, sample_rate_hz))


def _matched_sections(weighting: str, sample_rate_hz: float) -> np.ndarray:
    """One second-order section per Annex A.2 factor: its poles and finite zeros ``p`` mapped to
    ``exp(p / fs)``, its zeros at infinity to ``z = 0``; unit gain (rows b0, b1, b2, 1, a1, a2)."""
    rows = []
    for section in weighting_sections(weighting):
        poles = np.exp(np.roots(section.denominator) / sample_rate_hz)
        zeros = np.exp(np.roots(section.numerator) / sample_rate_hz)
        zeros = np.concatenate([zeros, np.zeros(poles.size - zeros.size)])
        rows.append(np.concatenate([np.poly(zeros).real, np.poly(poles).real]))
    return np.array(rows)


@functools.lru_cache(maxsize=64)
def _design(weighting: str, sample_rate_hz: float) -> DiscreteWeighting:
    band_low_hz, band_high_hz = NOMINAL_BAND_HZ[weighting]
    fit_high_hz = min(sample_rate_hz / SAMPLE_RATE_TO_BAND_RATIO, band_high_hz)
    frequency_hz = np.geomspace(0.5 * band_low_hz, fit_high_hz, _FIT_POINTS)
    reference_hz = math.sqrt(band_low_hz * band_high_hz)

    sos = _matched_sections(weighting, sample_rate_hz)
    unit = sos_response(sos, np.array([reference_hz]), sample_rate_hz)[0]
    sos[0, :3] *= float(np.abs(weighting_response(weighting, reference_hz) / unit))
    matched = sos_response(sos, frequency_hz, sample_rate_hz)

    # Rows of the fit, linear in the taps c: in band the relative error (M z^-n / W) c - 1; above
    # it, up to fs/2, the absolute error (M z^-n c - W) / max|W| with a small fixed weight, which
    # keeps the gain of the FIR bounded where the band fit does not constrain it.
    guard_hz = np.linspace(fit_high_hz, 0.49 * sample_rate_hz, _GUARD_POINTS + 1)[1:]
    peak = float(np.max(np.abs(weighting_response(weighting, frequency_hz))))
    matched_guard = sos_response(sos, guard_hz, sample_rate_hz)
    columns = (matched / weighting_response(weighting, frequency_hz))[:, None] * _delays(
        frequency_hz, sample_rate_hz
    )
    guard_columns = (matched_guard / peak)[:, None] * _delays(guard_hz, sample_rate_hz)
    guard_target = weighting_response(weighting, guard_hz) / peak
    guard_weight = math.sqrt(_GUARD_WEIGHT / guard_hz.size)
    weights = np.full(frequency_hz.size, 1.0 / frequency_hz.size)
    for _ in range(_LAWSON_ITERATIONS + 1):
        root_weights = np.sqrt(weights)[:, None]
        stacked = np.vstack([columns * root_weights, guard_columns * guard_weight])
        target = np.concatenate([root_weights[:, 0], guard_target * guard_weight])
        fir = least_squares(
            np.vstack([stacked.real, stacked.imag]), np.concatenate([target.real, target.imag])
        )
        weights = weights * np.abs(np.einsum("ij,j->i", columns, fir) - 1.0)  # no BLAS threads
        weights /= np.sum(weights)

    check_hz = np.geomspace(band_low_hz, band_high_hz, 4 * _FIT_POINTS)
    check = sos_response(sos, check_hz, sample_rate_hz) * fir_response(
        fir, check_hz, sample_rate_hz
    )
    magnitude_db, phase_deg = _errors(check / weighting_response(weighting, check_hz))
    if magnitude_db > MAGNITUDE_TOLERANCE_DB or phase_deg > PHASE_TOLERANCE_DEG:
        raise ValueError(  # only reachable far above any practical rate (checked up to 1 MHz)
            f"sample_rate_hz {sample_rate_hz:g} Hz gives a numerically inaccurate {weighting} "
            f"filter ({magnitude_db:.3g} dB, {phase_deg:.3g}°); resample to a lower rate"
        )
    sos.setflags(write=False)
    fir.setflags(write=False)
    return DiscreteWeighting(
        weighting=weighting,
        sample_rate_hz=sample_rate_hz,
        sos=sos,
        fir=fir,
        band_hz=(band_low_hz, band_high_hz),
        max_magnitude_error_db=magnitude_db,
        max_phase_error_deg=phase_deg,
        settling_time_s=settling_time_s(weighting),
    )


def weight_acceleration(
    acceleration: np.ndarray,
    sample_rate_hz: float,
    weighting: str,
    *,
    initial_state: str = "steady",
) -> np.ndarray:
    """Frequency-weighted acceleration a_w(t) (ISO 2631-1 6.3; the paper's a_wi = W_i(a_i)).

    Below 1 kHz (less 100 ppm) the record is weighted at an integer multiple of its rate of at
    least 1 kHz and taken back to its own samples (:mod:`loader_model.iso2631.upsampling`): at 200 Hz this
    keeps a_w within 0.1 % of exact causal filtering where the direct design alone is up to
    6.3 % high (Wj).

    Parameters
    ----------
    acceleration : array_like
        Unweighted acceleration samples in m/s² (rad/s² for rotational axes), 1-D and finite.
    sample_rate_hz : float
        Sample rate, at least :data:`MINIMUM_SAMPLE_RATE_HZ` of the weighting.
    weighting : str
        One of ``"Wk", "Wd", "Wc", "We", "Wj", "Wf"``.
    initial_state : {"steady", "rest"}
        How the filter starts, see :data:`INITIAL_STATES`.

    Returns
    -------
    numpy.ndarray
        Weighted acceleration, same length and unit as ``acceleration``.

    Examples
    --------
    >>> import numpy as np
    >>> t_s = np.arange(0.0, 20.0, 1e-3)
    >>> a_w = weight_acceleration(np.sin(2 * np.pi * 5.0 * t_s), 1000.0, "Wk")
    >>> round(float(np.sqrt(2.0 * np.mean(a_w[5000:] ** 2))), 3)
    1.039
    """
    check_weighting_name(weighting)
    design = design_weighting_filter(weighting, sample_rate_hz)
    factor = upsampling_factor(design.sample_rate_hz)
    if factor == 1:
        return design.apply(acceleration, initial_state=initial_state)
    design.check(acceleration, initial_state)  # length and initial state at the input rate
    fine = design_weighting_filter(weighting, factor * design.sample_rate_hz)
    signal = as_signal(acceleration, "acceleration")
    return weight_upsampled(signal, fine.sos, fine.fir, factor, initial_state == "steady")
