"""The scenario (issue 20, item 3): the same plant, controller and run as the keyword path, the
arrays shared read-only, and clear errors for what does not fit together."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import loader_model
from loader_model.parameters.sets import bucket_load
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector
from loader_model.plant.scenario import PlantScenario, resolve_plant
from loader_model.simulation.ride_control import controller_setup, plant_controller
from loader_model.simulation.scenario import (
    Scenario,
    closed_loop,
    resolve_scenario,
    ride_scenario,
)

DATA = Path(loader_model.__file__).parent / "data"


@pytest.mark.parametrize(
    ("loader", "load"),
    [(None, "full"), (DATA / "default_loader.toml", DATA / "load_full.toml")],
)
def test_a_resolved_plant_is_the_vector_and_equilibrium_of_its_files(loader, load) -> None:
    plant = resolve_plant(loader, load, PlantOptions(accumulator=True))
    params = plant_parameter_vector(None, "full", PlantOptions(accumulator=True))
    np.testing.assert_array_equal(plant.params, params)
    x0, u0 = static_state(params)
    np.testing.assert_array_equal(plant.x0, x0)
    assert plant.u0 == u0 and plant.load.mass == bucket_load("full").mass
    assert plant.options == PlantOptions(accumulator=True)
    assert plant.output("F_Ay") > 0.0 and plant.parameter("accumulator_on") == 1.0
    with pytest.raises(ValueError, match="read-only"):
        plant.params[0] = 1.0


def test_with_options_equals_the_vector_built_with_them() -> None:
    plant = resolve_plant(None, "empty")
    assert plant.with_options(PlantOptions()) is plant
    for options in (PlantOptions(accumulator=True), PlantOptions.closed()):
        changed = plant.with_options(options)
        expected = plant_parameter_vector(None, "empty", options)
        np.testing.assert_array_equal(changed.params, expected)
        np.testing.assert_array_equal(changed.x0, static_state(expected)[0])
        assert changed.options == options and changed.load is plant.load


@pytest.mark.parametrize("controller", ["virtual-accumulator", "skyhook"])
def test_a_ride_scenario_holds_the_settings_and_fixed_point_of_controller_setup(
    controller: str,
) -> None:
    scenario = resolve_scenario(None, "empty", controller=controller)
    params = plant_parameter_vector(None, "empty")
    vector, state = controller_setup(
        controller, params, bucket_load("empty").pressure_normalisation
    )
    np.testing.assert_array_equal(scenario.settings, vector)
    np.testing.assert_array_equal(scenario.controller_state, state)
    assert scenario.controller.name() == plant_controller(controller).name()
    assert scenario.name == controller


def test_holding_scenarios_hold_u0_and_passive_connects_the_accumulator() -> None:
    baseline = resolve_scenario(None, "full")
    passive = resolve_scenario(None, "full", controller="passive")
    assert baseline.plant.parameter("accumulator_on") == 0.0
    assert passive.plant.parameter("accumulator_on") == 1.0
    for scenario in (baseline, passive):
        assert scenario.controller.name() == "hold" and scenario.controller_state.size == 0
        np.testing.assert_array_equal(scenario.settings, [scenario.u0])


def test_a_scenario_runs_the_same_numbers_as_the_keyword_path() -> None:
    """The skyhook from a scenario against the simulator's keyword arguments (which compute the
    equilibrium again): the same rows, bit for bit."""
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input, simulate

    scenario = resolve_scenario(None, "full", controller="skyhook")
    params = plant_parameter_vector(None, "full")
    vector, state = controller_setup("skyhook", params, bucket_load("full").pressure_normalisation)
    course = paper_course(9.0)
    kept = simulate(course_input(course, scenario), scenario, duration_s=1.5)
    keyword = simulate(
        course_input(course, params),
        params,
        plant_controller("skyhook"),
        settings=vector,
        controller_state=state,
        duration_s=1.5,
    )
    assert kept.columns.keys() == keyword.columns.keys()
    for name, values in keyword.columns.items():
        np.testing.assert_array_equal(kept[name], values, err_msg=name)
    plant_only = simulate(course_input(course, scenario.plant), scenario.plant, duration_s=1.5)
    held = simulate(course_input(course, params), params, duration_s=1.5)
    np.testing.assert_array_equal(plant_only["f_Sy"], held["f_Sy"])


def test_what_does_not_fit_is_refused_with_the_reason() -> None:
    from loader_model.simulation.courses import single_obstacle_course
    from loader_model.simulation.simulator import course_input, simulate

    plant = resolve_plant(None, "empty")
    with pytest.raises(ValueError, match=r"controller 'sky' is unknown; allowed: \["):
        resolve_scenario(controller="sky")
    with pytest.raises(ValueError, match="'passive' is the accumulator connected"):
        ride_scenario(plant, "passive")
    with pytest.raises(ValueError, match="'baseline' holds the static command u0"):
        ride_scenario(plant, "baseline", settings=DATA / "controller_default.toml")
    with pytest.raises(ValueError, match="needs pressure_norm_pa"):
        ride_scenario(PlantScenario.from_vector(plant.params), "skyhook")
    with pytest.raises(TypeError, match="options must be a PlantOptions or None; got dict"):
        resolve_plant(None, "empty", {"accumulator": True})
    with pytest.raises(TypeError, match="settings must be a ControllerSettings"):
        ride_scenario(plant, "skyhook", settings=3)
    with pytest.raises(ValueError, match=r"params must have \d+ values; got 3"):
        PlantScenario.from_vector([1.0, 2.0, 3.0])
    hold = closed_loop(plant)
    with pytest.raises(
        ValueError, match="settings must have 1 values for controller 'hold'; got 2"
    ):
        Scenario(plant, hold.controller, [1.0, 2.0], [])
    with pytest.raises(ValueError, match="settings are for a controller"):
        closed_loop(plant, settings=[1.0])
    road = course_input(single_obstacle_course(), hold)
    with pytest.raises(ValueError, match=r"a Scenario holds the controller.*got settings"):
        simulate(road, hold, settings=[1.0])
    with pytest.raises(ValueError, match="got controller, controller_state besides it"):
        simulate(road, hold, hold.controller, controller_state=[])
