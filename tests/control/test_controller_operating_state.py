"""The controllers' fixed point without python-control (the simulator's start, issue 19 item C).

``controller_setup`` starts a ride controller at its fixed point; it used to build the whole
linear equivalent (python-control systems, a matrix logarithm) for it, 1.5 s of imports in
``loader-model simulate --controller skyhook``.
"""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control import CONTROLLER_NAMES, linear_controller
from loader_model.control.linear_controller import operating_state
from loader_model.parameters.sets import bucket_load
from loader_model.plant.plant_parameters import plant_parameter_vector
from loader_model.simulation.ride_control import RIDE_CONTROLLERS, controller_setup
from tests.control.test_controllers_linear import case


@pytest.mark.parametrize("name", CONTROLLER_NAMES)
def test_operating_state_is_the_linear_equivalents_fixed_point(name: str) -> None:
    _, settings, readings = case("full")
    z0 = operating_state(name, settings, readings)
    np.testing.assert_array_equal(z0, linear_controller(name, settings, readings).operating_state)


@pytest.mark.parametrize("name", sorted(RIDE_CONTROLLERS))
def test_controller_setup_starts_at_the_fixed_point(name: str) -> None:
    params = plant_parameter_vector(None, "empty")
    vector, state = controller_setup(name, params, bucket_load("empty").pressure_normalisation)
    _, settings, readings = case("empty")
    np.testing.assert_array_equal(vector, settings)
    fixed = linear_controller(RIDE_CONTROLLERS[name], vector, readings).operating_state
    np.testing.assert_array_equal(state, fixed)


def test_bad_shapes_are_refused() -> None:
    _, settings, readings = case("full")
    with pytest.raises(ValueError, match=r"settings has 3 entries, y_sensor .*; expected"):
        operating_state("skyhook", settings[:3], readings)
