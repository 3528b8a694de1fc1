"""Sensors (section 3.3) on a pitched resting loader, and the skyhook's velocity estimate at rest.

The pitched rest: the front road raised 5 cm under axle A; the coordinates and p_A that make
the plant's rates vanish are found by Newton's method on the plant Function itself (tyre anchors
at 0, the pump at its holding command). A chassis at rest pitched by θ1 reads specific force
R(θ1)ᵀ (0, g) = (g sin θ1, g cos θ1) at every chassis point.
"""

from __future__ import annotations

import math
from functools import cache

import casadi as ca
import numpy as np
import pytest

from loader_model.control import (
    SENSOR_NAMES,
    SensorModel,
    controller_function,
    default_settings,
    sensor_signals,
    settings_vector_for_plant,
)
from loader_model.parameters.sets import bucket_load
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import EXOGENOUS_NAMES, plant_function
from loader_model.plant.plant_parameters import plant_parameter_vector


@cache
def pitched_rest() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(state, plant outputs, params) of the full-bucket loader resting with its front raised."""
    params = plant_parameter_vector(None, "full")
    x0, u0 = static_state(params)
    road = np.zeros(len(EXOGENOUS_NAMES))
    road[EXOGENOUS_NAMES.index("w_Ay")] = 0.05
    v = ca.SX.sym("v", 5)
    # the occupant's states (x0[15:], zero) act on no sensor and not on the loader
    x = ca.vertcat(v[0:4], ca.DM.zeros(6), v[4], x0[11], x0[12], 0, x0[14], x0[15:])
    xdot, _ = plant_function()(x, u0, road, params)
    residual = ca.Function("rest", [v], [ca.vertcat(xdot[4:8], xdot[10])])
    solution = ca.rootfinder("rest_solver", "newton", residual)(np.r_[0, 0, 0, 0, x0[10]])
    state = np.asarray(ca.Function("x", [v], [x])(solution), dtype=float).ravel()
    xdot, y = plant_function()(state, u0, road, params)
    assert np.max(np.abs(np.asarray(xdot)[4:8])) < 1e-9
    return state, np.asarray(y, dtype=float).ravel(), params


def test_pitched_rest_reads_the_gravity_component() -> None:
    state, y, _ = pitched_rest()
    theta = state[2]
    assert theta > 0.03  # nose up by about 2.4 degrees
    f = dict(zip(SENSOR_NAMES, sensor_signals(y), strict=True))
    g = 9.81
    assert f["f_Hx"] == pytest.approx(g * math.sin(theta), rel=1e-9)
    assert f["f_Hy"] == pytest.approx(g * math.cos(theta), rel=1e-9)
    assert f["f_Ny"] == pytest.approx(f["f_Hy"], rel=1e-12)  # no pitch acceleration at rest


def _run(settings: np.ndarray, readings: np.ndarray, z: np.ndarray, steps: int) -> np.ndarray:
    f = controller_function("skyhook")
    history = []
    for _ in range(steps):
        z_next, u = f(z, readings, settings)
        z = np.asarray(z_next, dtype=float).ravel()
        history.append(np.r_[z, float(u)])
    return np.array(history)


def test_skyhook_velocity_estimate_is_bounded_from_a_constant_gravity_reading() -> None:
    """From the pitched rest, the velocity states settle at (g sin θ1, g (cos θ1 − 1), 0)/(2 g τ):
    constant, no drift (1/(s + τ), not 1/s); the high-pass state settles at p_A/ω_hp, so the
    command returns to the holding command."""
    state, y, params = pitched_rest()
    settings = settings_vector_for_plant(default_settings(), params, 2e7)
    readings = sensor_signals(y)
    tau, a_norm, g = 10.0, 19.62, 9.81
    history = _run(settings, readings, np.r_[0.0, 0.0, 0.0, readings[4]], 3000)
    theta = state[2]
    expected = np.array([g * math.sin(theta), g * (math.cos(theta) - 1), 0.0]) / (a_norm * tau)
    np.testing.assert_allclose(history[-1, :3], expected, rtol=1e-9, atol=1e-13)
    assert np.max(np.abs(history[:, :3])) <= np.max(np.abs(expected)) * (1 + 1e-9)
    _, hold = static_state(params)
    phi_term = -0.22 * y[3] / default_settings().angle_norm  # the boom stands 1.4 deg below φ0
    k = 0.5 * 46e-6
    velocity_term = -(2.75 * expected[0] + 5.10 * expected[1])
    assert history[-1, 4] == pytest.approx(hold + k * (phi_term + velocity_term), rel=1e-6)


def test_skyhook_velocity_estimate_decays_at_level_rest() -> None:
    params = plant_parameter_vector(None, bucket_load("full"))
    x0, u0 = static_state(params)
    readings = sensor_signals(np.asarray(plant_function()(x0, u0, np.zeros(11), params)[1]).ravel())
    settings = settings_vector_for_plant(default_settings(), params, 2e7)
    history = _run(settings, readings, np.r_[0.1, -0.1, 0.05, readings[4]], 500)
    decay = math.exp(-10.0 * 500e-3)
    np.testing.assert_allclose(history[-1, :3], np.r_[0.1, -0.1, 0.05] * decay, rtol=1e-9)
    used = history[-2, :3]  # the last command uses the states before the last update
    expected = u0 - 0.5 * 46e-6 * float(np.dot([2.75, 5.10, -4.0], used))
    assert history[-1, 4] == pytest.approx(expected, rel=1e-9)


def test_sensor_model_is_seeded_and_quantises() -> None:
    readings = np.tile([0.1, 9.81, 9.81, 0.0, 1.3e7], (100, 1))
    model = SensorModel(
        noise_std=(0.05, 0.05, 0.05, 1e-3, 1e4),
        offset=(0.01, 0.0, 0.0, 0.0, 0.0),
        quantisation=(0.0, 0.0, 0.0, 0.0, 1e5),
        seed=3,
    )
    first, again = model.measure(readings), model.measure(readings)
    np.testing.assert_array_equal(first, again)
    assert np.all(np.mod(first[:, 4], 1e5) == 0)
    assert np.mean(first[:, 0]) == pytest.approx(0.11, abs=0.02)
    assert np.std(first[:, 1]) == pytest.approx(0.05, rel=0.2)
    with pytest.raises(ValueError, match="noise_std"):
        SensorModel(noise_std=(-1.0, 0, 0, 0, 0))
