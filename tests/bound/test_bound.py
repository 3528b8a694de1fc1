"""The bound package: weighting, LQ bound (Riccati against a sparse KKT solve), replay, inputs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from loader_model.bound.linear import evaluate, linear_quadratic, solve_linear_bound
from loader_model.bound.problem import bound_problem
from loader_model.bound.replay import replay
from loader_model.bound.weighting import seat_weighting
from loader_model.simulation.scenario import closed_loop, ride_scenario
from loader_model.simulation.simulator import simulate


def _seat(result, weighting):
    return np.column_stack([result[s] - result[s][0] for s in weighting.signals])


@pytest.mark.slow  # two runs of the paper course with their first compilations
def test_sampled_weighting_reads_the_reports_a_total(plant):
    """The bound's filters (exact ZOH sampling of Annex A) against the report's evaluation on
    the paper course at 9 km/h, empty (the bound page): measured 3.0e-5 (baseline) and 3.6e-5
    (skyhook) apart, held at 1e-4."""
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input

    weighting = seat_weighting()
    road = course_input(paper_course(9.0), plant)
    for controller in ("baseline", "skyhook"):
        result = simulate(road, ride_scenario(plant, controller))
        reference = result.seat_evaluation().total_m_s2
        assert weighting.a_total(_seat(result, weighting)) == pytest.approx(reference, rel=1e-4)


def test_interval_maps_match_the_recursion():
    weighting = seat_weighting()
    rng = np.random.default_rng(1)
    samples = rng.normal(size=(7, len(weighting.axes)))
    l_xi, l_a, r_xi, r_a = weighting.interval_maps(7)
    assert np.allclose(l_a @ samples.ravel(), weighting.states(samples)[-1])
    assert np.allclose((r_a @ samples.ravel()).reshape(7, -1), weighting.weighted(samples))
    assert np.allclose(l_xi, np.linalg.matrix_power(weighting.phi, 7))
    assert r_xi.shape == (7 * len(weighting.axes), weighting.order)


def test_riccati_sweep_matches_the_sparse_kkt_solve(problem):
    riccati = solve_linear_bound(problem, "riccati")
    kkt = solve_linear_bound(problem, "kkt")
    assert riccati.a_total_m_s2 == pytest.approx(kkt.a_total_m_s2, rel=1e-9)
    assert np.allclose(riccati.command, kkt.command, rtol=1e-6, atol=1e-9 * problem.u_bounds[1])
    assert np.max(np.abs(riccati.end_residual)) < 1e-9


def test_lq_optimum_is_optimal_under_perturbation(problem):
    """Finite perturbations of the optimal command only raise the linear plant's a_total."""
    lq = linear_quadratic(problem)
    bound = solve_linear_bound(problem)
    optimum = bound.command / lq.u_scale
    zero = evaluate(lq, np.zeros_like(optimum), problem)[0]
    assert bound.a_total_m_s2 < 0.8 * zero
    rng = np.random.default_rng(0)
    for _ in range(3):
        step = 1e-3 * rng.normal(size=optimum.size)
        assert evaluate(lq, optimum + step, problem)[0] >= bound.a_total_m_s2 - 1e-12


def test_linear_model_at_zero_command_is_close_to_the_simulator(plant, road, problem):
    """The LQ problem's free response against the nonlinear baseline on 5 mm: within 5 %."""
    lq = linear_quadratic(problem)
    linear = evaluate(lq, np.zeros(problem.intervals), problem)[0]
    baseline = simulate(road, closed_loop(plant), duration_s=problem.duration_s)
    nonlinear = seat_weighting().a_total(_seat(baseline, seat_weighting()))
    assert linear == pytest.approx(nonlinear, rel=0.05)


# slow: 5.4 s (a bound playback over the course)
@pytest.mark.slow
def test_playback_of_the_static_command_is_the_baseline(plant, road, problem):
    table = np.full(problem.intervals, plant.u0)
    played = replay(plant, road, table, problem.hold_periods)
    baseline = simulate(road, closed_loop(plant), duration_s=problem.duration_s)
    assert np.allclose(played["f_Sy"], baseline["f_Sy"], rtol=0, atol=1e-12)


def test_playback_holds_each_value_for_its_interval(plant, road):
    table = plant.u0 + np.array([0.0, 1e-6, -1e-6, 2e-6] * 75)
    played = replay(plant, road, table, 10)
    assert np.array_equal(played["V_p_ref"], np.repeat(table, 10))


def test_bad_inputs_name_the_argument(plant, road):
    with pytest.raises(ValueError, match="hold_periods"):
        bound_problem(plant, road, hold_periods=0)
    with pytest.raises(ValueError, match="max_intervals"):
        bound_problem(plant, road, max_intervals=10)
    params = plant.params.copy()
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    params[PLANT_PARAMETER_NAMES.index("V_p_max")] = 0.0
    zero_pump = dataclasses.replace(plant, params=params)
    with pytest.raises(ValueError, match="V_p_max"):
        bound_problem(zero_pump, road)


def test_command_rejects_an_unknown_controller(capsys):
    from loader_model.cli import main

    assert main(["bound", "--controllers", "baseline,nope"]) == 2
    assert "--controllers" in capsys.readouterr().err
