"""ISO 2631-1 clause 6 values, paper Eq. 49 and 50, A(8) and Directive 2002/44/EC values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from loader_model.iso2631 import (
    A8_ACTION_VALUE_M_S2,
    A8_LIMIT_VALUE_M_S2,
    PAPER_K_FACTORS,
    VDV_ACTION_VALUE_M_S175,
    VDV_LIMIT_VALUE_M_S175,
    assess_directive_2002_44,
    crest_factor,
    daily_exposure_a8,
    daily_vibration_dose_value,
    estimated_vibration_dose_value,
    maximum_transient_vibration_value,
    running_rms,
    vibration_dose_value,
    vibration_total_value,
    weight_acceleration,
    weighted_rms,
)
from tests.iso2631.test_iso2631_annex_a import annex_a_response

RATE_HZ = 1000.0
samples = arrays(
    np.float64,
    st.integers(min_value=1, max_value=300),
    elements=st.integers(min_value=-10_000, max_value=10_000).map(lambda i: i / 100.0),
)


def sine(amplitude: float, frequency_hz: float, duration_s: float, rate_hz: float = RATE_HZ):
    time_s = np.arange(round(duration_s * rate_hz)) / rate_hz
    return amplitude * np.sin(2 * np.pi * frequency_hz * time_s)


def test_rms_of_a_sine_is_amplitude_over_sqrt2() -> None:
    """Eq. 49 over whole periods of A sin: A / sqrt(2) (rectangle rule exact here)."""
    assert weighted_rms(sine(0.8, 3.0, 2.0)) == pytest.approx(0.8 / math.sqrt(2), rel=1e-12)


def test_sawtooth_burst_gives_its_known_weighted_rms() -> None:
    """A periodic burst (3 periods of a 4 Hz sawtooth, then 0.25 s rest, repeated every 1 s)
    weighted by Wk: the steady-state a_w follows from Parseval, sum over the harmonics k Hz of
    |W(k)|^2 |X_k|^2 with the exact Annex A weighting (independent of the filter design)."""
    rate_hz, period_samples, periods = 1000.0, 1000, 8
    time_s = np.arange(period_samples) / rate_hz
    burst = np.where(time_s < 0.75, 2.0 * ((4.0 * time_s) % 1.0) - 1.0, 0.0)
    amplitude_m_s2 = 1.3
    one_period = amplitude_m_s2 * burst
    weighted = weight_acceleration(np.tile(one_period, periods), rate_hz, "Wk")
    steady = weighted[-2 * period_samples :]

    spectrum = np.fft.rfft(one_period) / period_samples
    harmonic_hz = np.fft.rfftfreq(period_samples, 1.0 / rate_hz)
    one_sided = np.abs(spectrum) ** 2 * np.where((harmonic_hz > 0) & (harmonic_hz < 500), 2, 1)
    # W(0) = 0 (band-limiting high-pass): the DC term does not count.
    weights = np.abs(annex_a_response("Wk", harmonic_hz[1:])) ** 2
    expected = math.sqrt(np.sum(weights * one_sided[1:]))
    assert weighted_rms(steady) == pytest.approx(expected, rel=2e-3)
    # The weighting matters here: a_w differs from the unweighted r.m.s. by more than 10 %.
    assert abs(expected / weighted_rms(one_period) - 1.0) > 0.1


def test_vdv_of_a_sine_matches_closed_form() -> None:
    """VDV = [∫ A^4 sin^4]^(1/4) = A (3T/8)^(1/4) over whole periods (ISO 2631-1 6.3.2)."""
    amplitude, duration_s = 2.0, 3.0
    assert vibration_dose_value(sine(amplitude, 5.0, duration_s), RATE_HZ) == pytest.approx(
        amplitude * (3 * duration_s / 8) ** 0.25, rel=1e-12
    )


def test_vdv_of_a_half_sine_shock_matches_closed_form() -> None:
    """One half-sine shock A sin(π t / D), 0 <= t <= D: ∫ = 3 A^4 D / 8."""
    amplitude, shock_s = 4.0, 0.1
    signal = np.zeros(2000)
    signal[500:600] = amplitude * np.sin(np.pi * np.arange(100) / 100)
    assert vibration_dose_value(signal, RATE_HZ) == pytest.approx(
        amplitude * (3 * shock_s / 8) ** 0.25, rel=1e-12
    )


def test_estimated_vdv_and_sine_ratio() -> None:
    """eVDV = 1.4 a_w T^(1/4); for a sine VDV / (a_w T^(1/4)) = (3/2)^(1/4)."""
    signal = sine(1.0, 2.0, 16.0)
    rms = weighted_rms(signal)
    assert estimated_vibration_dose_value(rms, 16.0) == pytest.approx(1.4 * rms * 2.0, rel=1e-12)
    assert vibration_dose_value(signal, RATE_HZ) / (rms * 16.0**0.25) == pytest.approx(
        1.5**0.25, rel=1e-12
    )


def test_crest_factor_of_sine_and_square_wave() -> None:
    assert crest_factor(sine(3.0, 2.0, 1.0, rate_hz=4000.0)) == pytest.approx(
        math.sqrt(2), rel=1e-6
    )
    assert crest_factor(np.sign(sine(3.0, 2.0, 1.0) + 1e-9)) == pytest.approx(1.0, rel=1e-12)


def test_running_rms_linear_and_mtvv_of_a_burst() -> None:
    """A 2 s sine burst of amplitude A in silence: the 1 s running r.m.s. peaks at A/sqrt(2)
    where the window lies inside the burst, and is 0 where it lies in the silence."""
    signal = np.concatenate([np.zeros(3000), sine(2.0, 4.0, 2.0), np.zeros(3000)])
    values = running_rms(signal, RATE_HZ)
    assert values.size == signal.size - 1000 + 1
    assert maximum_transient_vibration_value(signal, RATE_HZ) == pytest.approx(
        2.0 / math.sqrt(2), rel=1e-9
    )
    np.testing.assert_allclose(values[:2000], 0.0, atol=1e-12)
    np.testing.assert_allclose(values[3999:4001], 2.0 / math.sqrt(2), rtol=1e-9)


def test_running_rms_exponential_step_response() -> None:
    """Constant c from t = 0: a_w(t0)^2 = c^2 (1 - exp(-t0/τ)) (ISO 2631-1 6.3.1, exponential)."""
    constant, tau_s = 0.7, 0.5
    values = running_rms(
        np.full(3000, constant), RATE_HZ, integration_time_s=tau_s, method="exponential"
    )
    t0_s = (np.arange(3000) + 1) / RATE_HZ
    np.testing.assert_allclose(
        values, constant * np.sqrt(1 - np.exp(-t0_s / tau_s)), rtol=2e-3, atol=0.0
    )
    assert maximum_transient_vibration_value(
        np.full(3000, constant), RATE_HZ, method="exponential"
    ) == pytest.approx(constant * math.sqrt(1 - math.exp(-3.0)), rel=1e-3)


def test_total_value_eq_50_with_the_paper_k_factors() -> None:
    rms = {"x": 0.3, "y": 0.2, "z": 0.5, "pitch": 0.6}
    expected = math.sqrt(0.3**2 + 0.2**2 + 0.5**2 + (0.4 * 0.6) ** 2)
    assert vibration_total_value(rms, PAPER_K_FACTORS) == pytest.approx(expected, rel=1e-12)
    assert dict(PAPER_K_FACTORS) == {"x": 1.0, "y": 1.0, "z": 1.0, "pitch": 0.4}


@settings(max_examples=40, deadline=None)
@given(
    signal=samples,
    gain=st.floats(min_value=1e-3, max_value=1e3),
    negative=st.booleans(),
)
def test_rms_and_vdv_scale_linearly_with_amplitude(
    signal: np.ndarray, gain: float, negative: bool
) -> None:
    gain = -gain if negative else gain
    if not np.any(signal):
        signal = signal + 1.0
    assert weighted_rms(gain * signal) == pytest.approx(
        abs(gain) * weighted_rms(signal), rel=1e-12, abs=1e-300
    )
    assert vibration_dose_value(gain * signal, RATE_HZ) == pytest.approx(
        abs(gain) * vibration_dose_value(signal, RATE_HZ), rel=1e-12, abs=1e-300
    )


@settings(max_examples=40, deadline=None)
@given(first=samples, second=samples)
def test_vdv_fourth_powers_add_over_concatenation(first: np.ndarray, second: np.ndarray) -> None:
    joined = vibration_dose_value(np.concatenate([first, second]), RATE_HZ) ** 4
    parts = vibration_dose_value(first, RATE_HZ) ** 4 + vibration_dose_value(second, RATE_HZ) ** 4
    assert joined == pytest.approx(parts, rel=1e-9, abs=1e-300)


@settings(max_examples=40, deadline=None)
@given(
    rms=st.lists(st.integers(0, 10_000).map(lambda i: i / 1000.0), min_size=1, max_size=4),
    scale=st.one_of(st.just(0.0), st.floats(min_value=1e-6, max_value=100.0)),
)
def test_total_value_is_homogeneous_and_bounded(rms: list[float], scale: float) -> None:
    axes = ["x", "y", "z", "pitch"][: len(rms)]
    values = dict(zip(axes, rms, strict=True))
    total = vibration_total_value(values, PAPER_K_FACTORS)
    scaled = vibration_total_value({a: scale * v for a, v in values.items()}, PAPER_K_FACTORS)
    assert scaled == pytest.approx(scale * total, rel=1e-12, abs=1e-300)
    largest = max(PAPER_K_FACTORS[a] * v for a, v in values.items())
    assert largest <= total * (1 + 1e-12)
    assert total <= math.sqrt(len(rms)) * largest * (1 + 1e-12)


@settings(max_examples=40, deadline=None)
@given(
    rms=st.floats(min_value=0.0, max_value=5.0),
    hours=st.floats(min_value=0.01, max_value=12.0),
    fraction=st.floats(min_value=0.0, max_value=1.0),
)
def test_a8_is_unchanged_by_splitting_an_exposure(
    rms: float, hours: float, fraction: float
) -> None:
    whole = daily_exposure_a8(rms, hours * 3600.0)
    split = daily_exposure_a8(
        [rms, rms], [fraction * hours * 3600.0, (1 - fraction) * hours * 3600.0]
    )
    assert split == pytest.approx(whole, rel=1e-9, abs=1e-300)


def test_a8_and_daily_vdv_known_values() -> None:
    assert daily_exposure_a8(1.0, 2 * 3600.0) == pytest.approx(0.5, rel=1e-12)
    assert daily_exposure_a8([1.0, 0.5], [2 * 3600.0, 4 * 3600.0]) == pytest.approx(
        math.sqrt((1.0 * 2 + 0.25 * 4) / 8), rel=1e-12
    )
    assert daily_vibration_dose_value(10.0, 3600.0, 8 * 3600.0) == pytest.approx(
        10.0 * 8**0.25, rel=1e-12
    )
    assert daily_vibration_dose_value([3.0, 4.0], [60.0, 60.0], [60.0, 60.0]) == pytest.approx(
        (3.0**4 + 4.0**4) ** 0.25, rel=1e-12
    )


@pytest.mark.parametrize(
    ("a8", "vdv", "a8_status", "vdv_status"),
    [
        (0.3, 5.0, "below action value", "below action value"),
        (0.5, 9.1, "below action value", "below action value"),
        (0.6, 10.0, "action value exceeded", "action value exceeded"),
        (1.2, 22.0, "limit value exceeded", "limit value exceeded"),
    ],
)
def test_directive_2002_44_values(a8: float, vdv: float, a8_status: str, vdv_status: str) -> None:
    assert (A8_ACTION_VALUE_M_S2, A8_LIMIT_VALUE_M_S2) == (0.5, 1.15)
    assert (VDV_ACTION_VALUE_M_S175, VDV_LIMIT_VALUE_M_S175) == (9.1, 21.0)
    result = assess_directive_2002_44(a8_m_s2=a8, vdv_m_s175=vdv)
    assert (result.a8_status, result.vdv_status) == (a8_status, vdv_status)


def test_crest_factor_of_a_signal_without_vibration_is_undefined() -> None:
    assert math.isnan(crest_factor(np.zeros(10)))
    assert crest_factor(np.r_[np.zeros(9), 1e-100]) == pytest.approx(math.sqrt(10), rel=1e-12)


def test_bad_metric_inputs_are_refused() -> None:
    with pytest.raises(ValueError, match=r"weighted_acceleration must not be empty; got 0 samples"):
        weighted_rms([])
    with pytest.raises(
        ValueError, match=r"weighted_acceleration must be finite; got nan at index 1"
    ):
        vibration_dose_value([0.0, math.nan], RATE_HZ)
    with pytest.raises(
        ValueError, match=r"method must be one of \('linear', 'exponential'\); got 'x'"
    ):
        running_rms(np.ones(10), RATE_HZ, method="x")
    with pytest.raises(
        ValueError,
        match=r"integration_time_s must span 1 to 10 samples of the signal \(0.01 s at 1000 Hz\); "
        r"got 1.0 s",
    ):
        maximum_transient_vibration_value(np.ones(10), RATE_HZ)
    with pytest.raises(
        ValueError, match=r"integration_time_s must be a finite number > 0 s; got -1"
    ):
        running_rms(np.ones(10), RATE_HZ, integration_time_s=-1)
    with pytest.raises(ValueError, match=r"sample_rate_hz must be a finite number > 0 Hz; got 0"):
        vibration_dose_value(np.ones(10), 0)
    with pytest.raises(ValueError, match=r"k_factors has no entry for axis 'roll'; given axes: "):
        vibration_total_value({"roll": 0.1}, PAPER_K_FACTORS)
    with pytest.raises(
        ValueError, match=r"k_factors\['x'\] must be a finite number >= 0; got -1.0"
    ):
        vibration_total_value({"x": 0.1}, {"x": -1.0})
    with pytest.raises(
        ValueError, match=r"weighted_rms_by_axis\['x'\] must be a finite number >= 0; got nan"
    ):
        vibration_total_value({"x": math.nan}, {"x": 1.0})
    with pytest.raises(
        ValueError, match=r"weighted_rms_by_axis must name at least one axis; got none"
    ):
        vibration_total_value({}, PAPER_K_FACTORS)
    with pytest.raises(ValueError, match=r"duration_s must be a finite number > 0 s; got 0"):
        estimated_vibration_dose_value(1.0, 0)
    with pytest.raises(
        ValueError, match=r"weighted_rms_m_s2 must be a finite number >= 0; got -0.5"
    ):
        estimated_vibration_dose_value(-0.5, 1.0)


def test_bad_exposure_inputs_are_refused() -> None:
    with pytest.raises(
        ValueError,
        match=r"weighted_rms_m_s2 and exposure_duration_s must have the same length; got 2 and 1",
    ):
        daily_exposure_a8([1.0, 2.0], 3600.0)
    with pytest.raises(
        ValueError, match=r"exposure_duration_s must be finite and >= 0 s; got -1.0"
    ):
        daily_exposure_a8(1.0, -1.0)
    with pytest.raises(
        ValueError, match=r"weighted_rms_m_s2 must be numbers >= 0 in m/s²; got 'a'"
    ):
        daily_exposure_a8("a", 1.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"measurement_duration_s must be > 0 s; got 0.0"):
        daily_vibration_dose_value(1.0, 0.0, 3600.0)
    with pytest.raises(
        ValueError,
        match=r"vdv_m_s175, measurement_duration_s and exposure_duration_s must have the same "
        r"length; got 1, 2 and 1",
    ):
        daily_vibration_dose_value(1.0, [1.0, 2.0], 3600.0)
    with pytest.raises(ValueError, match=r"give a8_m_s2 and/or vdv_m_s175; got neither"):
        assess_directive_2002_44()
    with pytest.raises(ValueError, match=r"a8_m_s2 must be finite and >= 0 m/s²; got nan"):
        assess_directive_2002_44(a8_m_s2=math.nan)
