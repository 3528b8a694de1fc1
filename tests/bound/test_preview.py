"""The preview LQ law: plain LQR at zero preview, the approach to the bound, the 1 kHz controller."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from loader_model.bound.linear import solve_linear_bound
from loader_model.bound.preview import evaluate_preview, preview_design, preview_intervals
from loader_model.bound.problem import bound_problem
from loader_model.plant.scenario import resolve_plant
from loader_model.simulation.courses import Course
from loader_model.simulation.roads import board_course
from loader_model.simulation.simulator import course_input

LENGTHS_M = (0.0, 0.5, 1.0, 2.0, 4.0)


@pytest.fixture(scope="module")
def plant():
    return resolve_plant(None, "empty")


def _road(plant, height_m):
    course = Course(
        board_course(1, height_m=height_m, width_m=0.14, spacing_m=0.0), 2.5, -0.3, 2.0, ""
    )
    return course_input(course, plant)


@pytest.fixture(scope="module")
def road(plant):
    return _road(plant, 0.001)


@pytest.fixture(scope="module")
def problem(plant, road):
    return bound_problem(plant, road, duration_s=3.0)


@pytest.fixture(scope="module")
def design(problem):
    return preview_design(problem)


def _intervals(problem, road, length_m, wheelbase_preview=True):
    return preview_intervals(
        problem, length_m, road.speed_m_s, road.wheelbase_m, wheelbase_preview=wheelbase_preview
    )


def test_road_terms_of_the_two_axles_sum_to_the_bounds(design):
    wholes = (design.lq.d, design.lq.q_lin, design.lq.r_lin)
    for part, whole in zip(zip(*design.road_terms, strict=True), wholes, strict=True):
        np.testing.assert_allclose(part[0] + part[1], whole, atol=1e-12 * np.abs(whole).max())


def test_zero_preview_is_the_plain_lqr(design, problem, road):
    """No preview and no wheelbase preview: u = −K z, K python-control's ``dlqr`` on the same
    (A, B, Q + Q_drift, R, S) and the Riccati recursion iterated to its fixed point."""
    control = pytest.importorskip("control")
    lq = design.lq
    k_ref, _, _ = control.dlqr(
        lq.a, lq.b[:, None], design.state_weight, np.array([[lq.r]]), lq.s[:, None]
    )
    np.testing.assert_allclose(design.gain, np.ravel(k_ref), rtol=1e-6)
    # python-control solves with scipy here (no slycot): also iterate the Riccati recursion
    b, q, r, s = lq.b[:, None], design.state_weight, lq.r, lq.s[:, None]
    p = q.copy()
    for _ in range(20000):
        k = np.linalg.solve(r + b.T @ p @ b, b.T @ p @ lq.a + s.T)
        p_next = q + lq.a.T @ p @ lq.a - (lq.a.T @ p @ b + s) @ k
        if np.max(np.abs(p_next - p)) <= 1e-12 * np.max(np.abs(p)):
            break
        p = 0.5 * (p_next + p_next.T)
    np.testing.assert_allclose(design.gain, np.ravel(k), rtol=1e-5)
    run = evaluate_preview(design, problem, _intervals(problem, road, 0.0, False))
    assert run.intervals == (0, 0)
    z = np.zeros(lq.a.shape[0])
    for j, u in enumerate(run.command / lq.u_scale):
        assert u == pytest.approx(-design.gain @ z, rel=1e-9, abs=1e-12)
        z = lq.a @ z + lq.b * u + lq.d[j]


def test_a_total_falls_to_the_bound_as_the_preview_grows(design, problem, road):
    """a_total(L) non-increasing (to 1e-4 relative) and within 1 % of the non-causal LQ bound
    at L = 4 m (the drift weight costs 0.3 % on the paper course)."""
    totals = [
        evaluate_preview(design, problem, _intervals(problem, road, length), length).a_total_m_s2
        for length in LENGTHS_M
    ]
    assert all(b <= a * (1 + 1e-4) for a, b in itertools.pairwise(totals))
    bound = solve_linear_bound(problem).a_total_m_s2
    assert totals[-1] >= bound * (1 - 1e-6)
    assert totals[-1] == pytest.approx(bound, rel=0.01)
    plain = evaluate_preview(design, problem, _intervals(problem, road, 0.0, False))
    assert plain.a_total_m_s2 > totals[0]  # the wheelbase preview already pays


def test_simulated_controller_follows_the_linear_prediction(design, problem, road):
    """On 1 mm boards (the command within the pump's limits) with 2 m preview, the 1 kHz
    controller on the nonlinear plant reads a_total within 3 % of the linear prediction (0.6 %
    measured)."""
    from loader_model.bound.preview_report import simulate_preview

    run = evaluate_preview(design, problem, _intervals(problem, road, 2.0), 2.0)
    assert np.max(np.abs(run.command)) < problem.u_bounds[1]
    result = simulate_preview(design, problem, run, road)
    simulated = float(result.seat_evaluation().total_m_s2)
    assert simulated == pytest.approx(run.a_total_m_s2, rel=0.03)


@pytest.mark.parametrize(
    ("length", "message"),
    [(-0.5, "preview_m"), (float("nan"), "preview_m"), (100.0, "preview_m")],
)
def test_bad_preview_lengths_name_the_argument(problem, road, length, message):
    with pytest.raises(ValueError, match=message):
        _intervals(problem, road, length)


def test_bad_drift_weight_names_the_argument(problem):
    with pytest.raises(ValueError, match="drift_weight"):
        preview_design(problem, drift_weight=0.0)


def test_command_rejects_a_bad_preview_list(capsys):
    from loader_model.cli import main

    assert main(["preview", "--preview", "1,x"]) != 0
    assert "--preview" in capsys.readouterr().err


def test_sweep_writes_its_csv_and_figure(tmp_path):
    from loader_model.bound.preview_report import PreviewSweep, plot_sweep, write_csv

    sweep = PreviewSweep(
        title="test",
        preview_m=np.array([0.0, 1.0]),
        linear=np.array([3.0, 2.2]),
        simulated=np.array([np.nan, 2.3]),
        peak_command=np.array([6.0, 1.9]),
        bound_m_s2=2.18,
        lqr_m_s2=4.7,
        references={"baseline": 4.3},
    )
    assert "plain LQR" in sweep.format()
    table = np.loadtxt(write_csv(sweep, tmp_path / "preview.csv"), delimiter=",", skiprows=1)
    np.testing.assert_allclose(table[:, 1], sweep.linear)
    assert plot_sweep(sweep, tmp_path / "preview.png").stat().st_size > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["preview.csv", "preview.png"]


@pytest.mark.slow
def test_paper_course_approaches_the_bound(plant):
    """Paper course, 9 km/h, empty: a_total(L) non-increasing over 0 … 4 m and within 0.5 % of
    the non-causal LQ bound at 4 m (0.27 % measured; the drift weight is the rest)."""
    from loader_model.simulation.courses import paper_course

    road = course_input(paper_course(9.0), plant)
    problem = bound_problem(plant, road)
    design = preview_design(problem)
    totals = [
        evaluate_preview(design, problem, _intervals(problem, road, length)).a_total_m_s2
        for length in LENGTHS_M
    ]
    assert all(b <= a * (1 + 1e-4) for a, b in itertools.pairwise(totals))
    assert totals[-1] == pytest.approx(solve_linear_bound(problem).a_total_m_s2, rel=0.005)
