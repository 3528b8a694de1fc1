"""Hydraulic components alone against closed forms (loader_model.plant.components)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from loader_model.plant import components as hyd


def _f(value) -> float:
    return float(value)


@given(st.floats(-10.0, 10.0), st.floats(0.01, 5.0))
def test_ramp_is_exact_outside_its_band(x: float, width: float) -> None:
    value = _f(hyd.ramp(x, width))
    if x <= 0:
        assert value == 0.0
    elif x >= width:
        assert value == pytest.approx(x - width / 2, rel=1e-12, abs=1e-15)
    else:
        assert value == pytest.approx(x * x / (2 * width), rel=1e-12)
    # C¹: never more than w/2 from max(x, 0), monotone
    assert 0.0 <= max(x, 0.0) - value <= width / 2 + 1e-12


@given(st.floats(-3.0, 3.0), st.floats(0.5, 2.0), st.floats(0.001, 0.1))
def test_saturation_is_exact_below_the_knee_and_clipped_above(x, limit, width) -> None:
    value = _f(hyd.saturate(x, limit, width))
    if abs(x) <= limit - width:
        assert value == pytest.approx(x, rel=1e-12, abs=1e-15)
    elif abs(x) >= limit + width:
        assert value == pytest.approx(math.copysign(limit, x), rel=1e-12)
    # its largest error against the hard clip is w/2, at |x| = limit
    assert abs(value - np.clip(x, -limit, limit)) <= width / 2 + 1e-12


def test_orifice_tends_to_the_turbulent_and_laminar_laws() -> None:
    area = math.pi / 4 * 0.004**2
    turbulent = 0.7 * area * math.sqrt(2 * 50e5 / 870.0)
    assert _f(hyd.orifice_flow(0.004, 0.7, 870.0, 50e5, 1e5)) == pytest.approx(turbulent, rel=2e-4)
    assert _f(hyd.orifice_flow(0.004, 0.7, 870.0, -50e5, 1e5)) == pytest.approx(
        -turbulent, rel=2e-4
    )
    laminar = 0.7 * area * math.sqrt(2 / 870.0) / math.sqrt(1e5)
    assert _f(hyd.orifice_flow(0.004, 0.7, 870.0, 10.0, 1e5)) == pytest.approx(
        10 * laminar, rel=1e-6
    )


def test_accumulator_follows_the_polytropic_law() -> None:
    """(p + p_atm)(V_0 − V_oil)^n = (p_0 + p_atm) V_0^n; continuous into the empty region."""
    p_atm = hyd.ATMOSPHERIC_PRESSURE_PA
    for oil in (0.0, 1e-4, 4e-4, 7e-4):
        pressure = _f(hyd.accumulator_gas_pressure(50e5, 7.5e-4, 1.4, oil))
        assert (pressure + p_atm) * (7.5e-4 - oil) ** 1.4 == pytest.approx(
            (50e5 + p_atm) * 7.5e-4**1.4, rel=1e-12
        )
    assert _f(hyd.accumulator_gas_pressure(50e5, 7.5e-4, 1.4, -1e-9)) < 50e5
    assert _f(hyd.accumulator_gas_pressure(50e5, 7.5e-4, 1.4, -1e-12)) == pytest.approx(
        50e5, rel=1e-6
    )


def test_friction_opposes_motion_and_vanishes_at_rest() -> None:
    """Eq. 46 (errata 10 reading): odd in velocity, zero at rest whatever the pressure."""
    args = (17e3, 40.0, 5.7, 1.07e-4, 8.13e3)
    assert _f(hyd.seal_friction(*args, 89e5, 0.0)) == 0.0
    for velocity in (1e-3, 0.05, 0.3):
        forward = _f(hyd.seal_friction(*args, 89e5, velocity))
        backward = _f(hyd.seal_friction(*args, 89e5, -velocity))
        assert forward > 0 and backward == pytest.approx(-forward, rel=1e-14)
    # closed form at 0.1 m/s and 89 bar
    expected = (17e3 * math.exp(-4.0) + 1.07e-4 * 89e5) * math.tanh(0.57) + 813.0
    assert _f(hyd.seal_friction(*args, 89e5, 0.1)) == pytest.approx(expected, rel=1e-14)


def test_leakage_and_chambers_closed_forms() -> None:
    assert _f(hyd.leakage_flow(2.87e-11, -5e-4, 89e5, 20e5, 0.1)) == pytest.approx(
        2.87e-11 * 69e5 - 5e-5, rel=1e-14
    )
    v_a, v_b = hyd.chamber_volumes(0.1, 3e-3, 2e-3, 0.45, 5e-4, 3e-4)
    assert (_f(v_a), _f(v_b)) == pytest.approx((3e-4 + 5e-4, 2e-3 * 0.35 + 3e-4), rel=1e-14)
    assert _f(hyd.chamber_pressure_rate(1.64e9, 1e-3, 1e-5)) == pytest.approx(1.64e7, rel=1e-14)


def test_end_stops_push_back_and_never_pull() -> None:
    inside = _f(hyd.end_stop_force(0.2, 0.5, 0.45, 1e8, 1e5))
    assert inside == 0.0
    beyond = _f(hyd.end_stop_force(0.45 + 2e-3, 0.0, 0.45, 1e8, 1e5))
    assert beyond == pytest.approx(-1e8 * (2e-3 - 2.5e-4), rel=1e-12)
    below = _f(hyd.end_stop_force(-2e-3, 0.0, 0.45, 1e8, 1e5))
    assert below == pytest.approx(1e8 * (2e-3 - 2.5e-4), rel=1e-12)
    # leaving the stop fast: the damper would pull, the stop force is clipped at zero
    assert _f(hyd.end_stop_force(-1e-4, 10.0, 0.45, 1e8, 1e5)) == 0.0


def test_pump_is_a_second_order_system() -> None:
    omega, zeta = 2 * math.pi * 22.3, 0.53
    value = _f(hyd.pump_displacement_acceleration(1e-5, 2e-4, 3e-5, omega, zeta))
    assert value == pytest.approx(omega**2 * 2e-5 - 2 * zeta * omega * 2e-4, rel=1e-14)
