"""The enveloping model on the road-input path: road_input's cams, course_input per load, the
Scenario's switch and the Table 6 trials' (default tandem cam, rigid discs the other option)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from loader_model.experiments.trials import plant_scenario, trial_scenario, trial_specs
from loader_model.simulation import TandemCam, paper_course, road_input, single_obstacle_course
from loader_model.simulation.simulator import course_input
from loader_model.simulation.tandem_cam import tandem_cam_road


def test_road_input_with_cams_carries_height_plane_slope_and_rate():
    course = single_obstacle_course()
    cams = (TandemCam.from_deflection(0.42, 0.0073), TandemCam.from_deflection(0.42, 0.0099))
    drive = course.road_input(1.2, slope_to_x_m=(0.005, 0.004), cams=cams)
    assert drive.envelope == "tandem-cam" and drive.cams == cams
    distance = drive.axle_distance(drive.time_s)
    for axle, cam in enumerate(cams):
        road = tandem_cam_road(course.profile, distance[:, axle], cam)
        np.testing.assert_array_equal(drive.road_m[:, 2 * axle + 1], road.height_m)
        np.testing.assert_array_equal(drive.slope[:, axle], road.slope)
        np.testing.assert_allclose(
            drive.road_rate_m_s[:, 2 * axle + 1], course.speed_m_s * road.height_rate, rtol=1e-15
        )
        gain = (0.005, 0.004)[axle]
        np.testing.assert_array_equal(drive.road_m[:, 2 * axle], -gain * road.slope)
    np.testing.assert_allclose(drive.exact_road(drive.time_s), drive.road_m, rtol=0, atol=1e-15)
    # The board is shorter than the cam spacing at the rear (150 mm): its peak stays below 40 mm.
    assert drive.road_m[:, 3].max() < 0.04
    assert np.abs(drive.slope).max() < 0.32  # the rigid disc: 0.47 at first contact


def test_road_input_refuses_other_cams():
    with pytest.raises(ValueError, match="cams must be two TandemCam"):
        road_input(
            paper_course(9).profile,
            speed_m_s=2.5,
            wheelbase_m=1.2,
            duration_s=1.0,
            cams=(TandemCam.rigid_disc(0.42),),
        )


def test_course_input_builds_each_axles_cam_from_its_static_deflection():
    """The patch follows the load: the front tyre deflects 7.3 mm empty and 10.6 mm full."""
    course = paper_course(9)
    spacings = {}
    for load in ("empty", "full"):
        plant = plant_scenario(load, "baseline")
        drive = course_input(course, plant)
        assert drive.envelope == "tandem-cam"
        for axle, cam in zip("AB", drive.cams, strict=True):
            deflection = plant.output(f"F_{axle}y") / plant.parameter(f"k_{axle}y")
            assert cam == TandemCam.from_deflection(0.42, deflection)
        spacings[load] = tuple(cam.spacing_m for cam in drive.cams)
    assert spacings["full"][0] > spacings["empty"][0] and spacings["full"][1] < spacings["empty"][1]


def test_scenario_switches_the_envelope():
    scenario = trial_scenario("baseline", "empty")
    assert scenario.envelope == "tandem-cam"
    rigid = dataclasses.replace(scenario, envelope="rigid")
    course = paper_course(9)
    drive = course_input(course, rigid)
    assert drive.envelope == "rigid" and drive.cams is None
    plant = scenario.plant
    reference = course.road_input(
        plant.parameter("A_x") - plant.parameter("B_x"),
        slope_to_x_m=(
            plant.output("F_Ay") / plant.parameter("k_Ax"),
            plant.output("F_By") / plant.parameter("k_Bx"),
        ),
    )
    np.testing.assert_array_equal(drive.road_m, reference.road_m)
    assert course_input(course, rigid, envelope="tandem-cam").envelope == "tandem-cam"
    with pytest.raises(ValueError, match=r"envelope must be one of \['rigid', 'tandem-cam'\]"):
        dataclasses.replace(scenario, envelope="flexible")
    with pytest.raises(ValueError, match="envelope must be one of"):
        course_input(course, scenario, envelope="disc")


def test_trials_draw_the_same_whatever_the_envelope():
    cam = trial_specs(0, 2, speeds_kmh=(9.0,), loads=("empty",))
    rigid = trial_specs(0, 2, speeds_kmh=(9.0,), loads=("empty",), envelope="rigid")
    assert {spec.envelope for spec in cam} == {"tandem-cam"}
    assert {spec.envelope for spec in rigid} == {"rigid"}
    swapped = [
        dataclasses.replace(spec, variant=dataclasses.replace(spec.variant, envelope="rigid"))
        for spec in cam
    ]
    assert swapped == rigid
    with pytest.raises(ValueError, match=r"envelope must be one of \['tandem-cam', 'rigid'\]"):
        trial_specs(0, 2, envelope="soft")


def test_plot_envelopes_writes_a_figure(tmp_path):
    from loader_model.simulation import single_board
    from loader_model.simulation.envelope_plot import plot_envelopes

    board = single_board(height_m=0.04, width_m=0.14, position_m=0.0)
    cams = {"front, empty": TandemCam.from_deflection(0.42, 0.0073)}
    path = plot_envelopes(tmp_path / "board.png", board, cams, distance_range_m=(-0.5, 0.6))
    assert path.stat().st_size > 10_000
    with pytest.raises(ValueError, match=r"\.png, \.pdf or \.svg"):
        plot_envelopes(tmp_path / "board.jpg", board, cams, distance_range_m=(-0.5, 0.6))
    with pytest.raises(ValueError, match="low < high"):
        plot_envelopes(tmp_path / "board.png", board, cams, distance_range_m=(0.6, -0.5))
