"""The receding-horizon constrained preview: the unconstrained preview law when no limit is near,
within the pump's and the path's limits on a 40 mm board, its bad input."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from loader_model.bound.condensed import condense
from loader_model.bound.constrained import PATH_TOLERANCE, path_limits, solve_constrained_bound
from loader_model.bound.linear import evaluate
from loader_model.bound.preview import evaluate_preview, preview_design, preview_intervals
from loader_model.bound.preview_mpc import TAIL_INTERVALS, receding_preview
from loader_model.bound.problem import bound_problem
from loader_model.simulation.courses import Course
from loader_model.simulation.roads import board_course
from loader_model.simulation.simulator import course_input

PREVIEW_M = 0.5


def _widened(problem, factor):
    """``problem`` with every limit ``factor`` times as far from the static point."""
    static = path_limits(problem)[0][:-1]
    return dataclasses.replace(
        problem,
        u_bounds=tuple(factor * np.asarray(problem.u_bounds)),
        rate_limit=factor * problem.rate_limit,
        path_lower=static + factor * (problem.path_lower - static),
        path_upper=static + factor * (problem.path_upper - static),
    )


@pytest.fixture(scope="module")
def short(plant, road):
    """The conftest's 5 mm board over 2 s (the rear axle meets it at 0.6 s)."""
    return bound_problem(plant, road, duration_s=2.0)


@pytest.fixture(scope="module")
def design(short):
    return preview_design(short)


@pytest.fixture(scope="module")
def wide(short):
    problem = _widened(short, 100.0)
    return problem, preview_design(problem)


@pytest.fixture(scope="module")
def board(plant):
    """One 40 mm board (the paper course's), 2 s: the front axle meets it at 0.12 s, the rear
    at 0.6 s."""
    course = Course(board_course(1, height_m=0.04, width_m=0.14, spacing_m=0.0), 2.5, -0.3, 2.0, "")
    road = course_input(course, plant)
    return road, bound_problem(plant, road, duration_s=2.0)


def test_road_path_offsets_of_the_two_axles_sum_to_the_bounds(design):
    whole = design.lq.path[2]
    total = design.road_path[0] + design.road_path[1]
    np.testing.assert_allclose(total, whole, rtol=0.0, atol=1e-12 * np.abs(whole).max())


@pytest.mark.parametrize("tail", [0, TAIL_INTERVALS])
def test_far_limits_give_the_unconstrained_preview_law(wide, road, tail):
    """Every limit 100 times as far: with H = n_r (+ the tail) the plans' first commands are
    the preview law's (the terminal P is its value once the road is static). Measured on the
    5 mm board, 2 s, L = 0.5 m: a_total to 5e-15, the command and the states to 1.5e-10 of
    their peaks."""
    wide, design = wide
    intervals = preview_intervals(wide, PREVIEW_M, road.speed_m_s, road.wheelbase_m)
    reference = evaluate_preview(design, wide, intervals, PREVIEW_M)
    run = receding_preview(
        design, wide, PREVIEW_M, road.speed_m_s, road.wheelbase_m, horizon=intervals[1] + tail
    )
    assert run.intervals == intervals
    assert run.converged.all()
    assert run.a_total_m_s2 == pytest.approx(reference.a_total_m_s2, rel=1e-13)
    peak = np.max(np.abs(reference.command))
    np.testing.assert_allclose(run.command, reference.command, rtol=0.0, atol=1e-9 * peak)
    peaks = np.max(np.abs(reference.states), axis=0)
    assert np.all(np.abs(run.states - reference.states) <= 1e-9 * peaks)


def _clipped_preview(design, problem, intervals):
    """The preview law with its command clipped to the pump's limit (linear plant): scaled
    commands and a_total."""
    lq, u0 = design.lq, problem.plant.u0
    low, high = ((bound - u0) / lq.u_scale for bound in problem.u_bounds)
    feedforward, z = design.feedforward(intervals), np.zeros(lq.a.shape[0])
    command = np.empty(feedforward.size)
    for j, value in enumerate(feedforward):
        command[j] = np.clip(value - design.gain @ z, low, high)
        z = lq.a @ z + lq.b * command[j] + lq.d[j]
    return command * lq.u_scale, evaluate(lq, command, problem)[0]


def _violation(design, problem, command):
    """Largest violation of each path signal (p_A, p_B, x_piston, V̇_p) over every period,
    relative to its limit."""
    _, lower, upper, scale = path_limits(problem)
    values = condense(design.lq, problem.hold_periods).path_values(command / design.lq.u_scale)
    return np.max(np.maximum(values - upper, lower - values) / scale, axis=(0, 1))


def _check_constrained(design, problem, road, rel):
    """The receding horizon's command within ±0.99 V_p,max, every 1 ms sample of the path
    signals within its limit (to the QP's tolerance) and a_total within ``rel`` above the
    non-causal constrained bound (all on the linear plant)."""
    intervals = preview_intervals(problem, PREVIEW_M, road.speed_m_s, road.wheelbase_m)
    free = evaluate_preview(design, problem, intervals, PREVIEW_M)
    assert np.max(_violation(design, problem, free.command)) > 1.0  # the law breaks a limit
    run = receding_preview(design, problem, PREVIEW_M, road.speed_m_s, road.wheelbase_m)
    assert run.converged.all()
    assert np.max(run.plan_violation) <= PATH_TOLERANCE
    absolute = problem.plant.u0 + run.command
    assert np.all(absolute >= problem.u_bounds[0]) and np.all(absolute <= problem.u_bounds[1])
    assert np.all(_violation(design, problem, run.command) <= PATH_TOLERANCE)
    bound = solve_constrained_bound(problem).a_total_m_s2
    assert bound <= run.a_total_m_s2 <= bound * (1.0 + rel)
    return run, free


def test_the_rate_limit_holds_on_a_5_mm_board(design, short, road):
    """The preview law asks for 2.9 × the pump's displacement rate on the 5 mm board; the
    receding horizon (L = 0.5 m) keeps every limit and reads a_total 1.3e-4 above the
    non-causal constrained bound (measured)."""
    _, free = _check_constrained(design, short, road, rel=3e-4)
    assert np.max(np.abs(free.command)) < short.u_bounds[1]  # here only the rate binds


@pytest.mark.slow
def test_the_pump_and_the_stroke_hold_on_a_40_mm_board(board):
    """40 mm board, 2 s (measured 8.6 to 14.7 s on 2 cores shared with another job): the
    preview law asks for 10 × the pump's command and 36 × its rate, the receding horizon
    (L = 0.5 m) reaches the command's limit, keeps every limit and reads a_total 4e-4 above the
    non-causal constrained bound (measured). The clipped preview law is no upper reference on
    the linear plant: it breaks the rate limit and cavitation in A (3.6 × the limit) and reads
    below the bound."""
    road, problem = board
    design = preview_design(problem)
    run, _ = _check_constrained(design, problem, road, rel=1e-3)
    assert np.max(np.abs(problem.plant.u0 + run.command)) > 0.999 * problem.u_bounds[1]
    intervals = preview_intervals(problem, PREVIEW_M, road.speed_m_s, road.wheelbase_m)
    clipped, clipped_total = _clipped_preview(design, problem, intervals)
    assert np.max(_violation(design, problem, clipped)) > 1.0
    assert clipped_total < run.a_total_m_s2


@pytest.mark.parametrize(
    ("preview_m", "horizon", "message"),
    [
        (-0.5, None, "preview_m must be a finite length >= 0 m; got -0.5"),
        (float("nan"), None, "preview_m"),
        ("1", None, "preview_m must be a length in m >= 0; got '1'"),
        (0.5, 0, "horizon must be >= 1 command interval; got 0"),
        (0.5, -3, "horizon must be >= 1"),
        (0.5, 2.5, "horizon must be an integer number of command intervals; got 2.5"),
        (0.5, True, "horizon must be an integer"),
    ],
)
def test_bad_input_names_the_argument(design, short, road, preview_m, horizon, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        receding_preview(
            design, short, preview_m, road.speed_m_s, road.wheelbase_m, horizon=horizon
        )


@pytest.mark.parametrize("tolerance", [0.0, 0.5, float("nan")])
def test_bad_tolerance_names_the_argument(design, short, road, tolerance):
    with pytest.raises(ValueError, match="tolerance must be in"):
        receding_preview(design, short, 0.5, road.speed_m_s, road.wheelbase_m, tolerance=tolerance)
