"""The bound tests' plant and course: the empty bucket over one 5 mm board (small enough to stay
near the linearisation), and the 3 s bound problem on it."""

from __future__ import annotations

import pytest

from loader_model.bound.problem import BoundProblem, bound_problem
from loader_model.plant.scenario import PlantScenario, resolve_plant
from loader_model.simulation.courses import Course
from loader_model.simulation.roads import board_course
from loader_model.simulation.simulator import course_input
from loader_model.simulation.travel import RoadInput


@pytest.fixture(scope="module")
def plant() -> PlantScenario:
    return resolve_plant(None, "empty")


@pytest.fixture(scope="module")
def road(plant: PlantScenario) -> RoadInput:
    course = Course(
        board_course(1, height_m=0.005, width_m=0.14, spacing_m=0.0), 2.5, -0.3, 2.0, ""
    )
    return course_input(course, plant)


@pytest.fixture(scope="module")
def problem(plant: PlantScenario, road: RoadInput) -> BoundProblem:
    return bound_problem(plant, road, duration_s=3.0)
