"""Sensor offset, noise and quantisation inside the compiled 1 kHz loop (issue 12 / 13)."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control.sensors import SENSOR_NAMES, SensorModel
from loader_model.parameters.sets import bucket_load
from loader_model.plant.plant_parameters import plant_parameter_vector
from loader_model.simulation.courses import paper_course
from loader_model.simulation.ride_control import controller_setup, plant_controller
from loader_model.simulation.simulator import course_input, simulate

DURATION_S = 0.4
NOISY = SensorModel(
    noise_std=(0.05, 0.05, 0.05, 2e-4, 2e4),
    offset=(0.02, -0.01, 0.0, 1e-3, 5e4),
    quantisation=(0.0, 0.0, 0.0, 0.0, 1e5),
    seed=11,
)


@pytest.fixture(scope="module")
def skyhook_runs():
    params = plant_parameter_vector(None, "empty")
    settings, z0 = controller_setup("skyhook", params, bucket_load("empty").pressure_normalisation)
    controller = plant_controller("skyhook")
    road = course_input(paper_course(9.0, settle_s=0.5), params)
    common = {"controller": controller, "settings": settings, "controller_state": z0}

    def run(sensors):
        return simulate(road, params, sensors=sensors, duration_s=DURATION_S, **common)

    return controller, settings, z0, run(None), run(SensorModel()), run(NOISY)


def test_exact_sensors_give_the_run_without_a_sensor_model(skyhook_runs) -> None:
    _, _, _, plain, exact, _ = skyhook_runs
    np.testing.assert_array_equal(exact.columns["V_p_ref"], plain.columns["V_p_ref"])
    np.testing.assert_array_equal(exact.columns["p_A"], plain.columns["p_A"])
    for name in SENSOR_NAMES:
        np.testing.assert_array_equal(exact.columns[f"{name}_measured"], plain.columns[name])


def test_readings_carry_the_seeded_errors_and_the_converter_step(skyhook_runs) -> None:
    _, _, _, plain, _, noisy = skyhook_runs
    count = noisy.time_s.size
    errors = NOISY.errors(count + 1)[:count]
    for index, name in enumerate(SENSOR_NAMES[:4]):
        np.testing.assert_allclose(
            noisy.columns[f"{name}_measured"] - noisy.columns[name],
            errors[:, index],
            rtol=0,
            atol=1e-12 * max(1.0, float(np.max(np.abs(noisy.columns[name])))),
        )
    pressure = noisy.columns["p_A_measured"]
    np.testing.assert_array_equal(np.mod(pressure, 1e5), 0.0)
    assert np.max(np.abs(pressure - (noisy.columns["p_A"] + errors[:, 4]))) <= 0.5e5
    assert not np.array_equal(noisy.columns["V_p_ref"], plain.columns["V_p_ref"])


def test_the_controller_acted_on_the_measured_readings(skyhook_runs) -> None:
    """Replaying the recorded readings through the same controller Function gives the
    recorded commands: the loop fed the controller the noisy, quantised readings."""
    from loader_model.plant.plant import OUTPUT_NAMES

    controller, settings, z0, _, _, noisy = skyhook_runs
    y = np.zeros(len(OUTPUT_NAMES))
    z = np.asarray(z0, dtype=float)
    commands = []
    for k in range(noisy.time_s.size):
        for name in OUTPUT_NAMES:
            if name in noisy.columns:
                y[OUTPUT_NAMES.index(name)] = noisy.columns[name][k]
        for name in SENSOR_NAMES:
            y[OUTPUT_NAMES.index(name)] = noisy.columns[f"{name}_measured"][k]
        z_next, u = controller(z, y, settings)
        z = np.asarray(z_next, dtype=float).ravel()
        commands.append(float(u))
    np.testing.assert_allclose(commands, noisy.columns["V_p_ref"], rtol=1e-12, atol=1e-18)


def test_a_sensor_model_of_the_wrong_type_is_refused() -> None:
    params = plant_parameter_vector(None, "empty")
    road = course_input(paper_course(9.0, settle_s=0.5), params)
    with pytest.raises(TypeError, match="sensors must be a SensorModel"):
        simulate(road, params, sensors={"noise_std": 1.0}, duration_s=0.01)
