"""Long records are filtered and summed in segments (bounded memory): the values equal those of
one pass over the whole record, against SciPy and NumPy computed independently."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.signal

from loader_model.iso2631 import _digital, design_weighting_filter, metrics

#: A segment of 3 blocks, so a 2000-sample signal crosses 10 segment boundaries and ends in a
#: part-block.
SHORT_SEGMENT = 3 * _digital.BLOCK_SAMPLES


@pytest.fixture
def short_segments(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_digital, "SEGMENT_SAMPLES", SHORT_SEGMENT)
    monkeypatch.setattr(metrics, "SEGMENT_SAMPLES", SHORT_SEGMENT)


def _signal(size: int = 2000) -> np.ndarray:
    rng = np.random.default_rng(7)
    t_s = np.arange(size) / 1000.0
    return 9.81 + np.sin(2 * np.pi * 4.0 * t_s) + 0.3 * rng.standard_normal(size)


def test_sections_in_segments_filter_as_scipy(short_segments: None) -> None:
    sos = np.array(design_weighting_filter("Wk", 1000.0).sos)
    signal = _signal()
    zi = scipy.signal.sosfilt_zi(sos) * signal[0]
    expected, final = scipy.signal.sosfilt(sos, signal, zi=zi)
    got, state = _digital.sos_filter(sos, signal, _digital.sos_steady_state(sos, signal[0]))
    # the bound of test_iso2631_digital's Wk case at 1 kHz from the steady state
    assert np.max(np.abs(got - expected)) <= 1e-9 * np.max(np.abs(expected))
    assert np.max(np.abs(state - final.ravel())) <= 1e-9 * np.max(np.abs(final))


def test_fir_in_segments_matches_lfilter(short_segments: None) -> None:
    fir = np.array(design_weighting_filter("Wd", 500.0).fir)
    signal = _signal()
    got, history = _digital.fir_filter(fir, signal)
    np.testing.assert_allclose(got, scipy.signal.lfilter(fir, 1.0, signal), rtol=0, atol=1e-13)
    np.testing.assert_array_equal(history, signal[signal.size - (fir.size - 1) :])


def test_values_in_segments_equal_numpy_over_the_whole_record(short_segments: None) -> None:
    signal = _signal() - 9.81
    rate_hz, window = 1000.0, 250
    assert metrics.weighted_rms(signal) == pytest.approx(math.sqrt(np.mean(signal**2)), rel=1e-14)
    assert metrics.vibration_dose_value(signal, rate_hz) == pytest.approx(
        (np.sum(signal**4) / rate_hz) ** 0.25, rel=1e-14
    )
    assert metrics.crest_factor(signal) == pytest.approx(
        np.max(np.abs(signal)) / math.sqrt(np.mean(signal**2)), rel=1e-14
    )
    # running r.m.s. over windows of 0.25 s: a moving average of a² by convolution
    expected = np.sqrt(np.convolve(signal**2, np.ones(window) / window, mode="valid"))
    got = metrics.running_rms(signal, rate_hz, integration_time_s=window / rate_hz)
    np.testing.assert_allclose(got, expected, rtol=1e-12)
    mtvv = metrics.maximum_transient_vibration_value(
        signal, rate_hz, integration_time_s=window / rate_hz
    )
    assert mtvv == pytest.approx(np.max(expected), rel=1e-12)
    assert mtvv == np.max(got)  # the segment-wise maximum is the maximum of the whole series


def test_checked_signal_is_not_copied_and_the_record_is() -> None:
    from loader_model.iso2631 import VibrationRecord
    from loader_model.iso2631._checks import as_signal

    signal = _signal()
    assert as_signal(signal, "a") is signal
    record = VibrationRecord(time_s=np.arange(signal.size) / 1000.0, axes={"z": signal})
    assert not np.shares_memory(record.axes["z"], signal)
    signal[0] = 0.0
    assert record.axes["z"][0] != 0.0
