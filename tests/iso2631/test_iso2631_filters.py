"""Discrete ISO 2631-1 weighting filters against the exact continuous response (ISO 8041 limits)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.signal
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.iso2631 import (
    MINIMUM_SAMPLE_RATE_HZ,
    NOMINAL_BAND_HZ,
    WEIGHTING_NAMES,
    design_weighting_filter,
    settling_time_s,
    weight_acceleration,
    weighting_num_den,
)
from tests.iso2631.test_iso2631_annex_a import annex_a_response, third_octave_hz

#: ISO 8041 tolerances used by the brief: ±1 dB magnitude and ±6° phase in the pass band.
TOLERANCE_DB = 1.0
TOLERANCE_DEG = 6.0

#: Sample rates checked per weighting; Wf (0.02-4 Hz) is also checked at its lowest rate 10 Hz.
RATES = [(name, rate) for name in WEIGHTING_NAMES for rate in (200.0, 1000.0, 10000.0)] + [
    ("Wf", 10.0)
]


def response_errors(name: str, sample_rate_hz: float) -> tuple[float, float]:
    """Worst |magnitude error| (dB) and |phase error| (deg) over the band, on a dense grid and
    at the one-third-octave frequencies, from the filter's own coefficients (scipy)."""
    low_hz, high_hz = NOMINAL_BAND_HZ[name]
    frequency_hz = np.concatenate(
        [np.geomspace(low_hz, high_hz, 1500), third_octave_hz(low_hz, high_hz)]
    )
    design = design_weighting_filter(name, sample_rate_hz)
    _, sos_response = scipy.signal.sosfreqz(
        np.array(design.sos), worN=frequency_hz, fs=sample_rate_hz
    )
    _, fir_response = scipy.signal.freqz(design.fir, 1.0, worN=frequency_hz, fs=sample_rate_hz)
    ratio = sos_response * fir_response / annex_a_response(name, frequency_hz)
    return (
        float(np.max(np.abs(20 * np.log10(np.abs(ratio))))),
        float(np.max(np.abs(np.angle(ratio, deg=True)))),
    )


@pytest.mark.parametrize(("name", "sample_rate_hz"), RATES)
def test_discrete_filter_within_iso_8041_tolerance_over_the_band(
    name: str, sample_rate_hz: float
) -> None:
    magnitude_db, phase_deg = response_errors(name, sample_rate_hz)
    assert magnitude_db < TOLERANCE_DB
    assert phase_deg < TOLERANCE_DEG
    design = design_weighting_filter(name, sample_rate_hz)
    # The design's own record of its accuracy agrees with this independent check.
    assert design.max_magnitude_error_db == pytest.approx(magnitude_db, rel=0.05, abs=1e-5)
    assert design.band_hz == NOMINAL_BAND_HZ[name]


@pytest.mark.parametrize("name", ["Wk", "Wd", "Wc", "We", "Wj"])
def test_discrete_filter_is_much_better_than_tolerance_at_1khz(name: str) -> None:
    magnitude_db, phase_deg = response_errors(name, 1000.0)
    assert magnitude_db < 0.01
    assert phase_deg < 0.05


def test_bilinear_transform_would_fail_at_200_hz() -> None:
    """Why the design is not a plain bilinear transform: its 1/f slopes warp near fs/2."""
    numerator, denominator = weighting_num_den("Wk")
    b, a = scipy.signal.bilinear(numerator, denominator, fs=200.0)
    _, response = scipy.signal.freqz(b, a, worN=[80.0], fs=200.0)
    assert abs(20 * np.log10(abs(response[0] / annex_a_response("Wk", 80.0)))) > 3.0


@pytest.mark.parametrize("name", WEIGHTING_NAMES)
def test_rates_below_the_minimum_are_refused(name: str) -> None:
    minimum = MINIMUM_SAMPLE_RATE_HZ[name]
    assert minimum == 2.5 * NOMINAL_BAND_HZ[name][1]
    with pytest.raises(
        ValueError,
        match=rf"sample_rate_hz must be at least {minimum:g} Hz for weighting {name} .*; got 199.0 Hz"
        if name != "Wf"
        else r"sample_rate_hz must be at least 10 Hz for weighting Wf .*; got 9.5 Hz",
    ):
        design_weighting_filter(name, 199.0 if name != "Wf" else 9.5)


#: (weighting, sine frequency, sample rate, rtol): at 200 Hz the designs are accurate to 0.09 dB
#: (1 %) over the whole band (Wj: 0.56 dB), at 500 Hz and above to better than 0.03 dB.
SINES = [
    ("Wk", 5.0, 1000.0, 2e-3),
    ("Wk", 1.0, 200.0, 1.5e-2),
    ("Wd", 2.0, 500.0, 2e-3),
    ("We", 0.8, 200.0, 1.5e-2),
    ("Wc", 16.0, 1000.0, 2e-3),
    ("Wj", 40.0, 1000.0, 2e-3),
    ("Wf", 0.16, 20.0, 2e-3),
]


@pytest.mark.parametrize(("name", "frequency_hz", "sample_rate_hz", "rtol"), SINES)
def test_sine_gives_its_known_weighted_rms(
    name: str, frequency_hz: float, sample_rate_hz: float, rtol: float
) -> None:
    """Steady-state a_w of A sin(2π f t) is A |W(f)| / sqrt(2) (ISO 2631-1 6.1)."""
    amplitude = 1.7
    periods_settle = math.ceil(2 * settling_time_s(name) * frequency_hz)
    periods = periods_settle + 20
    time_s = np.arange(round(periods * sample_rate_hz / frequency_hz)) / sample_rate_hz
    weighted = weight_acceleration(
        amplitude * np.sin(2 * np.pi * frequency_hz * time_s), sample_rate_hz, name
    )
    steady = weighted[round(periods_settle * sample_rate_hz / frequency_hz) :]
    expected = amplitude * abs(annex_a_response(name, frequency_hz)) / math.sqrt(2)
    assert math.sqrt(np.mean(steady**2)) == pytest.approx(expected, rel=rtol)


def test_steady_initial_state_removes_the_offset_transient() -> None:
    sample_rate_hz = 500.0
    time_s = np.arange(0.0, 6.0, 1 / sample_rate_hz)
    offset = 9.81 + 0.0 * time_s  # gravity on a vertical accelerometer
    steady = weight_acceleration(offset, sample_rate_hz, "Wk")
    at_rest = weight_acceleration(offset, sample_rate_hz, "Wk", initial_state="rest")
    np.testing.assert_allclose(steady, 0.0, atol=1e-9)
    assert np.max(np.abs(at_rest)) > 1.0


@settings(max_examples=20, deadline=None)
@given(
    gain=st.floats(min_value=-50.0, max_value=50.0, allow_nan=False),
    seed=st.integers(min_value=0, max_value=2**32 - 1),
)
def test_weighting_is_linear(gain: float, seed: int) -> None:
    signal = np.random.default_rng(seed).standard_normal(1500)
    weighted = weight_acceleration(signal, 500.0, "Wk")
    atol = 1e-10 * max(1.0, abs(gain)) * float(np.max(np.abs(weighted)))
    np.testing.assert_allclose(
        weight_acceleration(gain * signal, 500.0, "Wk"), gain * weighted, rtol=1e-9, atol=atol
    )


@pytest.mark.parametrize(
    ("rate_hz", "look_ahead"), [(1000.0, 0), (2000.0, 0), (500.0, 31), (200.0, 31)]
)
def test_filter_is_causal_up_to_the_interpolation_look_ahead(
    rate_hz: float, look_ahead: int
) -> None:
    """Changing the signal from sample n on leaves the output before n - look_ahead unchanged.

    From 1 kHz on the filter is strictly causal; below it the band-limited interpolation of the
    internal upsampling looks 31 input samples ahead (loader_model.iso2631.upsampling).
    """
    rng = np.random.default_rng(3)
    signal = rng.standard_normal(6000)
    changed = signal.copy()
    changed[4000:] += 5.0
    before = weight_acceleration(signal, rate_hz, "Wd")
    after = weight_acceleration(changed, rate_hz, "Wd")
    np.testing.assert_array_equal(before[: 4000 - look_ahead], after[: 4000 - look_ahead])
    assert before[4000 - look_ahead] != after[4000 - look_ahead] or look_ahead == 0


def test_frequency_response_method_matches_exact_in_band() -> None:
    design = design_weighting_filter("Wk", 1000.0)
    frequency_hz = np.array([0.5, 5.0, 50.0])
    np.testing.assert_allclose(
        design.frequency_response(frequency_hz), annex_a_response("Wk", frequency_hz), rtol=1e-3
    )
    assert design.sos.flags.writeable is False


def test_bad_signals_are_refused() -> None:
    good = np.zeros(2000)
    with pytest.raises(ValueError, match=r"acceleration must be finite; got nan at index 3"):
        weight_acceleration(np.where(np.arange(2000) == 3, np.nan, good), 500.0, "Wk")
    with pytest.raises(ValueError, match=r"acceleration must be finite; got inf at index 0"):
        weight_acceleration(np.where(np.arange(2000) == 0, np.inf, good), 500.0, "Wk")
    with pytest.raises(ValueError, match=r"acceleration must not be empty; got 0 samples"):
        weight_acceleration([], 500.0, "Wk")
    with pytest.raises(ValueError, match=r"acceleration must be a 1-D array; got shape \(2, 2\)"):
        weight_acceleration(np.zeros((2, 2)), 500.0, "Wk")
    with pytest.raises(
        ValueError,
        match=r"acceleration is too short for weighting Wk: 1000 samples = 2 s at 500 Hz; "
        r"the filter needs at least its settling time 2.591 s",
    ):
        weight_acceleration(good[:1000], 500.0, "Wk")
    with pytest.raises(ValueError, match=r"weighting must be one of .*; got 'Wz'"):
        weight_acceleration(good, 500.0, "Wz")
    with pytest.raises(ValueError, match=r"sample_rate_hz must be a finite number > 0 Hz; got nan"):
        weight_acceleration(good, math.nan, "Wk")
    with pytest.raises(
        ValueError, match=r"initial_state must be one of \('steady', 'rest'\); got 'x'"
    ):
        weight_acceleration(good, 500.0, "Wk", initial_state="x")
