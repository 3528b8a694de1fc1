r"""Receding-horizon preview with the machine's limits: linear MPC on the preview law's model.

The design model and cost are the preview law's (:mod:`~loader_model.bound.preview`): the lifted
linear plant z_{j+1} = A z_j + B u_j + d_j on the 10 ms command grid, the stage cost of a_total²
(Eq. 49, 50) with the drift weight's stage terms (Q + Q_drift, S, R and the road's q_j, r_j). At
every command interval j, from the plant's lifted state z_j, it solves over H intervals

.. math::

    \min_u \sum_{m<H} \ell_{j+m}(x_m, u_m) + x_H^T P x_H, \qquad x_0 = z_j, \quad
    x_{m+1} = A x_m + B u_m + \hat d_{j+m},

with \hat d, \hat q, \hat r the road terms of the preview window only (the front axle's for
m < n_f, the rear axle's for m < n_r, :func:`~loader_model.bound.preview.preview_intervals`;
beyond it the road is static, zero deviation) and P the design's Riccati solution: the exact
value of the unconstrained law once the road is static, so without active limits and with
H ≥ n_r the plan's first command is the preview law's. Constraints: |u_m| ≤ 0.99 V_p,max
(the bound problem's ``u_bounds`` around u0) and at every 1 ms period of the horizon the pump's
displacement rate, both chamber pressures (cavitation, relief) and the piston stroke
(:func:`~loader_model.bound.constrained.path_limits`), each with the window road's offsets.

The QP is the condensed one (:func:`~loader_model.bound.condensed.condense` on the window's
problem; the current state folded into the first interval's road terms; the terminal cost as the
end map of a square root of P, moved from the equality rows into the Hessian), solved by
constraint generation as the constrained bound's (:func:`~loader_model.bound.constrained.
generate_constraints`) with :func:`~loader_model.bound.dense_qp.solve_dense_qp`: every 1 ms
sample of the horizon is checked, the violated ones join the working set (carried to the next
interval shifted by one), so the plan meets all H M samples to the tolerance. The path rows are
softened by one variable σ ≥ 0, the plan's largest violation relative to the limits, weighted
by :data:`SOFT_WEIGHT` (an exact L∞ penalty: σ = 0 and the hard plan whenever one exists): a
causal plan may find a board too late to meet every limit, and the hard QP of
``generate_constraints`` stopped with NaN in the interior point's normal matrix on the paper
course (L = 0.5 m), where the softened one solved every plan with σ ≤ 8e-9. The first command
is applied and the plant advanced one interval on the true road of both axles, as
:func:`~loader_model.bound.preview.evaluate_preview` advances it.

Default horizon: the rear axle's preview intervals n_r plus :data:`TAIL_INTERVALS`. Beyond the
window the road is static, so the tail only lets the plan see the limits while the boom comes
back to rest under the terminal law (the closed loop's slowest modes decay by about 1.5 % per
interval); a plan that ends where the last known board does could leave the terminal law a state
it cannot bring back within the limits.

Each plan's matrices are small (H up to about 150): the loop runs on one BLAS thread. With the
default threads on the development machine (2 cores shared with another job) one Cholesky factor
of 153 × 153 took 40 ms instead of 0.2 ms and a run 30 times as long.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from loader_model.bound.condensed import CondensedProblem, condense
from loader_model.bound.constrained import DROP_MARGIN, PATH_TOLERANCE, _violation, path_limits
from loader_model.bound.dense_qp import solve_dense_qp
from loader_model.bound.linear import evaluate
from loader_model.bound.preview import PreviewDesign, PreviewRun, preview_intervals
from loader_model.bound.problem import BoundProblem

__all__ = ["TAIL_INTERVALS", "RecedingRun", "receding_preview"]

#: Intervals (10 ms) the default horizon extends past the rear axle's preview (module notes).
TAIL_INTERVALS = 25
#: Weight of a plan's largest path violation σ (relative to the limits) over the QP's own scale:
#: an exact L∞ penalty, so σ = 0 whenever a plan within all limits exists (module notes).
SOFT_WEIGHT = 1e3
#: σ = κ s with s the QP's variable, which shares the command's (scaled) box: σ ≤ κ u_hi (8.9 for
#: the empty bucket).
_SIGMA_SCALE = 10.0
#: Stands for "no bound" on the one-sided halves of the softened rows (relative units).
_FAR = 1e3


@dataclass(frozen=True)
class RecedingRun(PreviewRun):
    """A :class:`~loader_model.bound.preview.PreviewRun` of the receding-horizon law, with the
    QP's statistics (the simulator's path, :func:`~loader_model.bound.preview_report.
    simulate_preview`, reads the base fields only).

    Attributes
    ----------
    horizon : int
        H, command intervals of each plan.
    qp_s : numpy.ndarray
        (N,) wall time of each interval's QP (building and constraint generation), s.
    iterations : numpy.ndarray
        (N,) interior-point iterations of each interval over its rounds.
    rows : numpy.ndarray
        (N,) path rows in each interval's final working set.
    converged : numpy.ndarray
        (N,) each QP converged with no sample of its plan violating by more than the tolerance.
    plan_violation : numpy.ndarray
        (N,) σ of each plan: its largest path violation relative to the limits (0 when a plan
        within all limits exists).
    run_s : float
        Wall time of the whole run, s.
    """

    horizon: int = 0
    qp_s: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    iterations: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, int))
    rows: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, int))
    converged: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, bool))
    plan_violation: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    run_s: float = 0.0


def _window(terms: tuple, counts: tuple[int, int], start: int, horizon: int) -> list:
    """Each of the (front, rear) axles' road terms over ``horizon`` intervals from ``start``,
    kept for the first ``counts`` intervals and zero beyond (also beyond the course), summed."""
    total = []
    for parts in zip(*terms, strict=True):
        window = np.zeros((horizon, *parts[0].shape[1:]))
        for part, count in zip(parts, counts, strict=True):
            stop = min(start + min(count, horizon), part.shape[0])
            window[: max(stop - start, 0)] += part[start:stop]
        total.append(window)
    return total


def _plan(
    condensed: CondensedProblem,
    p_matrix: np.ndarray,
    q_vector: np.ndarray,
    limits: tuple[np.ndarray, ...],
    box: tuple[float, float],
    rows: np.ndarray,
    tolerance: float,
    max_rounds: int = 40,
) -> tuple:
    """One plan: min ½ uᵀPu + qᵀu + ρ σ with every path sample within its limits widened by σ ≥ 0
    (relative), by constraint generation from ``rows`` (module notes).

    Returns
    -------
    tuple
        (u, σ, working set, interior-point iterations, converged).
    """
    _, lower, upper, scale = limits
    size = q_vector.size
    weight = SOFT_WEIGHT * max(
        1.0, float(np.max(np.abs(q_vector))), float(np.max(np.diag(p_matrix)))
    )
    p_soft = np.zeros((size + 1, size + 1))
    p_soft[:size, :size] = p_matrix
    p_soft[size, size] = 1e-9 * weight
    q_soft = np.append(q_vector, weight)
    iterations, converged = 0, False
    for round_ in range(max_rounds):
        i, s, k = rows.T
        if len(rows) == 0:  # the box alone: no σ
            result = solve_dense_qp(
                p_matrix, q_vector, np.zeros((0, size)), np.zeros(0), np.zeros((0, size)),
                np.zeros(0), np.zeros(0), *box,
            )  # fmt: skip
            u, sigma = result.u, 0.0
        else:
            g = condensed.path_rows(i, s, k) / scale[k, None]
            offset = condensed.path_offset[i, s, k]
            low, high, far = (lower[k] - offset) / scale[k], (upper[k] - offset) / scale[k], _FAR
            column = np.full((len(rows), 1), _SIGMA_SCALE)
            last = np.zeros((1, size + 1))
            last[0, size] = 1.0
            result = solve_dense_qp(
                p_soft, q_soft, np.zeros((0, size + 1)), np.zeros(0),
                np.vstack([np.hstack([g, -column]), np.hstack([g, column]), last]),
                np.concatenate([np.full(len(rows), -far), low, [0.0]]),
                np.concatenate([high, np.full(len(rows), far), [far]]), *box,
            )  # fmt: skip
            u, sigma = result.u[:size], max(_SIGMA_SCALE * float(result.u[size]), 0.0)
        iterations += result.iterations
        excess = _violation(condensed, u, limits)
        worst, sub = excess.max(axis=1), excess.argmax(axis=1)
        new_i, new_k = np.nonzero(worst > sigma + tolerance)
        if new_i.size == 0:
            converged = result.converged
            break
        if round_ == 0 and len(rows):  # carried rows far inside their limits leave the set
            rows = rows[excess[rows[:, 0], rows[:, 1], rows[:, 2]] > -DROP_MARGIN]
        rows = np.vstack([rows, np.column_stack([new_i, sub[new_i, new_k], new_k])])
    return u, sigma, rows, iterations, converged


def receding_preview(
    design: PreviewDesign,
    problem: BoundProblem,
    preview_m: float,
    speed_m_s: float,
    wheelbase_m: float,
    *,
    horizon: int | None = None,
    tolerance: float = PATH_TOLERANCE,
) -> RecedingRun:
    """Run the receding-horizon constrained preview (module notes) over ``problem``'s course.

    Parameters
    ----------
    design : PreviewDesign
        The preview law of ``problem`` (:func:`~loader_model.bound.preview.preview_design`).
    problem : BoundProblem
        Grid, road and limits (``design`` built from it: the same command scale).
    preview_m : float
        L, metres of road known ahead of the front axle (the rear axle's: L + wheelbase).
    speed_m_s, wheelbase_m : float
        Travel speed in m/s and wheelbase in m (:class:`~loader_model.simulation.travel.
        RoadInput`).
    horizon : int, optional
        H, command intervals of each plan, >= 1 (default: the rear axle's preview intervals plus
        :data:`TAIL_INTERVALS`).
    tolerance : float
        Largest violation of a plan's path samples accepted, relative to each limit.

    Raises
    ------
    ValueError
        Naming the argument: ``preview_m`` negative, not finite or longer than the course,
        ``horizon`` not an integer or < 1, ``tolerance`` outside (0, 0.1].
    """
    if isinstance(preview_m, bool) or not isinstance(preview_m, int | float | np.number):
        raise ValueError(f"preview_m must be a length in m >= 0; got {preview_m!r}")
    counts = preview_intervals(problem, float(preview_m), speed_m_s, wheelbase_m)
    if horizon is None:
        horizon = counts[1] + TAIL_INTERVALS
    if isinstance(horizon, bool) or not isinstance(horizon, int | np.integer):
        raise ValueError(f"horizon must be an integer number of command intervals; got {horizon!r}")
    if horizon < 1:
        raise ValueError(f"horizon must be >= 1 command interval; got {horizon}")
    if not 0.0 < tolerance <= 0.1:
        raise ValueError(
            f"tolerance must be in (0, 0.1] (relative to the limits); got {tolerance!r}"
        )
    start_s = time.perf_counter()
    lq, m = design.lq, problem.hold_periods
    weights = np.linalg.eigh(design.riccati)
    root = np.sqrt(np.clip(weights[0], 0.0, None))[:, None] * weights[1].T  # rootᵀ root = P
    base = dataclasses.replace(lq, q=design.state_weight, end=root)
    limits = path_limits(problem)
    u_low = (problem.u_bounds[0] - problem.plant.u0) / lq.u_scale
    u_high = (problem.u_bounds[1] - problem.plant.u0) / lq.u_scale
    n, horizon = lq.d.shape[0], int(horizon)
    command, states = np.empty(n), np.zeros((n + 1, lq.a.shape[0]))
    stats = np.zeros((n, 4))
    converged = np.zeros(n, bool)
    rows = np.zeros((0, 3), dtype=int)
    p_z, p_u, _ = lq.path
    with threadpool_limits(1):  # H × H factors: one BLAS thread (module notes)
        for j in range(n):
            tic, z = time.perf_counter(), states[j]
            d, q, r = _window(design.road_terms, counts, j, horizon)
            (offset,) = _window(tuple((p,) for p in design.road_path), counts, j, horizon)
            d[0] += lq.a @ z  # x_0 = z_j folded into the first interval (condense starts at zero)
            r[0] += lq.s @ z
            offset[0] += p_z @ z
            window = dataclasses.replace(base, d=d, q_lin=q, r_lin=r, path=(p_z, p_u, offset))
            condensed = condense(window, m)
            terminal, target = condensed.end_matrix, condensed.end_target  # root x_H = E u − e
            p_matrix = 2.0 * (condensed.hessian + terminal.T @ terminal) / lq.count
            q_vector = 2.0 * (condensed.gradient - terminal.T @ target) / lq.count
            plan, violation, rows, iterations, ok = _plan(
                condensed, p_matrix, q_vector, limits, (u_low, u_high), rows, tolerance
            )
            command[j] = plan[0]
            states[j + 1] = lq.a @ z + lq.b * command[j] + lq.d[j]  # the true road, both axles
            stats[j] = time.perf_counter() - tic, iterations, len(rows), violation
            converged[j] = ok
            rows = rows[rows[:, 0] > 0] - np.array([1, 0, 0])  # the next plan starts one later
    a_total, end, _ = evaluate(lq, command, problem)
    return RecedingRun(
        preview_m=float(preview_m), intervals=counts, command=command * lq.u_scale,
        a_total_m_s2=a_total, end_residual=end, states=states, horizon=horizon,
        qp_s=stats[:, 0], iterations=stats[:, 1].astype(int), rows=stats[:, 2].astype(int),
        converged=converged, plan_violation=stats[:, 3], run_s=time.perf_counter() - start_s,
    )  # fmt: skip
