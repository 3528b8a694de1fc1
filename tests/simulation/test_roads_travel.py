"""Road input tables: rear-axle delay, table accuracy, rates, horizontal input, errors."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.simulation import (
    ROAD_NAMES,
    effective_road,
    flat_road,
    paper_course,
    road_input,
    single_board,
    single_obstacle_course,
)

WHEELBASE_M = 1.2  # the default loader's


@pytest.fixture(scope="module")
def obstacle_drive():
    """Fig. 10 drive at 17 km/h, w_x from c = 5 mm (order of F_y0 / k_x of the default loader)."""
    return single_obstacle_course().road_input(WHEELBASE_M, slope_to_x_m=(0.005, 0.004))


def test_rear_axle_follows_front_with_wheelbase_delay(obstacle_drive):
    delay_s = WHEELBASE_M / obstacle_drive.speed_m_s
    t = np.linspace(0.0, obstacle_drive.duration_s - delay_s, 5001)
    front = obstacle_drive.exact_road(t)
    rear = obstacle_drive.exact_road(t + delay_s)
    np.testing.assert_allclose(rear[:, 3], front[:, 1], rtol=0, atol=1e-15)
    # Table: axle B's samples equal axle A's L / (v dt) samples earlier when that is whole.
    drive = road_input(
        single_board(height_m=0.04, width_m=0.14, position_m=1.0),
        speed_m_s=2.0,
        wheelbase_m=1.2,
        duration_s=3.0,
        sample_rate_hz=1000.0,
    )
    shift = 600  # 1.2 m / 2 m/s = 0.6 s
    np.testing.assert_allclose(drive.road_m[shift:, 3], drive.road_m[:-shift, 1], atol=1e-15)


def test_table_nodes_are_exact_and_columns_are_the_plant_order(obstacle_drive):
    assert ROAD_NAMES == ("w_Ax", "w_Ay", "w_Bx", "w_By")
    t = obstacle_drive.time_s
    np.testing.assert_allclose(obstacle_drive.road(t), obstacle_drive.exact_road(t), atol=1e-15)
    distance = obstacle_drive.axle_distance(t)
    height, slope = effective_road(obstacle_drive.profile, distance[:, 0], 0.42)
    np.testing.assert_allclose(obstacle_drive.road_m[:, 1], height, atol=0)
    np.testing.assert_allclose(obstacle_drive.road_m[:, 0], -0.005 * slope, atol=0)
    np.testing.assert_allclose(obstacle_drive.road_rate_m_s[:, 1], 17 / 3.6 * slope, atol=1e-15)
    assert obstacle_drive.road_m[:, 1].max() == pytest.approx(0.04, abs=1e-15)
    # w_x opposes the climb: negative while the wheel rides up the leading edge, at most
    # c a / (R - H) (the first-contact slope, which the 4.7 mm sample spacing just misses).
    assert -0.005 * 0.4706 <= obstacle_drive.road_m[:, 0].min() <= -0.005 * 0.46


@pytest.mark.parametrize(
    ("speed_kmh", "rate_hz", "bound_m"),
    # Linear interpolation between exact nodes: worst at first contact with an edge, where the
    # slope jumps by a / (R - H) = 0.47: error <= v dt * 0.47 / 4.
    [(9, 1000.0, 2.7e-4), (18, 1000.0, 2.7e-4), (18, 5000.0, 2.7e-5)],
)
def test_table_interpolation_error_between_nodes(speed_kmh, rate_hz, bound_m):
    drive = paper_course(speed_kmh).road_input(WHEELBASE_M, sample_rate_hz=rate_hz)
    middle = drive.time_s[:-1] + 0.5 / rate_hz
    error_m = np.abs(drive.road(middle) - drive.exact_road(middle))[:, [1, 3]].max()
    assert error_m <= bound_m
    assert error_m <= speed_kmh / 3.6 / rate_hz * 0.4706 / 4 * 1.01


def test_rates_integrate_to_displacement_on_smooth_road():
    # A gentle sinusoid (no kinks): trapezoid integral of the rate table reproduces w_y.
    s = np.linspace(0.0, 40.0, 4001)
    profile_rows = (s, 0.02 * np.sin(2 * np.pi * s / 5.0))
    from loader_model.simulation import RoadProfile

    drive = road_input(
        RoadProfile(*profile_rows),
        speed_m_s=3.0,
        wheelbase_m=1.2,
        duration_s=10.0,
        start_m=2.0,
        sample_rate_hz=2000.0,
        slope_to_x_m=(0.005, 0.005),
    )
    dt = 1.0 / drive.sample_rate_hz
    integral = np.cumsum(0.5 * (drive.road_rate_m_s[1:] + drive.road_rate_m_s[:-1]) * dt, axis=0)
    vertical = [1, 3]
    np.testing.assert_allclose(
        integral[:, vertical], drive.road_m[1:, vertical] - drive.road_m[0, vertical], atol=2e-6
    )
    # The horizontal input is a force equivalent, not ground motion: no rate.
    assert np.all(drive.road_rate_m_s[:, [0, 2]] == 0.0)
    assert np.abs(drive.road_m[:, [0, 2]]).max() > 1e-4


def test_scalar_and_array_evaluation(obstacle_drive):
    t = 1.0537
    scalar = obstacle_drive.road(t)
    assert scalar.shape == (4,)
    np.testing.assert_array_equal(scalar, obstacle_drive.road(np.array([t]))[0])
    np.testing.assert_array_equal(obstacle_drive.road_rate(np.float64(t)).shape, (4,))
    # Held beyond the ends of the table.
    np.testing.assert_array_equal(obstacle_drive.road(-1.0), obstacle_drive.road_m[0])
    np.testing.assert_array_equal(obstacle_drive.road(1e6), obstacle_drive.road_m[-1])
    assert obstacle_drive.road(np.zeros((3, 2))).shape == (3, 2, 4)


def test_flat_road_gives_zero_input():
    drive = road_input(flat_road(100.0), speed_m_s=5.0, wheelbase_m=1.2, duration_s=2.0)
    assert np.all(drive.road_m == 0.0) and np.all(drive.road_rate_m_s == 0.0)
    assert drive.time_s.size == 2001 and drive.time_s[-1] == 2.0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"speed_m_s": 0.0}, r"speed_m_s must be a finite number in \(0, 30\] m/s; got 0.0"),
        ({"wheelbase_m": -1.0}, r"wheelbase_m must be a finite number in \[0, 10\] m; got -1.0"),
        ({"duration_s": "long"}, r"duration_s must be a number in \(0, 3600\] s; got 'long'"),
        ({"sample_rate_hz": 1.0}, r"sample_rate_hz must be a finite number in \[10, 1e\+06\] Hz"),
        ({"slope_to_x_m": (0.1,)}, r"slope_to_x_m must give \(c_A, c_B\) in m"),
        ({"slope_to_x_m": (0.0, -0.1)}, r"slope_to_x_m\[1\] must be a finite number in \[0, 1\] m"),
        ({"duration_s": 0.01, "sample_rate_hz": 10.0}, r"must give 2 to 5e7 samples; got 1"),
    ],
)
def test_road_input_errors_name_argument(kwargs, message):
    arguments = {"speed_m_s": 2.5, "wheelbase_m": 1.2, "duration_s": 1.0} | kwargs
    with pytest.raises(ValueError, match=message):
        road_input(flat_road(), **arguments)


def test_three_axles_each_delayed_by_its_distance():
    """Three axles 0, 1.5 and 3.0 m behind the front one at 2 m/s: each axle's samples are the
    front axle's 750 and 1500 samples earlier (to 1e-15 m of a 4 cm board: the distances
    s_0 + v t − d_i round differently; measured 5.6e-17 m), each with its own c_i (equal
    cams, so that the delayed roads compare)."""
    from loader_model.simulation.tandem_cam import TandemCam

    cams = tuple(TandemCam.from_deflection(0.42, d) for d in (0.03, 0.03, 0.03))
    drive = road_input(
        single_board(height_m=0.04, width_m=0.14, position_m=1.0),
        speed_m_s=2.0,
        duration_s=4.0,
        axle_offsets_m=(0.0, 1.5, 3.0),
        axle_names=("A", "B", "R"),
        slope_to_x_m=(0.005, 0.004, 0.003),
        cams=cams,
    )
    assert drive.road_m.shape == (4001, 6) and drive.slope.shape == (4001, 3)
    assert drive.wheelbase_m == 3.0 and drive.n_axles == 3
    for axle, shift in ((1, 750), (2, 1500)):
        np.testing.assert_allclose(
            drive.road_m[shift:, 2 * axle + 1], drive.road_m[:-shift, 1], rtol=0, atol=1e-15
        )
        np.testing.assert_allclose(
            drive.slope[shift:, axle], drive.slope[:-shift, 0], rtol=0, atol=1e-12
        )
    c = np.array([0.005, 0.004, 0.003])
    np.testing.assert_array_equal(drive.road_m[:, 0::2], -c * drive.slope)
    assert drive.road_m[:, 1].max() > 0.03 and np.all(drive.road_rate_m_s[:, 0::2] == 0.0)
    # the same two axles by wheelbase or by offsets: the same table, bit for bit
    two = {"speed_m_s": 2.0, "duration_s": 2.0, "slope_to_x_m": (0.005, 0.004)}
    board = single_board(height_m=0.04, width_m=0.14, position_m=1.0)
    by_wheelbase = road_input(board, wheelbase_m=1.2, **two)
    by_offsets = road_input(board, axle_offsets_m=(0.0, 1.2), **two)
    np.testing.assert_array_equal(by_wheelbase.road_m, by_offsets.road_m)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({}, r"give either wheelbase_m \(two axles\) or axle_offsets_m"),
        ({"wheelbase_m": 1.2, "axle_offsets_m": (0.0, 1.2)}, r"give either wheelbase_m"),
        ({"axle_offsets_m": (0.5, 1.2)}, r"axle_offsets_m must give .* the first 0, front to rear"),
        ({"axle_offsets_m": (0.0, 2.0, 1.0)}, r"front to rear \(non-decreasing\); got \(0.0, 2.0"),
        (
            {"axle_offsets_m": (0.0, 11.0)},
            r"axle_offsets_m\[1\] must be a finite number in \[0, 10",
        ),
        ({"axle_offsets_m": (0.0, 1.0, 2.0), "slope_to_x_m": (0.0, 0.0)}, r"\(3 values c_i\)"),
        ({"axle_offsets_m": (0.0, 1.0, 2.0), "axle_names": ("A", "B")}, r"name the 3 axles"),
    ],
)
def test_axle_offsets_errors_name_argument(kwargs, message):
    with pytest.raises(ValueError, match=message):
        road_input(flat_road(), speed_m_s=2.5, duration_s=1.0, **kwargs)
