"""The Riccati interior point of the stage-form QP against qpOASES (CasADi's active-set solver)
on the explicit condensation, built here by impulse responses of the dynamics, and the stage
model of the nonlinear bound against finite differences of the simulator."""

from __future__ import annotations

from dataclasses import replace

import casadi as ca
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from loader_model.bound.constrained import path_limits
from loader_model.bound.problem import PATH_SIGNALS, bound_problem
from loader_model.bound.riccati_qp import solve_riccati_qp
from loader_model.bound.stage_form import StageQP, condensed_gradient, mean_condensed_curvature
from loader_model.bound.stage_model import stage_qp
from loader_model.bound.trajectory import linearise, linearised_period, rollout
from loader_model.bound.weighting import seat_weighting


def _random_qp(
    seed: int, n: int = 14, nz: int = 4, n_rows: int = 3, n_end: int = 2, nu: int = 1
) -> StageQP:
    rng = np.random.default_rng(seed)
    transition = 0.9 * rng.normal(size=(n, nz, nz)) / np.sqrt(nz)
    residuals = rng.normal(size=(n, 2 + nu, nz + nu))
    hessian = np.einsum("jri,jrk->jik", residuals, residuals)
    hessian[:, nz:, nz:] += 1e-3 * np.eye(nu)
    qp = StageQP(
        transition=transition,
        command_map=rng.normal(size=(n, nz, nu)),
        hessian=hessian,
        gradient=rng.normal(size=(n, nz + nu)),
        rows=rng.normal(size=(n, n_rows, nz + nu)),
        row_low=np.zeros((n, n_rows)),
        row_high=np.zeros((n, n_rows)),
        v_low=np.full((n, nu), -0.5),
        v_high=np.full((n, nu), 0.5),
        end_rows=rng.normal(size=(n_end, nz)),
        end_target=np.zeros(n_end),
    )
    # limits around a feasible point, some of them tight
    feasible = rng.uniform(-0.4, 0.4, size=n * nu)
    _, _, rows, end = _condensed(qp)
    values = (rows @ feasible).reshape(n, n_rows)
    return replace(
        qp,
        row_low=values - rng.uniform(0.01, 0.5, size=(n, n_rows)),
        row_high=values + rng.uniform(0.01, 0.5, size=(n, n_rows)),
        end_target=end @ feasible,
    )


def _condensed(qp: StageQP) -> tuple[np.ndarray, ...]:
    """The QP in the commands alone (stage by stage, n_u per stage): every stage variable's
    response to each unit command, by the loop of the dynamics written out here."""
    n, nz, nu = qp.command_map.shape
    response = np.zeros((n, nz + nu, n * nu))  # w_j as a function of the commands
    end = np.zeros((nz, n * nu))
    for i in range(n * nu):
        z = np.zeros(nz)
        for j in range(n):
            response[j, :nz, i] = z
            v = np.zeros(nu)
            if j == i // nu:
                v[i % nu] = 1.0
            response[j, nz:, i] = v
            z = qp.transition[j] @ z + qp.command_map[j] @ v
        end[:, i] = z
    hessian = np.einsum("jai,jab,jbk->ik", response, qp.hessian, response)
    gradient = np.einsum("ja,jai->i", qp.gradient, response)
    rows = np.einsum("jra,jai->jri", qp.rows, response).reshape(-1, n * nu)
    return hessian, gradient, rows, qp.end_rows @ end


def _qpoases(qp: StageQP) -> tuple[np.ndarray, float]:
    hessian, gradient, rows, end = _condensed(qp)
    a = np.vstack([rows, end])
    solver = ca.conic(
        "reference", "qpoases", {"h": ca.DM(hessian).sparsity(), "a": ca.DM(a).sparsity()},
        {"printLevel": "none", "error_on_fail": True},
    )  # fmt: skip
    solution = solver(
        h=hessian, g=gradient, a=a, lbx=qp.v_low.ravel(), ubx=qp.v_high.ravel(),
        lba=np.concatenate([qp.row_low.ravel(), qp.end_target]),
        uba=np.concatenate([qp.row_high.ravel(), qp.end_target]),
    )  # fmt: skip
    return np.asarray(solution["x"]).ravel(), float(solution["cost"])


def _cost(qp: StageQP, v: np.ndarray) -> float:
    hessian, gradient, _, _ = _condensed(qp)
    return 0.5 * v @ hessian @ v + gradient @ v


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**31), inputs=st.integers(1, 3))
@example(seed=1107360, inputs=2)  # stalled at a dual residual of 2.8e-9 with one refinement step
def test_random_stage_qps_reach_qpoases_optimum(seed, inputs):
    """Random convex stage QPs (14 stages, 4 states, 1-3 inputs, 3 two-sided rows per stage, a
    box, 2 end rows; random dynamics, some unstable): the optimum's cost agrees with qpOASES'
    within 1e-7 relative (measured below 1e-9), the rows and end rows hold to 1e-8, it
    converged, and the commands differ from qpOASES' only as far as the cost's curvature
    allows: ½ λ_min ‖u − u_ref‖² ≤ |f(u) − f(u_ref)| + 1e-9 (1 + |f|) (strong convexity at
    the optimum; λ_min the condensed Hessian's smallest eigenvalue). Measured over 150 seeds
    each: max |u − u_ref| 4.5e-6 with one input (λ_min ≥ 2), 3.8e-5 with two (λ_min 6e-3:
    flat directions the tolerance leaves open)."""
    qp = _random_qp(seed, nu=inputs)
    result, w = solve_riccati_qp(qp)
    reference, cost = _qpoases(qp)
    assert result.converged
    ours = _cost(qp, result.u)
    assert ours == pytest.approx(cost, rel=1e-7, abs=1e-9)
    hessian, _, rows, end = _condensed(qp)
    smallest = np.linalg.eigvalsh(hessian)[0]
    distance = np.sum((result.u - reference) ** 2)
    assert 0.5 * smallest * distance <= abs(ours - cost) + 1e-9 * (1.0 + abs(cost))
    values = rows @ result.u
    assert np.all(values <= qp.row_high.ravel() + 1e-8)
    assert np.all(values >= qp.row_low.ravel() - 1e-8)
    assert np.max(np.abs(end @ result.u - qp.end_target)) <= 1e-8
    assert np.max(np.abs(w[:, qp.states :].ravel() - result.u)) == 0.0


def test_curvature_and_gradient_are_the_condensed_ones():
    """The exact mean of the condensed Hessian's diagonal and the condensed gradient against
    the explicit condensation: within 1e-12 relative."""
    for inputs in (1, 3):
        qp = _random_qp(7, nu=inputs)
        hessian, gradient, _, _ = _condensed(qp)
        curvature = mean_condensed_curvature(qp)
        assert curvature == pytest.approx(np.mean(np.diag(hessian)), rel=1e-12)
        error = np.max(np.abs(condensed_gradient(qp) - gradient))
        assert error <= 1e-12 * np.max(np.abs(gradient))


def test_one_linearisation_does_not_compile_the_period(plant, road, tmp_path, monkeypatch):
    """Without ``compile_missing`` and with an empty cache, :func:`linearise` runs the period in
    CasADi's virtual machine and writes no library (its compilation, about 12 s, would not be
    repaid by one linearisation); the result is the period Function's, to 1e-12."""
    from loader_model.bound import trajectory as module

    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(module, "_MAPPED", {})
    problem = bound_problem(plant, road, duration_s=0.05)
    command = np.full(problem.intervals, plant.u0 + 0.2 * problem.u_bounds[1])
    trajectory = rollout(problem, command)
    linearisation = linearise(problem, trajectory)
    assert not list(tmp_path.glob("bound_linearised_period-*"))
    k = problem.periods - 1
    out = linearised_period()(
        trajectory.states[k], command[-1], problem.exogenous[k], problem.exogenous[k + 1],
        plant.params,
    )  # fmt: skip
    expected = np.asarray(out[2])
    assert np.max(np.abs(linearisation.a[k] - expected)) <= 1e-12 * np.max(np.abs(expected))


# slow: 15 s (compiles the chunked linearisation)
@pytest.mark.slow
def test_linearise_is_the_linearised_period_at_every_sampled_period(plant, road):
    """The compiled, chunked evaluation of :func:`linearise` against the period Function in
    CasADi's virtual machine at the chunks' edges: equal to 1e-12 of each matrix's size
    (measured: identical)."""
    problem = bound_problem(plant, road, duration_s=1.1)
    command = plant.u0 + 0.3 * problem.u_bounds[1] * np.sin(np.arange(problem.intervals) / 5)
    trajectory = rollout(problem, command)
    linearisation = linearise(problem, trajectory, compile_missing=True)
    function = linearised_period()
    u_k = np.append(np.repeat(command, problem.hold_periods), command[-1])
    exo = problem.exogenous
    for k in (0, 1, 499, 500, 501, 999, 1000, problem.periods - 1):
        out = function(trajectory.states[k], u_k[k], exo[k], exo[k + 1], plant.params)
        for ours, theirs in ((linearisation.a[k], out[2]), (linearisation.c[k], out[4])):
            theirs = np.asarray(theirs)
            assert np.max(np.abs(ours - theirs)) <= 1e-12 * np.max(np.abs(theirs))
        theirs = np.asarray(out[3]).ravel()
        assert np.max(np.abs(linearisation.b[k] - theirs)) <= 1e-12 * np.max(np.abs(theirs))


@pytest.mark.parametrize("block", [1, 5])
def test_stage_rows_are_the_linearised_path_sensitivities(plant, road, block):
    """The path rows of the stage model (one and five command intervals per stage),
    condensed, on a 0.3 s problem and three commands:
    against the period-by-period product of the linearisation written out here, within 1e-9 of
    each signal's largest sensitivity; against central differences of the simulated signals,
    V̇_p within 1e-8 and the piston within 1e-2 (measured 1e-12 and 4.6e-3), the pressures within
    0.15 (measured 9.6e-2 in A, 3.1e-2 in B): the flow's sensitivities differ from the
    discrete step's in the stiff hydraulic modes (the gradient test of test_nonlinear)."""
    from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES

    problem = bound_problem(plant, road, duration_s=0.3)
    scale, m = problem.u_bounds[1], problem.hold_periods
    command = plant.u0 + 0.2 * scale * np.sin(np.arange(problem.intervals) / 3.0)
    trajectory = rollout(problem, command)
    linearisation = linearise(problem, trajectory)
    limits = path_limits(problem)
    qp = stage_qp(problem, trajectory, linearisation, seat_weighting(), scale, limits, block)
    _, _, rows, _ = _condensed(qp)  # (N M n_p, N) divided by each limit
    n_p = len(PATH_SIGNALS) + 1
    rows = rows.reshape(problem.periods, n_p, problem.intervals) * limits[3][None, :, None]
    outputs = [OUTPUT_NAMES.index(name) for name in PATH_SIGNALS]
    step, finite_tolerance = 1e-4, (0.15, 0.15, 1e-2, 1e-8)
    for j in (0, 11, 23):
        sensitivity, product = np.zeros(len(STATE_NAMES)), np.empty((problem.periods, n_p))
        for k in range(problem.periods):
            product[k, :-1] = linearisation.c[k][outputs] @ sensitivity
            product[k, -1] = sensitivity[STATE_NAMES.index("Vd_p")]
            sensitivity = linearisation.a[k] @ sensitivity
            sensitivity += linearisation.b[k] * scale * (k // m == j)
        delta = np.zeros(problem.intervals)
        delta[j] = step * scale
        finite = (
            rollout(problem, command + delta).path() - rollout(problem, command - delta).path()
        ) / (2 * step)
        for signal in range(n_p):
            size = np.max(np.abs(product[:, signal]))
            assert np.max(np.abs(rows[:, signal, j] - product[:, signal])) <= 1e-9 * size
            error = np.max(np.abs(rows[:, signal, j] - finite[:, signal]))
            assert error <= finite_tolerance[signal] * np.max(np.abs(finite[:, signal]))


@pytest.mark.parametrize("block", [1, 3])
def test_the_corrected_qp_predicts_the_simulated_step(plant, road, block):
    """The second-order correction's rows and end condition, at the step they are made from,
    equal the simulated step's path values and end values (the linearisation's error is put
    back exactly, to 1e-9 of the limits), and they differ from the uncorrected rows by that
    error (nonzero here: the step is large)."""
    from loader_model.bound.stage_form import forward as _forward
    from loader_model.bound.stage_model import corrected_qp, end_values

    problem = bound_problem(plant, road, duration_s=0.3)
    scale = problem.u_bounds[1]
    command = plant.u0 + 0.2 * scale * np.sin(np.arange(problem.intervals) / 3.0)
    trajectory = rollout(problem, command)
    limits = path_limits(problem)
    qp = stage_qp(problem, trajectory, linearise(problem, trajectory), seat_weighting(), scale,
                  limits, block)  # fmt: skip
    step = 0.5 * np.cos(np.arange(problem.intervals) / 4.0)
    w, z_end = _forward(qp, step.reshape(-1, block))
    candidate = rollout(problem, command + step * scale)
    corrected = corrected_qp(qp, w, problem, trajectory, candidate, limits)
    static, _, upper, size = limits
    predicted = corrected.row_high - (qp.rows @ w[:, :, None])[:, :, 0]
    simulated = ((upper - (candidate.path() - static)) / size).reshape(predicted.shape)
    assert np.max(np.abs(predicted - simulated)) <= 1e-9
    assert np.max(np.abs(corrected.row_high - qp.row_high)) >= 1e-4
    targets = np.array(list(problem.end_targets.values()))
    ends = corrected.end_target - qp.end_rows @ z_end
    expected = targets - end_values(problem, candidate)
    assert np.max(np.abs(ends - expected) / (np.abs(targets) + scale + 1e-3)) <= 1e-9


def test_stages_of_several_intervals_solve_the_same_qp(plant, road):
    """The stage model with 1, 3 and 5 command intervals per stage is the same QP: on a 0.3 s
    problem (30 intervals) the condensed gradient and mean curvature agree to 1e-12 relative
    (measured 4e-15) and the solutions' commands to 1e-9 of the pump's limit (measured 1.6e-12
    with the QPs' tolerance 1e-8; on the 11.55 s paper course at 18 km/h, tolerance 1e-6,
    3.4e-7)."""
    from loader_model.bound.stage_model import stage_block

    problem = bound_problem(plant, road, duration_s=0.3)
    scale = problem.u_bounds[1]
    command = plant.u0 + 0.2 * scale * np.sin(np.arange(problem.intervals) / 3.0)
    trajectory = rollout(problem, command)
    linearisation = linearise(problem, trajectory)
    limits = path_limits(problem)
    solutions = {}
    for block in (1, 3, 5):
        qp = stage_qp(problem, trajectory, linearisation, seat_weighting(), scale, limits, block)
        solutions[block] = (
            condensed_gradient(qp),
            mean_condensed_curvature(qp),
            solve_riccati_qp(qp, tolerance=1e-8)[0],
        )
    gradient, curvature, result = solutions[1]
    assert result.converged
    for block in (3, 5):
        other_gradient, other_curvature, other = solutions[block]
        assert other.converged
        assert other_curvature == pytest.approx(curvature, rel=1e-12)
        assert np.max(np.abs(other_gradient - gradient)) <= 1e-12 * np.max(np.abs(gradient))
        assert np.max(np.abs(other.u - result.u)) <= 1e-9
    assert stage_block(30) == 5 and stage_block(1200) == 4 and stage_block(601) == 1
    with pytest.raises(ValueError, match="intervals_per_stage must divide the 30"):
        stage_qp(problem, trajectory, linearisation, seat_weighting(), scale, limits, 4)
