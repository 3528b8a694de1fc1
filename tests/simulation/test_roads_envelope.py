"""Rigid-wheel enveloping filter against closed forms, a brute-force search and invariants."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.simulation import (
    RoadProfile,
    board_course,
    edge_contact_length,
    effective_road,
    flat_road,
    single_board,
)

R_M = 0.42  # the 12-16.5 tyre of the brief
H_M = 0.04  # the paper's board


def closed_form_step(s: np.ndarray, s0: float, radius: float, height: float) -> np.ndarray:
    """Effective height under a rigid disc approaching a step up of ``height`` at ``s0``.

    The disc rests on flat ground (centre at R) until its rim reaches the edge corner (s0, H):
    the corner is on the disc when (s0 - s)^2 + (R - H)^2 = R^2, i.e. s = s0 - a with
    a = sqrt(R^2 - (R - H)^2). From there the disc pivots on the corner, its centre on the
    circle of radius R about it: y_c = H + sqrt(R^2 - (s0 - s)^2), so h_eff = y_c - R, until the
    centre is above the edge (s = s0); after that it rolls on the top, h_eff = H.
    """
    a = np.sqrt(2.0 * radius * height - height**2)
    arc = height - radius + np.sqrt(np.maximum(radius**2 - (s0 - s) ** 2, 0.0))
    return np.where(s < s0 - a, 0.0, np.where(s < s0, arc, height))


def closed_form_board(s: np.ndarray, s0: float, width: float, radius: float, height: float):
    """A board is a step up at s0 and, by symmetry, a step down at s0 + width."""
    up = closed_form_step(s, s0, radius, height)
    down = closed_form_step(2.0 * s0 + width - s, s0, radius, height)
    return np.minimum(up, down)


def test_step_matches_circular_arc_of_rigid_wheel():
    """The brief's acceptance test: 4 cm step, R = 0.42 m, circular arc to 1e-6 m (achieved 1e-15)."""
    s0 = 3.0
    # A step as a board far longer than the wheel: the down edge is out of reach.
    profile = single_board(height_m=H_M, width_m=4.0, position_m=s0)
    s = np.concatenate([np.linspace(s0 - 0.5, s0 + 0.5, 200_001), [s0 - 0.1788854381999831, s0]])
    height_m, _ = effective_road(profile, s, R_M)
    error_m = np.abs(height_m - closed_form_step(s, s0, R_M, H_M))
    assert error_m.max() <= 1e-15  # the brief's requirement is 1e-6 m
    contact = (s > s0 - 0.17) & (s < s0)  # on the arc, not the flat parts
    assert np.all(height_m[contact] > 0.0) and np.all(height_m[contact] < H_M)


def test_board_and_slope_match_closed_form():
    s0, width = 1.0, 0.14
    profile = single_board(height_m=H_M, width_m=width, position_m=s0)
    s = np.linspace(0.0, 2.0, 40_001)
    height_m, slope = effective_road(profile, s, R_M)
    np.testing.assert_allclose(
        height_m, closed_form_board(s, s0, width, R_M, H_M), rtol=0, atol=1e-15
    )
    # dh/ds on the up arc: (s0 - s) / sqrt(R^2 - (s0 - s)^2); on the down arc the mirror image.
    a = np.sqrt(2 * R_M * H_M - H_M**2)
    up = (s > s0 - a) & (s < s0)
    expected = (s0 - s[up]) / np.sqrt(R_M**2 - (s0 - s[up]) ** 2)
    np.testing.assert_allclose(slope[up], expected, rtol=1e-12, atol=1e-15)
    down = (s > s0 + width) & (s < s0 + width + a)
    u = s[down] - s0 - width
    np.testing.assert_allclose(slope[down], -u / np.sqrt(R_M**2 - u**2), rtol=1e-12, atol=1e-15)
    flat = (s < s0 - a - 1e-9) | ((s > s0) & (s < s0 + width)) | (s > s0 + width + a + 1e-9)
    assert np.all(slope[flat] == 0.0)
    # First contact: the steepest slope a / (R - H) = 0.4706 for the 4 cm board.
    assert slope.max() == pytest.approx(a / (R_M - H_M), rel=1e-3)


def test_queries_with_no_vertex_within_reach_lie_on_the_segment():
    """Every query more than R from every vertex (a slow drive, 1 kHz samples millimetres apart):
    the disc rests on the segment, h + R (sqrt(1 + m²) − 1) (an empty corner set crashed)."""
    profile = RoadProfile(np.array([0.0, 10.0]), np.array([0.0, 0.1]))
    s = np.linspace(4.9, 5.1, 300)
    height_m, slope = effective_road(profile, s, R_M)
    np.testing.assert_allclose(height_m, 0.01 * s + R_M * (np.sqrt(1.0001) - 1.0), atol=1e-15)
    np.testing.assert_array_equal(slope, 0.01)


def test_edge_contact_length():
    assert edge_contact_length(R_M, H_M) == pytest.approx(np.sqrt(0.42**2 - 0.38**2), rel=1e-15)
    with pytest.raises(ValueError, match=r"step_height_m must be a finite number in \[0, 0.42\] m"):
        edge_contact_length(R_M, 0.5)


def test_slope_matches_finite_differences_of_height():
    profile = RoadProfile([0.0, 0.3, 0.5, 0.5, 0.9, 1.4], [0.0, 0.02, -0.01, 0.03, 0.0, 0.05])
    s = np.linspace(-0.5, 2.0, 25_001)
    _, slope = effective_road(profile, s, 0.3)
    step = 1e-7
    numeric = effective_road(profile, s + step, 0.3)[0] - effective_road(profile, s - step, 0.3)[0]
    numeric /= 2 * step
    smooth = np.abs(numeric - slope) < 1e-3  # kinks (where two contacts trade) are excluded
    assert smooth.mean() > 0.99
    np.testing.assert_allclose(numeric[smooth], slope[smooth], rtol=0, atol=2e-6)


def brute_force(profile: RoadProfile, s: np.ndarray, radius: float, points: int) -> np.ndarray:
    """Independent reference: the defining maximum over contact offsets u, evaluated directly.

    Candidates: a dense grid of u plus the offsets of the vertices within reach (where a corner
    maximum sits exactly). A maximum on a segment's interior is smooth in u, so the grid misses it
    by O(du²).
    """
    grid = np.broadcast_to(np.linspace(-radius, radius, points), (s.size, points))
    corners = profile.distance_m[None, :] - s[:, None]
    corners = np.where(np.abs(corners) <= radius, corners, 0.0)
    u = np.concatenate([grid, corners], axis=1)
    return np.max(profile.height(s[:, None] + u) + np.sqrt(radius**2 - u**2), axis=1) - radius


def highest_within(profile: RoadProfile, s: np.ndarray, radius: float) -> np.ndarray:
    """Highest ground in [s - R, s + R]: at a vertex inside or at an end of the window."""
    ends = np.maximum(profile.height(s - radius), profile.height(s + radius))
    inside = np.abs(profile.distance_m[None, :] - s[:, None]) <= radius
    vertices = np.where(inside, profile.height_m[None, :], -np.inf).max(axis=1)
    return np.maximum(ends, vertices)


profiles = st.lists(
    st.tuples(st.floats(0.01, 0.5), st.floats(-0.05, 0.05)), min_size=2, max_size=12
).map(
    lambda rows: RoadProfile(
        np.cumsum([row[0] for row in rows]), np.array([row[1] for row in rows]), name="random"
    )
)


gentle_profiles = st.lists(
    st.tuples(st.floats(0.05, 0.5), st.floats(-0.05, 0.05)), min_size=2, max_size=12
).map(
    lambda rows: RoadProfile(
        np.cumsum([row[0] for row in rows]), np.array([row[1] for row in rows])
    )
)


@settings(max_examples=15, deadline=None)
@given(profile=gentle_profiles, radius=st.floats(0.1, 0.6))
def test_exact_envelope_matches_brute_force(profile, radius):
    s = np.linspace(profile.start_m - radius, profile.end_m + radius, 101)
    exact, _ = effective_road(profile, s, radius)
    direct = brute_force(profile, s, radius, 4001)
    # The direct search is a lower bound; on segments of slope <= 2 its grid (du <= 0.3 mm) misses
    # a tangent maximum by at most (1 + 2²)^1.5 du² / (8 R) = 1.3e-6 m.
    assert np.all(direct <= exact + 1e-12)
    assert np.max(exact - direct) < 2e-6


@settings(max_examples=30, deadline=None)
@given(
    profile=profiles,
    radius=st.floats(0.1, 0.6),
    shift=st.floats(-3.0, 3.0),
    lift=st.floats(-1.0, 1.0),
)
def test_envelope_invariants(profile, radius, shift, lift):
    s = np.linspace(profile.start_m - 1.0, profile.end_m + 1.0, 401)
    height_m, slope = effective_road(profile, s, radius)
    # The wheel never sinks into the ground under its axle ...
    assert np.all(height_m >= profile.height(s) - 1e-12)
    # ... and never rises above the highest ground within its reach.
    reach = highest_within(profile, s, radius)
    assert np.all(height_m <= reach + 1e-12)
    # Moving the road moves the effective road with it.
    moved = RoadProfile(profile.distance_m + shift, profile.height_m + lift)
    moved_height, _ = effective_road(moved, s + shift, radius)
    np.testing.assert_allclose(moved_height, height_m + lift, rtol=0, atol=1e-9)
    assert np.all(np.isfinite(slope))
    # Raising the ground anywhere never lowers the wheel (monotone in the profile).
    raised = RoadProfile(
        profile.distance_m, profile.height_m + np.linspace(0.0, 0.01, profile.height_m.size)
    )
    assert np.all(effective_road(raised, s, radius)[0] >= height_m - 1e-12)


@settings(max_examples=25, deadline=None)
@given(level=st.floats(-2.0, 2.0), radius=st.floats(0.05, 1.5))
def test_flat_road_stays_flat(level, radius):
    s = np.linspace(-5.0, 15.0, 1001)
    height_m, slope = effective_road(flat_road(10.0, height_m=level), s, radius)
    np.testing.assert_allclose(height_m, level, rtol=0, atol=1e-12)
    assert np.all(slope == 0.0)


@settings(max_examples=25, deadline=None)
@given(low=st.floats(0.001, 0.2), extra=st.floats(0.0, 0.2), width=st.floats(0.01, 1.0))
def test_monotone_in_board_height_and_slope_bounded(low, extra, width):
    s = np.linspace(-1.0, 2.0, 3001)
    boards = [single_board(height_m=h, width_m=width) for h in (low, low + extra)]
    (h1, slope1), (h2, _) = (effective_road(b, s, R_M) for b in boards)
    assert np.all(h2 >= h1 - 1e-15)
    # Steepest climb of a rigid wheel onto a board of height H: a / (R - H) at first contact.
    a = np.sqrt(2 * R_M * low - low**2)
    assert np.max(np.abs(slope1)) <= a / (R_M - low) * (1 + 1e-12)
    assert np.all(np.abs(np.diff(h1)) <= a / (R_M - low) * np.diff(s) * (1 + 1e-9))


def test_wall_taller_than_radius_gives_infinite_slope_and_travel_refuses():
    from loader_model.simulation import road_input

    wall = RoadProfile([0.0, 1.0, 1.0, 2.0], [0.0, 0.0, 0.5, 0.5])
    _, slope = effective_road(wall, np.array([1.0 - 0.3]), 0.3)
    assert np.isinf(slope[0])
    with pytest.raises(ValueError, match="wall at its equator"):
        road_input(
            wall,
            speed_m_s=1.0,
            wheelbase_m=0.0,
            duration_s=1.0,
            tyre_radius_m=0.3,
            sample_rate_hz=10.0,
        )


def test_board_course_geometry_and_jitter():
    course = board_course(5, height_m=0.04, width_m=0.14, spacing_m=6.0, first_board_m=2.0)
    assert course.distance_m.tolist()[:8] == [2.0, 2.0, 2.14, 2.14, 8.0, 8.0, 8.14, 8.14]
    assert course.height(np.array([1.99, 2.0, 2.07, 2.14, 2.15])).tolist() == [
        0,
        0.04,
        0.04,
        0.04,
        0,
    ]
    jittered = board_course(
        5, height_m=0.04, width_m=0.14, spacing_m=6.0, position_jitter_m=0.1, seed=3
    )
    again = board_course(
        5, height_m=0.04, width_m=0.14, spacing_m=6.0, position_jitter_m=0.1, seed=3
    )
    np.testing.assert_array_equal(jittered.distance_m, again.distance_m)
    shifts = jittered.distance_m[::4] - 6.0 * np.arange(5)
    assert 0.0 < np.abs(shifts).max() < 0.5
    with pytest.raises(ValueError, match="overlap"):
        board_course(5, height_m=0.04, width_m=0.14, spacing_m=0.2, position_jitter_m=0.5)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"count": 0}, r"count must be an integer in \[1, 1000\]"),
        ({"height_m": -0.01}, r"height_m must be a finite number in \(0, 0.5\] m; got -0.01"),
        ({"width_m": float("nan")}, r"width_m must be a finite number in \(0, 5\] m; got nan"),
        ({"spacing_m": 0.1}, r"spacing_m must be a finite number in \(0.14, inf\] m; got 0.1"),
        ({"seed": -1}, r"seed must be a non-negative integer; got -1"),
    ],
)
def test_board_course_errors_name_argument(kwargs, message):
    arguments = {"count": 3, "height_m": 0.04, "width_m": 0.14, "spacing_m": 6.0} | kwargs
    count = arguments.pop("count")
    with pytest.raises(ValueError, match=message):
        board_course(count, **arguments)


@pytest.mark.parametrize(
    ("distance", "height", "message"),
    [
        ([0.0], [0.0], "at least 2 vertices"),
        ([0.0, 1.0], [0.0], "one value per distance"),
        ([0.0, 2.0, 1.0], [0, 0, 0], r"non-decreasing; got 2 m then 1 m at index 2"),
        ([0.0, 1.0, 1.0, 1.0], [0, 0, 1, 2], "at most twice"),
        ([0.0, np.inf], [0, 0], "distance_m must be finite"),
        ([0.0, 1.0], [0, np.nan], "height_m must be finite"),
    ],
)
def test_profile_errors(distance, height, message):
    with pytest.raises(ValueError, match=message):
        RoadProfile(distance, height)


def test_effective_road_errors():
    with pytest.raises(ValueError, match=r"tyre_radius_m must be a finite number in \(0, 2\] m"):
        effective_road(flat_road(), [0.0], 0.0)
    with pytest.raises(ValueError, match="profile must be a RoadProfile"):
        effective_road([0.0, 1.0], [0.0], 0.4)
    with pytest.raises(ValueError, match="distance_m must be finite"):
        effective_road(flat_road(), [np.nan], 0.4)
