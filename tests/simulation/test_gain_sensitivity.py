"""The closed loop's a_total and its gradient to the skyhook gains against the simulator and
central finite differences of it."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control.settings import default_settings, with_gains
from loader_model.experiments.trials import plant_scenario
from loader_model.simulation.courses import LEAD_IN_M, Course, kmh_to_m_s
from loader_model.simulation.gain_sensitivity import gain_gradient
from loader_model.simulation.roads import board_course
from loader_model.simulation.scenario import ride_scenario
from loader_model.simulation.simulator import course_input, simulate

TABLE3 = np.array([2.75, 5.10, -4.0, 0.22])


def _scenario(gain: np.ndarray, load: str = "full"):
    plant = plant_scenario(load, "skyhook")
    settings = with_gains(default_settings(), gain, "test")
    return ride_scenario(
        plant, "skyhook", settings, pressure_norm_pa=plant.load.pressure_normalisation
    )


def _course(height_m: float, boards: int = 1) -> Course:
    profile = board_course(boards, height_m=height_m, width_m=0.14, spacing_m=6.0)
    return Course(profile, kmh_to_m_s(9.0), -LEAD_IN_M, 1.0, f"{boards} board(s) {height_m} m")


def _simulated(gain: np.ndarray, course: Course) -> float:
    scenario = _scenario(gain)
    return float(simulate(course_input(course, scenario), scenario).seat_evaluation().total_m_s2)


@pytest.mark.slow
def test_gradient_against_central_differences_on_boards_without_lift_off() -> None:
    """5 mm boards: no tyre leaves the ground, the cost is smooth in K. The run is the
    simulator's (a_total equal to round-off); each component of the gradient agrees with central
    differences of the simulator (step 1e-3 of the gain, truncation error about 1e-6 of the
    largest component) to 2e-3 of the largest component (measured: 1.6e-3 relative on the
    smallest component, k_y, within 1e-5 of the largest elsewhere)."""
    course = _course(0.005)
    scenario = _scenario(TABLE3)
    found = gain_gradient(scenario, course_input(course, scenario), jit=False)
    assert found.a_total == pytest.approx(_simulated(TABLE3, course), rel=1e-12)
    assert found.refined_periods == 0
    differences = []
    for j in range(4):
        h = 1e-3 * max(1.0, abs(TABLE3[j]))
        up, down = TABLE3.copy(), TABLE3.copy()
        up[j] += h
        down[j] -= h
        differences.append((_simulated(up, course) - _simulated(down, course)) / (2 * h))
    differences = np.asarray(differences)
    scale = np.max(np.abs(differences))
    assert scale > 0
    np.testing.assert_allclose(found.gradient, differences, rtol=0, atol=2e-3 * scale)
