"""Discrete filters of the controllers against their continuous closed forms, and the settings file.

The filters are ZOH equivalents, which are exact for inputs held over a sample: the sampled step
responses must equal the continuous ones at every sample instant to rounding (measured: below
1e-13 absolute over 3 s at 1 kHz). Between these and the continuous filters there is only the
sampling: at 1 kHz the semi-integrator's frequency response differs from 1/(s + τ) by the
one-sample delay (phase e^{−jωT}) and the ZOH's half-sample droop.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from loader_model.control.filters import highpass_step, semi_integrator_step
from loader_model.control.settings import default_settings, load_settings
from loader_model.parameters.sets import default_loader

T = 1e-3
N = 3000


def _step_response(step, corner: float) -> np.ndarray:
    z, v = ca.SX.sym("z"), ca.SX.sym("v")
    f = ca.Function("f", [z, v], list(step(z, v, corner, T)))
    state, out = 0.0, []
    for _ in range(N):
        state, y = (float(r) for r in f(state, 1.0))
        out.append(y)
    return np.array(out)


def test_semi_integrator_step_response_equals_the_continuous_one_at_the_samples() -> None:
    tau = default_settings().tau
    t = np.arange(N) * T
    exact = (1 - np.exp(-tau * t)) / tau  # step response of 1/(s + τ)
    np.testing.assert_allclose(_step_response(semi_integrator_step, tau), exact, rtol=0, atol=1e-13)
    assert exact[-1] == pytest.approx(1 / tau, rel=1e-12)  # DC gain 1/τ


def test_highpass_step_response_equals_the_continuous_one_at_the_samples() -> None:
    corner = default_settings().highpass_corner
    t = np.arange(N) * T
    np.testing.assert_allclose(
        _step_response(highpass_step, corner), np.exp(-corner * t), rtol=0, atol=1e-13
    )


@pytest.mark.parametrize("hz", [0.5, 3.0, 10.0])
def test_semi_integrator_frequency_response_close_to_continuous(hz: float) -> None:
    """|G_d(e^{jωT}) / G_c(jω) − 1| below 1.1 ωT (one-sample delay plus ZOH) up to 10 Hz."""
    tau = default_settings().tau
    w = 2 * math.pi * hz
    q = math.exp(-tau * T)
    discrete = (1 - q) / tau / (np.exp(1j * w * T) - q)
    continuous = 1 / (1j * w + tau)
    assert abs(discrete / continuous - 1) < 1.1 * w * T


def test_default_settings_equal_the_loader_files_controller_section() -> None:
    settings, loader = default_settings(), default_loader().controller
    for name in ("k_fb", "tau", "k_p", "sample_rate", "linear_acceleration_norm", "angle_norm"):
        assert getattr(settings, name) == getattr(loader, name), name
    assert settings.k_fb == (2.75, 5.10, -4.0, 0.22)  # Table 3, k_φ sign corrected (errata 12)
    assert settings.source("highpass_corner").startswith("choice")


def test_settings_file_out_of_range_value_names_field_and_reason(tmp_path) -> None:
    from importlib import resources

    text = resources.files("loader_model").joinpath("data", "controller_default.toml").read_text()
    path = tmp_path / "c.toml"
    path.write_text(text.replace("value = 10.0, unit", "value = 1000.0, unit"))
    with pytest.raises(ValueError, match=r"c\.toml: tau = 1000\.0 rad/s is out of range"):
        load_settings(path)
    path.write_text(text.replace('unit = "rad/s", source = "Table 3', 'unit = "Hz", source = "x'))
    with pytest.raises(ValueError, match="unit 'Hz' is not allowed"):
        load_settings(path)
