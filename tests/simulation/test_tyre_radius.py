"""Each axle's tyre radius in the road input, against the rigid-disc geometry on a step.

A rigid disc of radius R approaching a step of height h first touches its edge when its centre
is d0 = sqrt(R² − (R − h)²) before it; over the last d0 it pivots on the corner, its centre on a
circle of radius R about it, so the effective height is h − (R − sqrt(R² − d²)) at a distance d
before the edge, and h on top. A machine with different front and rear radii must see each
axle's own curve.
"""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.simulation import TandemCam, road_input, single_board, tandem_cam_road
from loader_model.simulation.validity import validity_bounds

H_M = 0.04  # the paper's board
EDGE_M = 2.0  # leading edge of the board
SPEED_M_S = 2.5
RADII_M = (0.3, 0.75)  # front, rear: a tractor's small front and large rear tyres


def step_height(s: np.ndarray, radius_m: float) -> np.ndarray:
    """Closed form: the effective height of a rigid disc before and on a step up at EDGE_M."""
    d0 = np.sqrt(radius_m**2 - (radius_m - H_M) ** 2)
    d = EDGE_M - s
    arc = H_M - (radius_m - np.sqrt(np.maximum(radius_m**2 - d**2, 0.0)))
    return np.where(d > d0, 0.0, np.where(d > 0.0, arc, H_M))


def board_drive(**kwargs: object):
    board = single_board(height_m=H_M, width_m=2.0, position_m=EDGE_M)
    return road_input(
        board, speed_m_s=SPEED_M_S, wheelbase_m=1.2, duration_s=1.6, sample_rate_hz=2000.0,
        **kwargs,
    )  # fmt: skip


def test_each_axle_follows_its_own_radius_over_a_step() -> None:
    drive = board_drive(tyre_radius_m=RADII_M)
    assert drive.tyre_radii_m == RADII_M
    distance = drive.axle_distance(drive.time_s)
    on_step = distance < EDGE_M + 0.5  # the leading edge only; the board is 2 m long
    for axle, radius_m in enumerate(RADII_M):
        expected = step_height(distance[:, axle], radius_m)
        height = drive.road_m[:, 2 * axle + 1]
        rows = on_step[:, axle]
        # the same arithmetic in another order: rounding only (1e-12 of the 4 cm step)
        np.testing.assert_allclose(height[rows], expected[rows], rtol=0, atol=1e-12 * H_M)
    # first contact: d0 = 0.153 m before the edge for R = 0.3 m, 0.243 m for R = 0.75 m
    first = [EDGE_M - np.sqrt(r**2 - (r - H_M) ** 2) for r in RADII_M]
    for axle, start in enumerate(first):
        rising = distance[drive.road_m[:, 2 * axle + 1] > 0.0, axle]
        assert rising.min() == pytest.approx(start, abs=SPEED_M_S / 2000.0)
    # the two axles' curves differ as the closed forms do (the rear one rises earlier, slower)
    s = np.linspace(EDGE_M - 0.3, EDGE_M, 61)
    assert np.max(np.abs(step_height(s, RADII_M[0]) - step_height(s, RADII_M[1]))) > 0.01


def test_one_radius_for_all_axles_is_the_same_table() -> None:
    one = board_drive(tyre_radius_m=0.42)
    each = board_drive(tyre_radius_m=(0.42, 0.42))
    assert one.tyre_radius_m == 0.42 and each.tyre_radii_m == (0.42, 0.42)
    np.testing.assert_array_equal(one.road_m, each.road_m)
    np.testing.assert_array_equal(one.road_rate_m_s, each.road_rate_m_s)


def test_cams_of_different_shapes_envelop_each_axle_by_its_own() -> None:
    cams = tuple(TandemCam.from_deflection(r, 0.02) for r in RADII_M)
    drive = board_drive(tyre_radius_m=RADII_M, cams=cams)
    distance = drive.axle_distance(drive.time_s)
    for axle, cam in enumerate(cams):
        alone = tandem_cam_road(drive.profile, distance[:, axle], cam)
        np.testing.assert_array_equal(drive.road_m[:, 2 * axle + 1], alone.height_m)
        np.testing.assert_array_equal(drive.slope[:, axle], alone.slope)


@pytest.mark.parametrize(
    ("radius", "message"),
    [
        (0.0, r"tyre_radius_m must be a finite number in \(0, 2\] m; got 0\.0"),
        (float("nan"), r"tyre_radius_m must be a finite number in \(0, 2\] m; got nan"),
        (2.5, r"tyre_radius_m must be a finite number in \(0, 2\] m; got 2\.5"),
        ((0.4, -0.1), r"tyre_radius_m\[1\] \(axle B\) must be a finite number .* got -0\.1"),
        ((0.4,), r"tyre_radius_m must give one radius in m per axle \(A, B\)"),
    ],
)
def test_bad_radii_are_refused(radius: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        board_drive(tyre_radius_m=radius)


def test_validity_contact_points_lie_each_axle_radius_below_it() -> None:
    from loader_model.plant.plant_parameters import plant_parameter_vector

    params = plant_parameter_vector(None, "empty")
    same = validity_bounds(params, tyre_radius_m=0.42)
    assert validity_bounds(params, tyre_radius_m=(0.42, 0.42)) == same
    # a larger front tyre lowers the front contact: the nose-down tip-over angle shrinks
    larger = validity_bounds(params, tyre_radius_m=(0.6, 0.42))
    assert larger.pitch_down_rad < same.pitch_down_rad


def test_a_machines_own_radii_reach_each_axle_of_its_road_input() -> None:
    """The compact wheel loader with 0.3 m front and 0.6 m rear tyres over one long board:
    course_input builds each axle's rigid envelope from its own radius (closed form above)."""
    import dataclasses

    from loader_model.machines import machine
    from loader_model.parameters.machine_files import default_machine_parameters
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation import Course
    from loader_model.simulation.simulator import course_input

    shipped = default_machine_parameters(machine("compact_wheel_loader"))
    radii = {"R_A": 0.3, "R_B": 0.6}
    params = dataclasses.replace(shipped, tyres=shipped.tyres | radii)
    plant = resolve_plant(params, None, machine="compact_wheel_loader")
    board = single_board(height_m=H_M, width_m=2.0, position_m=EDGE_M)
    course = Course(board, speed_m_s=SPEED_M_S, start_m=0.0, settle_s=0.0, name="one board")
    drive = course_input(course, plant, envelope="rigid")
    assert drive.tyre_radii_m == (0.3, 0.6)
    distance = drive.axle_distance(drive.time_s)
    for axle, radius_m in enumerate(radii.values()):
        rows = distance[:, axle] < EDGE_M + 0.5
        expected = step_height(distance[rows, axle], radius_m)
        np.testing.assert_allclose(
            drive.road_m[rows, 2 * axle + 1], expected, rtol=0, atol=1e-12 * H_M
        )
    # the tandem cams take each axle's radius too: different shapes, each its own envelope
    cams = course_input(course, plant, envelope="tandem-cam").cams
    assert [cam.half_height_m for cam in cams] == [0.3, 0.6]  # b_e = 1.0 R of each axle


def test_the_description_and_the_runtime_state_the_same_tyre_limits() -> None:
    from derive.description_tyres import TYRE_LIMITS as DESCRIBED
    from loader_model.parameters.tyres import TYRE_FIELDS, TYRE_LIMITS

    assert [prefix for prefix, _, _ in TYRE_FIELDS] == list(DESCRIBED)
    for prefix, name, unit in TYRE_FIELDS:
        limit = TYRE_LIMITS[name]
        assert DESCRIBED[prefix] == (unit, limit.low, limit.high, limit.low_open), prefix
        assert not limit.high_open
