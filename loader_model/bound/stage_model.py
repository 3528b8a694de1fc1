r"""The Gauss-Newton QP of the nonlinear bound in stage form, for the Riccati interior point.

Along the trajectory of :mod:`~loader_model.bound.trajectory` the stage variables are the
deviations of the stacked plant and ISO weighting-filter state at the start of stage j, δz_j
(n_z = plant states + filter states), and of the stage's n_b commands, δv_j (in units of the
pump's limit; n_b command intervals per stage, :func:`stage_block`). The equations below are
written for n_b = 1; with n_b > 1 the stage spans n_b M periods and ψ has one column per command,
the column of interval i receiving B̃_k in that interval's periods. Stages of n_b = 4 or 5
intervals solve the same QP (on the 11.55 s paper course at 18 km/h the commands of n_b = 1, 3,
5 and 7 agreed to 3.4e-7 of the limit, their mean curvature and gradient to 1e-14) in 1.7 s
instead of 4.5 s (27 interior-point iterations; the Riccati recursion's cost is per stage and
hardly grows with n_b, while the rows' cost is the same in total). Inside the interval the period
maps Ã_k, B̃_k (the plant's A_k, B_k of
:func:`~loader_model.bound.trajectory.linearise` with the weighting filter's state ξ driven by
the seat's rows C_{s,k}: ξ_{k+1} = Φ ξ_k + Γ C_{s,k} δx_k, :mod:`~loader_model.bound.weighting`)
give, for the sub-periods b = 0 … M − 1,

.. math:: \delta z_{jM+b} = \Phi_{j,b}\,\delta z_j + \psi_{j,b}\,\delta v_j , \qquad
    \Phi_{j,b+1} = \tilde A_{jM+b} \Phi_{j,b},\quad \psi_{j,b+1} = \tilde A_{jM+b}\psi_{j,b}
    + \tilde B_{jM+b}

(Φ_{j,0} = I, ψ_{j,0} = 0), so the dynamics are δz_{j+1} = Φ_{j,M} δz_j + ψ_{j,M} δv_j, and
each weighted seat residual of a_total² (Eq. 49, 50) and each path sample of the interval
(:data:`~loader_model.bound.problem.PATH_SIGNALS` and V̇_p, divided by its limit) is linear in
(δz_j, δv_j): the stage's Gauss-Newton cost 2/K_s Σ_b ‖r_b + J_b (δz_j, δv_j)‖² and its M n_p
path rows. δz_0 = 0; the end condition is a constraint on δz_N. The states are in units of
their largest one-stage response to a command (the Riccati recursion and the interior
point's tolerances then see entries of one size; HPIPM did not converge without it). It
replaces an earlier condensed model (the sensitivities of every sample to all N commands,
a dense N × N Hessian and every path sample a dense row: O(N² K_s) to build and O(N³) per
interior-point iteration); on the 6 s problem its gradient and mean curvature agreed with that
model's to 1e-14 and its path rows to 1e-15 relative. Built in O(N M n_z³): 0.4 s for the
11.55 s course (n_b = 5).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from loader_model.bound.problem import PATH_SIGNALS, BoundProblem, pump_states
from loader_model.bound.stage_form import StageQP
from loader_model.bound.trajectory import Linearisation, Trajectory
from loader_model.bound.weighting import SeatWeighting

__all__ = ["INTERVALS_PER_STAGE", "corrected_qp", "end_values", "stage_block", "stage_qp"]

#: Command intervals per stage the nonlinear bound aims for (:func:`stage_block`).
INTERVALS_PER_STAGE = 4
#: Most command intervals in one stage.
MAX_INTERVALS_PER_STAGE = 8


def stage_block(intervals: int, target: int = INTERVALS_PER_STAGE) -> int:
    """The command intervals per stage for a problem of ``intervals``: the divisor of it in
    1 … :data:`MAX_INTERVALS_PER_STAGE` nearest to ``target`` (the larger on a tie)."""
    divisors = [b for b in range(1, MAX_INTERVALS_PER_STAGE + 1) if intervals % b == 0]
    return min(divisors, key=lambda b: (abs(b - target), -b))


def stage_qp(
    problem: BoundProblem,
    trajectory: Trajectory,
    linearisation: Linearisation,
    weighting: SeatWeighting,
    u_scale: float,
    limits: tuple[np.ndarray, ...],
    intervals_per_stage: int = 1,
) -> StageQP:
    """The stage-form Gauss-Newton QP about ``trajectory`` in δv (module notes), with
    ``intervals_per_stage`` command intervals (n_b, a divisor of N) in each stage."""
    count, m, n_int = problem.periods, problem.hold_periods, problem.intervals
    b_int = int(intervals_per_stage)
    if b_int < 1 or n_int % b_int:
        raise ValueError(
            f"intervals_per_stage must divide the {n_int} command intervals; got {b_int}"
        )
    n, span = n_int // b_int, b_int * m  # stages, periods per stage
    states, outputs = problem.layout.state_names, problem.layout.output_names
    nx, nf, na = len(states), weighting.order, len(weighting.axes)
    nz = nx + nf
    seat_rows = [outputs.index(s) for s in weighting.signals]
    path_outputs = [outputs.index(s) for s in PATH_SIGNALS]
    rate = states.index(pump_states(problem.layout)[1])
    n_p = len(PATH_SIGNALS) + 1
    k_diag = np.diag(weighting.k_factors)
    residual = weighting.weighted(trajectory.seat()).reshape(n, span * na)
    c_all = linearisation.c[:count].reshape(n, span, -1, nx)
    a_all = linearisation.a.reshape(n, span, nx, nx)
    b_all = linearisation.b.reshape(n, span, nx) * u_scale
    phi = np.broadcast_to(np.eye(nz), (n, nz, nz)).copy()
    psi = np.zeros((n, nz, b_int))
    res_rows = np.empty((n, span, na, nz + b_int))
    path_rows = np.empty((n, span, n_p, nz + b_int))
    aug = np.zeros((n, nz, nz))
    aug[:, nx:, nx:] = weighting.phi
    out_seat = np.zeros((n, na, nz))
    out_seat[:, :, nx:] = k_diag @ weighting.c
    seat_d = k_diag @ weighting.d
    out_path = np.zeros((n, n_p, nz))
    out_path[:, n_p - 1, rate] = 1.0
    for q in range(span):
        c_seat = c_all[:, q][:, seat_rows]  # (n, axes, nx)
        out_seat[:, :, :nx] = np.matmul(seat_d, c_seat)
        out_path[:, : n_p - 1, :nx] = c_all[:, q][:, path_outputs]
        res_rows[:, q, :, :nz] = out_seat @ phi
        res_rows[:, q, :, nz:] = out_seat @ psi
        path_rows[:, q, :, :nz] = out_path @ phi
        path_rows[:, q, :, nz:] = out_path @ psi
        aug[:, :nx, :nx] = a_all[:, q]
        aug[:, nx:, :nx] = np.matmul(weighting.gamma, c_seat)
        phi = aug @ phi
        psi = aug @ psi
        psi[:, :nx, q // m] += b_all[:, q]
    # the states in units of their largest one-interval response to the command
    d = np.max(np.abs(psi), axis=(0, 2))
    d = np.where(d > 0, d, 1.0)
    dd = np.concatenate([d, np.ones(b_int)])
    jac = res_rows.reshape(n, span * na, nz + b_int) * dd
    hessian = 2.0 / count * np.matmul(jac.transpose(0, 2, 1), jac)
    gradient = 2.0 / count * np.einsum("bri,br->bi", jac, residual)
    static, lower, upper, scale = limits
    current = (trajectory.path() - static).reshape(n, span, n_p)
    path_rows *= dd / scale[None, None, :, None]
    end_rows = []
    for name in problem.end_targets:
        row = np.zeros(nz)
        if name in states:
            row[states.index(name)] = 1.0
        else:
            row[:nx] = linearisation.c[count, outputs.index(name)]
        end_rows.append(row * d)
    end_target = np.array(list(problem.end_targets.values())) - end_values(problem, trajectory)
    v = (trajectory.command / u_scale).reshape(n, b_int)
    return StageQP(
        transition=phi * d[None, None, :] / d[None, :, None],
        command_map=psi / d[None, :, None],
        hessian=hessian,
        gradient=gradient,
        rows=path_rows.reshape(n, span * n_p, nz + b_int),
        row_low=((lower - current) / scale).reshape(n, span * n_p),
        row_high=((upper - current) / scale).reshape(n, span * n_p),
        v_low=problem.u_bounds[0] / u_scale - v,
        v_high=problem.u_bounds[1] / u_scale - v,
        end_rows=np.array(end_rows),
        end_target=end_target,
    )


def end_values(problem: BoundProblem, trajectory: Trajectory) -> np.ndarray:
    """The end condition's signals at the end of ``trajectory`` (states or outputs), in the
    order of :attr:`~loader_model.bound.problem.BoundProblem.end_targets`."""
    states, outputs = problem.layout.state_names, problem.layout.output_names
    return np.array([
        trajectory.states[-1, states.index(name)] if name in states
        else trajectory.outputs[-1, outputs.index(name)]
        for name in problem.end_targets
    ])  # fmt: skip


def corrected_qp(
    qp: StageQP,
    w: np.ndarray,
    problem: BoundProblem,
    trajectory: Trajectory,
    candidate: Trajectory,
    limits: tuple[np.ndarray, ...],
) -> StageQP:
    """``qp`` with its path rows and end condition shifted by the linearisation's error at its
    step ``w`` (the second-order correction of SQP, Nocedal and Wright, 2006, § 18.3).

    The error is what the simulated ``candidate`` (the trajectory of the step) gives minus what
    the QP's rows predict for it; the corrected QP asks the *simulated* path values and end
    values, to first order about the step, to meet the limits. Both QPs share the Hessian and
    the gradient.
    """
    n = qp.transition.shape[0]
    scale = limits[3]
    predicted = (qp.rows @ w[:, :, None])[:, :, 0]
    simulated = ((candidate.path() - trajectory.path()) / scale).reshape(n, -1)
    error = simulated - predicted
    end_predicted = qp.end_rows @ (qp.stacked[-1] @ w[-1])
    end_error = end_values(problem, candidate) - end_values(problem, trajectory) - end_predicted
    return replace(
        qp,
        row_low=qp.row_low - error,
        row_high=qp.row_high - error,
        end_target=qp.end_target - end_error,
    )
