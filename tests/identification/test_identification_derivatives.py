"""Savitzky-Golay derivatives: closed-form sine derivatives, window choice, matched kernel."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import freqz, savgol_coeffs

from loader_model.identification.derivatives import (
    POLYORDER,
    acceleration_kernel,
    savgol_derivative,
    savgol_window,
)


@pytest.mark.parametrize("sample_rate_hz", [200.0, 500.0, 1000.0])
def test_window_meets_the_cutoff_and_is_the_shortest(sample_rate_hz: float) -> None:
    cutoff_hz = 10.0
    window = savgol_window(sample_rate_hz, cutoff_hz)
    assert window % 2 == 1

    def gain(w: int, f_hz: float) -> float:
        _, h = freqz(savgol_coeffs(w, POLYORDER), worN=[f_hz], fs=sample_rate_hz)
        return float(np.abs(h[0]))

    assert gain(window, cutoff_hz * 1.001) < 1.0 / np.sqrt(2.0)
    assert gain(window - 2, cutoff_hz * 0.99) > 1.0 / np.sqrt(2.0)
    assert gain(window, 1.0) > 0.99  # the lift test's motion (about 1 Hz) passes


def test_window_scales_with_the_sample_rate() -> None:
    # Same cutoff, twice the rate: about twice the samples (the same time span).
    w500, w1000 = savgol_window(500.0, 10.0), savgol_window(1000.0, 10.0)
    assert abs(w1000 / w500 - 2.0) < 0.05


@pytest.mark.parametrize("sample_rate_hz", [500.0, 1000.0])
def test_sine_derivatives_match_closed_form(sample_rate_hz: float) -> None:
    # y = A sin(2π f t): y' = A ω cos, y'' = −A ω² sin. At f = 1 Hz, a tenth of the 10 Hz
    # cutoff, the value and slope are within 2e-4 and the curvature within 1 % (measured
    # 0.85 %: the second-derivative filter attenuates earlier than the smoothing).
    f_hz, amplitude = 1.0, 0.2
    omega = 2 * np.pi * f_hz
    t = np.arange(0.0, 5.0, 1.0 / sample_rate_hz)
    y = amplitude * np.sin(omega * t)
    window = savgol_window(sample_rate_hz)
    inner = slice(window, -window)
    d0 = savgol_derivative(y, sample_rate_hz, 0, window)
    d1 = savgol_derivative(y, sample_rate_hz, 1, window)
    d2 = savgol_derivative(y, sample_rate_hz, 2, window)
    np.testing.assert_allclose(d0[inner], y[inner], rtol=0, atol=2e-4 * amplitude)
    exact1 = amplitude * omega * np.cos(omega * t)
    np.testing.assert_allclose(d1[inner], exact1[inner], rtol=0, atol=2e-4 * amplitude * omega)
    exact2 = -amplitude * omega**2 * np.sin(omega * t)
    np.testing.assert_allclose(d2[inner], exact2[inner], rtol=0, atol=1e-2 * amplitude * omega**2)


def test_noise_is_reduced_by_the_smoothing() -> None:
    rng = np.random.default_rng(1)
    fs = 500.0
    noise = rng.standard_normal(50_000)
    window = savgol_window(fs, 10.0)
    smoothed = savgol_derivative(noise, fs, 0, window)
    # White noise through a 10 Hz low-pass at 500 Hz keeps roughly 2·10/250 of its power.
    assert 0.03 < np.var(smoothed) < 0.2


def test_acceleration_kernel_is_the_low_pass_inside_the_second_derivative() -> None:
    fs, window = 500.0, 55
    dt = 1.0 / fs
    h2 = acceleration_kernel(window, fs)
    assert h2.size == window - 2
    np.testing.assert_allclose(h2.sum(), 1.0, rtol=1e-12)
    c2 = savgol_coeffs(window, POLYORDER, deriv=2, delta=dt, use="dot")
    np.testing.assert_allclose(np.convolve(h2, [1.0, -2.0, 1.0]), c2 * dt**2, rtol=0, atol=1e-14)
    # Applied to any signal: c2 ∗ x = h2 ∗ (second difference of x) / dt².
    x = np.random.default_rng(0).standard_normal(400)
    direct = np.correlate(x, c2, mode="valid")
    second_difference = (x[2:] - 2 * x[1:-1] + x[:-2]) / dt**2
    through_kernel = np.correlate(second_difference, h2, mode="valid")
    np.testing.assert_allclose(through_kernel, direct, rtol=1e-9, atol=1e-9 * np.abs(direct).max())


def test_bad_arguments_are_named() -> None:
    with pytest.raises(ValueError, match="sample rate"):
        savgol_window(0.0)
    with pytest.raises(ValueError, match="cutoff"):
        savgol_window(100.0, 30.0)
    with pytest.raises(ValueError, match="order"):
        savgol_derivative(np.zeros(100), 100.0, 3, 11)
    with pytest.raises(ValueError, match="longer than the record"):
        savgol_derivative(np.zeros(10), 100.0, 1, 11)
