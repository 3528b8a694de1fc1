r"""Smoothed signals and their time derivatives by Savitzky-Golay filtering (section 4.1).

The paper computed acceleration from the measured position and the pressure rate from the
measured pressure ("derivatives ... were calculated numerically, signal noise presented more of
a concern", section 4.1.2) without saying how. Here every signal that enters a regression is
passed through the *same* Savitzky-Golay filter (a least-squares polynomial of order
:data:`POLYORDER` fitted over a sliding window, Savitzky and Golay 1964), evaluated as value,
first or second derivative. Filtering all signals alike keeps the linear parts of Eq. 44 and
Eq. 48 consistent for the filtered signals.

A Savitzky-Golay *derivative* is not the derivative of the Savitzky-Golay *smoothed* signal:
the second-derivative filter c₂ equals a second difference followed by a low-pass kernel h₂
that differs from the smoothing filter near the cutoff. :func:`acceleration_kernel` returns
that h₂, so that the other terms of Eq. 44 can be filtered exactly as the acceleration is.

The window is chosen from the sample rate: the shortest odd window whose smoothing response
has fallen to 1/√2 (−3 dB) at the stated cutoff frequency or below (computed from the filter's
own coefficients, not from a rule of thumb). Signals well below the cutoff pass with their
derivatives intact; white sensor noise is cut to the band below the cutoff.
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.signal import freqz, savgol_coeffs, savgol_filter

__all__ = [
    "DEFAULT_CUTOFF_HZ",
    "POLYORDER",
    "acceleration_kernel",
    "savgol_derivative",
    "savgol_window",
]

#: Polynomial order of the Savitzky-Golay fit (cubic: exact for value, slope and curvature of
#: a cubic over the window).
POLYORDER = 3
#: Default −3 dB cutoff of the smoothing in Hz: above the boom's motion and pressure transients
#: of a lift test (a few Hz), below most of the sensor noise band at 0.2-2 kHz sampling.
DEFAULT_CUTOFF_HZ = 10.0


@functools.lru_cache(maxsize=256)
def _cutoff_of_window(window: int) -> float:
    """−3 dB frequency of the order-:data:`POLYORDER` smoothing filter, as a fraction of fs."""
    coefficients = savgol_coeffs(window, POLYORDER)
    frequencies = np.linspace(0.0, 0.5, 4097)
    _, response = freqz(coefficients, worN=frequencies, fs=1.0)
    below = np.flatnonzero(np.abs(response) < 1.0 / np.sqrt(2.0))
    return float(frequencies[below[0]]) if below.size else 0.5


def savgol_window(sample_rate_hz: float, cutoff_hz: float = DEFAULT_CUTOFF_HZ) -> int:
    """Shortest odd window (samples) whose −3 dB smoothing cutoff is at or below ``cutoff_hz``.

    Parameters
    ----------
    sample_rate_hz : float
        Sample rate fs in Hz.
    cutoff_hz : float
        Wanted −3 dB frequency in Hz, below the Nyquist frequency fs / 2.

    Returns
    -------
    int
        Odd window length ≥ :data:`POLYORDER` + 2.

    Raises
    ------
    ValueError
        If the rates are not positive finite numbers or the cutoff is not below fs / 4 (a
        shorter window than 5 samples would be needed).
    """
    if not (np.isfinite(sample_rate_hz) and sample_rate_hz > 0.0):
        raise ValueError(f"sample rate must be a positive number in Hz; got {sample_rate_hz!r}")
    if not (np.isfinite(cutoff_hz) and 0.0 < cutoff_hz < sample_rate_hz / 4.0):
        raise ValueError(
            f"derivative cutoff must be in (0, fs/4) = (0, {sample_rate_hz / 4.0:g}) Hz; "
            f"got {cutoff_hz!r}"
        )
    target = cutoff_hz / sample_rate_hz
    window = POLYORDER + 2
    while _cutoff_of_window(window) > target:
        window += 2
    return window


def savgol_derivative(
    signal: np.ndarray, sample_rate_hz: float, order: int, window: int
) -> np.ndarray:
    r"""Smoothed ``order``-th time derivative of a uniformly sampled signal.

    .. math:: \hat{y}^{(k)}(t_i) = \frac{d^k}{dt^k} \sum_{j=0}^{3} c_{ij} (t - t_i)^j
        \Big|_{t = t_i}

    with c_ij the least-squares cubic over the ``window`` samples centred at t_i; the ends use
    the polynomial fitted to the first / last window (``mode="interp"``).

    Parameters
    ----------
    signal : numpy.ndarray
        Samples, uniformly spaced at 1 / ``sample_rate_hz``.
    sample_rate_hz : float
        Sample rate in Hz.
    order : int
        0 (smoothed value), 1 or 2.
    window : int
        Odd window length, e.g. from :func:`savgol_window`; at most the signal length.

    Returns
    -------
    numpy.ndarray
        The smoothed derivative in (signal unit)/sᵏ.
    """
    if order not in (0, 1, 2):
        raise ValueError(f"derivative order must be 0, 1 or 2; got {order!r}")
    signal = np.asarray(signal, dtype=float)
    if window > signal.size:
        raise ValueError(
            f"the derivative window of {window} samples is longer than the record "
            f"({signal.size} samples); record longer or raise the cutoff"
        )
    return savgol_filter(
        signal, window, POLYORDER, deriv=order, delta=1.0 / sample_rate_hz, mode="interp"
    )


def acceleration_kernel(window: int, sample_rate_hz: float) -> np.ndarray:
    r"""Low-pass kernel h₂ hidden in the Savitzky-Golay second derivative.

    With c₂ the (symmetric) second-derivative coefficients of ``window`` samples,

    .. math::

        \hat{\ddot{x}}_i = \sum_{m} c_{2,m} x_{i+m}
        = \sum_{n} h_{2,n} \frac{x_{i+n+1} - 2 x_{i+n} + x_{i+n-1}}{\Delta t^2},

    h₂ (``window`` − 2 samples, centred, sums to 1) is c₂ Δt² summed twice. Filtering a signal
    with h₂ treats it like the acceleration estimate, up to the error of the second difference,
    (ω Δt)²/12 relative.

    Parameters
    ----------
    window : int
        Odd window of the Savitzky-Golay filter.
    sample_rate_hz : float
        Sample rate in Hz.

    Returns
    -------
    numpy.ndarray
        h₂, length ``window`` − 2; apply with ``scipy.ndimage.correlate1d``.
    """
    dt = 1.0 / sample_rate_hz
    c2 = savgol_coeffs(window, POLYORDER, deriv=2, delta=dt, use="dot")
    return np.cumsum(np.cumsum(c2 * dt * dt))[: window - 2]
