"""Accuracy of the discrete ISO 2631-1 weightings against exact causal Annex A filtering.

The reference is independent of ``loader_model.iso2631``: the Annex A.2 factors are written out
here as second-order sections (from ``tests/iso2631/test_iso2631_annex_a.py``'s parameter table) and
simulated in continuous time by :func:`scipy.signal.lsim` on a 10 kHz grid of the analytic
signal (exact for piecewise-linear input, which the fine grid makes the signal). Sines use the
steady-state gain ``|W(j 2π f)|`` directly. Run ``python -m tests.iso_accuracy`` for the table.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.signal

from loader_model.iso2631 import maximum_transient_vibration_value, weight_acceleration
from tests.iso2631.test_iso2631_annex_a import ANNEX_A_PARAMETERS, Q_BAND, annex_a_response

REFERENCE_RATE_HZ = 10_000.0
SINE_HZ = 10.0 ** (np.arange(-3, 16) / 10.0)  # one-third octaves 0.5 .. 31.5 Hz
WF_SINE_HZ = 10.0 ** (np.arange(-10, 7) / 10.0)  # Wf: its own band 0.1 .. 4 Hz


def _sections(name: str) -> list[tuple[list[float], list[float]]]:
    f1, f2, f3, f4, q4, f5, q5, f6, q6 = ANNEX_A_PARAMETERS[name]
    w1, w2, w3, w4, w5, w6 = (2 * math.pi * f for f in (f1, f2, f3, f4, f5, f6))
    sections = [
        ([1.0, 0.0, 0.0], [1.0, w1 / Q_BAND, w1**2]),
        ([w2**2], [1.0, w2 / Q_BAND, w2**2]),
    ]
    if math.isfinite(f4):
        numerator = [w4**2 / w3, w4**2] if math.isfinite(w3) else [w4**2]
        sections.append((numerator, [1.0, w4 / q4, w4**2]))
    if math.isfinite(f5):
        sections.append(([1.0, w5 / q5, w5**2], [1.0, w6 / q6, w6**2]))
    return sections


def exact_weighted(name: str, signal: np.ndarray, rate_hz: float) -> np.ndarray:
    """Causal continuous-time Annex A filtering of ``signal`` sampled at ``rate_hz``, from rest."""
    time_s = np.arange(signal.size) / rate_hz
    out = signal
    for numerator, denominator in _sections(name):
        _, out, _ = scipy.signal.lsim((numerator, denominator), out, time_s)
    return out


def shock(rate_hz: float, kind: str, duration_s: float = 12.0) -> np.ndarray:
    """A shock record sampled at ``rate_hz``: ``"half-sine"`` (0.1 s, 20 m/s² at t = 2 s) or
    ``"decay"`` (an 8 Hz oscillation from t = 2 s decaying with 0.3 s, 10 m/s²)."""
    t = np.arange(round(duration_s * rate_hz)) / rate_hz
    if kind == "half-sine":
        inside = (t >= 2.0) & (t <= 2.1)
        return np.where(inside, 20.0 * np.sin(np.pi * (t - 2.0) / 0.1), 0.0)
    late = t >= 2.0
    return np.where(
        late, 10.0 * np.exp(-(t - 2.0) / 0.3) * np.sin(2 * np.pi * 8.0 * (t - 2.0)), 0.0
    )


def metrics(weighted: np.ndarray, rate_hz: float) -> tuple[float, float, float]:
    """a_w (r.m.s. over the record), MTVV (1 s linear running r.m.s.) and VDV."""
    rms = float(np.sqrt(np.mean(weighted**2)))
    window = round(rate_hz)
    energy = np.concatenate([[0.0], np.cumsum(weighted**2)])
    mtvv = float(np.sqrt(np.max(energy[window:] - energy[:-window]) / window))
    vdv = float((np.sum(weighted**4) / rate_hz) ** 0.25)
    return rms, mtvv, vdv


def shock_errors(name: str, rate_hz: float, kind: str) -> tuple[float, float, float]:
    """Relative errors of a_w, MTVV and VDV of the package at ``rate_hz`` against the reference."""
    duration_s = 40.0 if name == "Wf" else 12.0  # longer than the filter's settling time
    exact = exact_weighted(name, shock(REFERENCE_RATE_HZ, kind, duration_s), REFERENCE_RATE_HZ)
    reference = metrics(exact, REFERENCE_RATE_HZ)
    record = shock(rate_hz, kind, duration_s)
    weighted = weight_acceleration(record, rate_hz, name, initial_state="rest")
    measured = metrics(weighted, rate_hz)
    measured = (measured[0], maximum_transient_vibration_value(weighted, rate_hz), measured[2])
    return tuple(m / r - 1.0 for m, r in zip(measured, reference, strict=True))


def sine_error(name: str, rate_hz: float, frequency_hz: float) -> float:
    """Relative error of a_w of a unit sine (steady state) against |W(j 2π f)| / √2."""
    periods = max(4, math.ceil(4.0 * frequency_hz))
    settle_s = 30.0 if name == "Wf" else 12.0
    t = np.arange(round((settle_s + periods / frequency_hz) * rate_hz)) / rate_hz
    weighted = weight_acceleration(np.sin(2 * np.pi * frequency_hz * t), rate_hz, name)
    tail = weighted[-round(periods / frequency_hz * rate_hz) :]
    exact = abs(annex_a_response(name, frequency_hz)) / math.sqrt(2.0)
    return float(np.sqrt(np.mean(tail**2)) / exact - 1.0)


def worst_sine_error(name: str, rate_hz: float) -> float:
    """Largest |relative error| over the one-third octaves (0.5-31.5 Hz; Wf 0.1-4 Hz)."""
    frequencies = WF_SINE_HZ if name == "Wf" else SINE_HZ
    return max(abs(sine_error(name, rate_hz, f)) for f in frequencies)


def main() -> None:
    print("weighting  rate_Hz  sine_max_%  half-sine a_w/MTVV/VDV %   decay a_w/MTVV/VDV %")
    for rate in (200.0, 250.0, 400.0, 1000.0):
        for name in ANNEX_A_PARAMETERS:
            sine = 100 * worst_sine_error(name, rate)
            half = [100 * e for e in shock_errors(name, rate, "half-sine")]
            decay = [100 * e for e in shock_errors(name, rate, "decay")]
            print(
                f"{name:<9}  {rate:7g}  {sine:10.3f}  "
                + " ".join(f"{e:+7.3f}" for e in half)
                + "  "
                + " ".join(f"{e:+7.3f}" for e in decay)
            )


if __name__ == "__main__":
    main()
