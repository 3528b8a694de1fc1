"""The constrained linear bound: condensing, the dense interior point, the limits on its optimum."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from loader_model.bound.condensed import condense
from loader_model.bound.constrained import path_limits, solve_constrained_bound
from loader_model.bound.linear import evaluate, linear_quadratic, solve_linear_bound
from loader_model.simulation.scenario import closed_loop
from loader_model.simulation.simulator import simulate


@pytest.fixture(scope="module")
def lq(problem):
    return linear_quadratic(problem)


@pytest.fixture(scope="module")
def bound(problem, lq):
    return solve_constrained_bound(problem, lq)


def test_condensed_cost_and_paths_match_the_recursion(problem, lq):
    condensed = condense(lq, problem.hold_periods)
    u = np.random.default_rng(2).normal(size=problem.intervals) * 0.3
    a_total, end, _ = evaluate(lq, u, problem)
    assert np.sqrt(condensed.cost(u) / lq.count) == pytest.approx(a_total, rel=1e-9)
    assert np.allclose(condensed.end_matrix @ u - condensed.end_target, end, atol=1e-9)
    p_z, p_u, p_offset = lq.path
    z, direct = np.zeros(lq.a.shape[0]), []
    for j in range(problem.intervals):
        direct.append(p_z @ z + p_u * u[j] + p_offset[j])
        z = lq.a @ z + lq.b * u[j] + lq.d[j]
    direct = np.array(direct).reshape(condensed.path_offset.shape)
    values = condensed.path_values(u)
    scale = np.max(np.abs(direct), axis=(0, 1))
    assert np.max(np.abs(values - direct) / scale) < 1e-9
    picked = (np.array([3, 200]), np.array([0, 7]), np.array([0, 3]))
    rows = condensed.path_rows(*picked) @ u + condensed.path_offset[picked]
    assert np.allclose(rows, direct[picked], rtol=1e-9, atol=1e-12 * scale.max())


def test_constraints_hold_on_the_constrained_optimum(problem, bound):
    """Every 1 ms sample of the pressures, stroke and rate and every command within its limit,
    to the stated tolerance (1e-6 of each limit's range); the end condition to 1e-9."""
    assert bound.converged
    _, lower, upper, scale = path_limits(problem)
    static = path_limits(problem)[0]
    deviation = bound.path - static
    assert np.all(deviation <= upper + 1e-6 * scale)
    assert np.all(deviation >= lower - 1e-6 * scale)
    command = problem.plant.u0 + bound.command
    limit = problem.u_bounds[1]
    assert np.all(np.abs(command) <= limit * (1 + 1e-9))
    assert np.max(np.abs(bound.end_residual)) < 1e-9


def test_constrained_bound_between_the_unconstrained_and_the_baseline(plant, road, problem, bound):
    unconstrained = solve_linear_bound(problem)
    baseline = simulate(road, closed_loop(plant), duration_s=problem.duration_s)
    assert unconstrained.a_total_m_s2 <= bound.a_total_m_s2 * (1 + 1e-9)
    assert bound.a_total_m_s2 < baseline.seat_evaluation().total_m_s2


def test_loose_limits_give_the_unconstrained_bound(problem, lq):
    """With every limit 100 times wider no row binds: a_total equal within 1e-7 (relative)."""
    static, lower, upper, _ = path_limits(problem)
    loose = dataclasses.replace(
        problem,
        u_bounds=tuple(100.0 * v for v in problem.u_bounds),
        rate_limit=100.0 * problem.rate_limit,
        path_lower=static[:3] + 100.0 * lower[:3],
        path_upper=static[:3] + 100.0 * upper[:3],
    )
    unconstrained = solve_linear_bound(loose)
    constrained = solve_constrained_bound(loose)
    assert constrained.a_total_m_s2 == pytest.approx(unconstrained.a_total_m_s2, rel=1e-7)


def test_bad_options_name_the_argument(problem, lq):
    with pytest.raises(ValueError, match="tolerance"):
        solve_constrained_bound(problem, lq, tolerance=0.0)
    with pytest.raises(ValueError, match="max_rounds"):
        solve_constrained_bound(problem, lq, max_rounds=0)


def test_dense_interior_point_matches_qpoases_on_a_small_qp():
    """A random definite QP with bounds, general rows and one equality: the objective equal to
    CasADi's qpOASES within 1e-8 (relative; the duality gap's tolerance 1e-9), u within 1e-5."""
    import casadi as ca

    from loader_model.bound.dense_qp import solve_dense_qp

    rng = np.random.default_rng(3)
    n, m = 20, 15
    root = rng.normal(size=(n, n))
    p, q = root @ root.T + 0.1 * np.eye(n), rng.normal(size=n)
    g, e = rng.normal(size=(m, n)), rng.normal(size=(1, n))
    lower, upper = -0.3 * np.ones(m), 0.2 * np.ones(m)
    ours = solve_dense_qp(p, q, e, np.array([0.1]), g, lower, upper, -0.5, 0.5)
    a = np.vstack([e, g])
    qp = {"h": ca.DM(p).sparsity(), "a": ca.DM(a).sparsity()}
    solver = ca.conic("reference", "qpoases", qp, {"printLevel": "none"})
    reference = solver(
        h=p, g=q, a=a, lbx=-0.5, ubx=0.5, lba=np.r_[0.1, lower], uba=np.r_[0.1, upper]
    )
    x = np.asarray(reference["x"]).ravel()

    def objective(u: np.ndarray) -> float:
        return 0.5 * u @ p @ u + q @ u

    assert ours.converged
    assert objective(ours.u) == pytest.approx(objective(x), rel=1e-8)
    assert np.allclose(ours.u, x, atol=1e-5)
