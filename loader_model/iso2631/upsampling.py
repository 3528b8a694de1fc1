"""Weighting of records sampled below 1 kHz through internal upsampling.

At 200 Hz the discrete design of :mod:`loader_model.iso2631.filters` alone reads a_w 0.5-1 % high
for Wk, Wd, Wc, We and 6.3 % high for Wj below 16 Hz (``python -m tests.iso_accuracy``): its
FIR correction cannot hold the shape of the 100 Hz band limit at the 100 Hz Nyquist frequency.
At 1 kHz and above it agrees with exact causal filtering to 3e-4. So a record sampled below
:data:`INTERNAL_RATE_HZ` is upsampled by the smallest integer factor ``L`` that reaches it
(band-limited polyphase interpolation, :func:`~loader_model.iso2631._digital.interpolate`, as
:func:`scipy.signal.resample_poly` does it), weighted at ``L fs``
and taken back at every ``L``-th sample, which keeps the output aligned with the input samples.

The interpolation is zero-phase: the weighted sample ``n`` depends on the input up to 31
samples after ``n`` (the interpolation filter's half-length less one: its end taps are zero),
so below 1 kHz the weighting is causal up to that look-ahead. The record is processed in blocks
of :data:`BLOCK_SAMPLES` input samples with overlapping margins and the filter state carried
across, so memory stays at about ``L`` times one block whatever the record's length. Beyond its
ends the record is continued with its first and last value, and each phase of the
interpolation filter has a DC gain of exactly one, so an offset (gravity) passes without ripple
or edge transient.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from loader_model.iso2631._digital import (
    dc_gain,
    fir_filter,
    interpolate,
    sos_filter,
    sos_steady_state,
)

__all__ = [
    "BLOCK_SAMPLES",
    "INTERNAL_RATE_HZ",
    "RATE_TOLERANCE",
    "upsampling_factor",
    "weight_upsampled",
]

#: Records sampled below this rate are weighted at an integer multiple of their rate reaching it.
INTERNAL_RATE_HZ = 1000.0
#: Relative shortfall of a sample rate below a multiple of :data:`INTERNAL_RATE_HZ` still taken as
#: that multiple: a rate measured from time stamps is off by their rounding over the record's
#: span (Unix stamps, resolved to 2.4e-7 s, over a 3 s record: 8e-8) and by the logger's crystal
#: (typically 20-50 ppm), so a nominal 1 kHz record must not switch to upsampling by 2 for that.
#: The direct design is as accurate 100 ppm below 1 kHz as at it.
RATE_TOLERANCE = 1e-4
#: Input samples per processing block.
BLOCK_SAMPLES = 1 << 18
#: Half-length of the interpolation filter in input samples, and its Kaiser window's beta
#: (about 80 dB stop band; flat to 0.1 % up to 0.4 fs, where scipy's default, 10 samples and
#: beta 5, loses 1 %).
_HALF_LENGTH = 32
_KAISER_BETA = 8.0
#: Input samples of overlap on each side of a block (covers the filter's half-length).
_MARGIN = 48


@functools.cache
def _interpolator(factor: int) -> np.ndarray:
    """Kaiser-windowed sinc with cut-off fs_in / 2 (:func:`scipy.signal.firwin`'s design), each
    phase scaled to a DC gain of 1 / ``factor``."""
    numtaps = 2 * _HALF_LENGTH * factor + 1
    lag = np.arange(numtaps) - _HALF_LENGTH * factor
    taps = np.sinc(lag / factor) * np.kaiser(numtaps, _KAISER_BETA)
    for phase in range(factor):  # every output phase passes a constant exactly (no ripple)
        taps[phase::factor] /= factor * np.sum(taps[phase::factor])
    taps.setflags(write=False)
    return taps


def upsampling_factor(sample_rate_hz: float) -> int:
    """Smallest integer L >= 1 with L x ``sample_rate_hz`` >= :data:`INTERNAL_RATE_HZ`, within
    :data:`RATE_TOLERANCE`."""
    return max(1, math.ceil(INTERNAL_RATE_HZ * (1.0 - RATE_TOLERANCE) / sample_rate_hz))


def weight_upsampled(
    signal: np.ndarray, sos: np.ndarray, fir: np.ndarray, factor: int, steady: bool
) -> np.ndarray:
    """Weight ``signal`` with the filter (``sos``, ``fir``) designed for ``factor`` x its rate.

    Parameters
    ----------
    signal : numpy.ndarray
        Checked 1-D finite samples.
    sos, fir : numpy.ndarray
        Second-order sections and FIR correction of the weighting at the upsampled rate.
    factor : int
        Upsampling factor L >= 2.
    steady : bool
        Start from the steady state of the first sample (else from rest).

    Returns
    -------
    numpy.ndarray
        Weighted samples at the input rate, same length as ``signal``.
    """
    if steady:
        sos_state = sos_steady_state(sos, signal[0])
        fir_state = np.full(fir.size - 1, dc_gain(sos) * signal[0])
    else:
        sos_state = np.zeros(2 * sos.shape[0])
        fir_state = np.zeros(fir.size - 1)
    out = np.empty_like(signal)
    for start in range(0, signal.size, BLOCK_SAMPLES):
        stop = min(signal.size, start + BLOCK_SAMPLES)
        low, high = start - _MARGIN, stop + _MARGIN
        # beyond the record's ends the signal is continued with its first and last value
        piece = signal[np.clip(np.arange(low, high), 0, signal.size - 1)]
        upsampled = interpolate(piece, factor, _interpolator(factor))
        core = upsampled[_MARGIN * factor : (_MARGIN + stop - start) * factor]
        filtered, sos_state = sos_filter(sos, core, sos_state)
        filtered, fir_state = fir_filter(fir, filtered, fir_state)
        out[start:stop] = filtered[::factor]
    return out
