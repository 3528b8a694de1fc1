r"""The bound of the linearised plant with the machine's limits: a condensed convex QP.

The LQ problem of :mod:`~loader_model.bound.linear` (lifted to the command grid, exact in the
linear model) with the limits of :mod:`~loader_model.bound.problem`: the command bounds on u_j
and, at every controller period, the displacement rate |V̇_p| ≤ 0.99 V̇_p,max, the chamber
pressures between cavitation (absolute 0 Pa) and relief and the piston inside its stroke. It is
condensed onto the N command values (:mod:`~loader_model.bound.condensed`: a dense N × N
Hessian, every path sample a Toeplitz row) and solved by constraint generation: a dense
interior point (:mod:`~loader_model.bound.dense_qp`) solves the QP with the box, the end
condition and a working set of path rows; all K_s samples of every path signal are then
evaluated by one convolution, and for each interval and signal whose worst sample violates its
bound by more than ``tolerance`` (relative to the limit) that sample's row joins the set. Rows
are never removed, so the cost rises monotonically to the constrained optimum; it stops when no
sample of the K_s periods violates. Its a_total is the pump's bound in the linear regime.

Measured on the development machine (2 cores shared with other jobs) on the paper course,
9 km/h, empty (N = 1530 command values of 10 ms, 15.3 s; the baseline's a_total 4.286 m/s², the
unconstrained LQ bound's 2.180 with its command at 12.4 × the limit): a_total 3.6331 m/s², the
command at 1.00 × the limit (0.99 V_p,max), the largest violation over all 61 200 path samples
4e-8 of the limits, the end condition to 1e-14; 10 rounds, 200 interior-point iterations, 2244
rows in the final set, 54 s (133 s in an earlier run under a load of about 4). Without dropping
rows (all 4398 kept) the same a_total to 1e-7 took 265 s under that load. The rows added after
the first round are the pressure in A (cavitation) and the rate limit. Started from a known
working set (``working_set``, e.g. a neighbouring pump size) it needs fewer rounds.

What failed before (the 3 s, 5 mm test course, stage-wise form with the states as variables,
all 12 000 per-period rows): CasADi's ``conic`` with OSQP stopped at 20 000 iterations after
650 s, not converged; HiGHS' QP had not finished after 300 s; IPOPT (tol 1e-8) had not returned
after 400 s; a primal-dual active set on the sparse KKT cycled (the M = 10 path rows of one
interval are nearly dependent). On the condensed problem of the paper course, CasADi's DAQP
failed (status −4) and proxqp needed 90 s for the box alone; qpOASES did not return in 200 s.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from loader_model.bound.condensed import CondensedProblem, condense
from loader_model.bound.dense_qp import solve_dense_qp
from loader_model.bound.linear import LinearQuadratic, evaluate, linear_quadratic
from loader_model.bound.problem import PATH_SIGNALS, BoundProblem

__all__ = ["ConstrainedBound", "generate_constraints", "path_limits", "solve_constrained_bound"]

#: Largest violation accepted, relative to each signal's limit (deviation from static).
PATH_TOLERANCE = 1e-6
#: Rows farther inside their limits than this (relative) leave the working set after a round
#: (only in the first :data:`DROP_ROUNDS` rounds, so that the iteration terminates).
DROP_MARGIN = 0.25
DROP_ROUNDS = 4


@dataclass(frozen=True)
class ConstrainedBound:
    """The constrained linear bound (module notes).

    Attributes
    ----------
    command : numpy.ndarray
        (N,) command deviation from u0, m³/rev.
    a_total_m_s2 : float
        a_total (Eq. 50) of the linear plant under it.
    seat : numpy.ndarray
        (K_s, axes) seat samples of the linear plant.
    path : numpy.ndarray
        (K_s, len(PATH_SIGNALS) + 1) bounded signals (absolute values) and V̇_p.
    end_residual : numpy.ndarray
        C_T z_N (boom position, pump displacement and rate at the end).
    iterations : int
        Interior-point iterations over all rounds.
    rounds : int
        Constraint-generation rounds.
    working_set : numpy.ndarray
        (rows, 3) the path rows used: interval, sub-period, signal.
    max_violation : float
        Largest violation over all K_s samples, relative to the limits.
    solve_s : float
        Wall time of building and solving, s.
    converged : bool
        Every round's QP converged and no sample violates by more than the tolerance.
    """

    command: np.ndarray
    a_total_m_s2: float
    seat: np.ndarray
    path: np.ndarray
    end_residual: np.ndarray
    iterations: int
    rounds: int
    working_set: np.ndarray
    max_violation: float
    solve_s: float
    converged: bool


def path_limits(problem: BoundProblem) -> tuple[np.ndarray, ...]:
    """Static values, lower and upper bounds (deviations) and scales of the path signals."""
    plant = problem.plant
    static = np.array([*(plant.output(name) for name in PATH_SIGNALS), 0.0])
    lower = np.concatenate([problem.path_lower, [-problem.rate_limit]]) - static
    upper = np.concatenate([problem.path_upper, [problem.rate_limit]]) - static
    return static, lower, upper, np.maximum(np.abs(upper), np.abs(lower))


def _violation(
    condensed: CondensedProblem, u: np.ndarray, limits: tuple[np.ndarray, ...]
) -> np.ndarray:
    _, lower, upper, scale = limits
    values = condensed.path_values(u)
    return np.maximum(values - upper, lower - values) / scale


def generate_constraints(
    condensed: CondensedProblem,
    p_matrix: np.ndarray,
    q_vector: np.ndarray,
    limits: tuple[np.ndarray, ...],
    u_low: float,
    u_high: float,
    rows: np.ndarray,
    *,
    tolerance: float = PATH_TOLERANCE,
    max_rounds: int = 40,
    drop_rounds: int = DROP_ROUNDS,
    bar: object | None = None,
) -> tuple:
    """Constraint generation (module notes) on a condensed QP ½ uᵀ P u + qᵀ u with the end
    condition, the box [u_low, u_high] and the path rows of ``condensed`` (anything with
    ``path_values``, ``path_rows``, ``path_offset``, ``end_matrix``, ``end_target``).

    Returns
    -------
    tuple
        (QPResult, working set, interior-point iterations, rounds, largest violation, converged).
    """
    _, lower, upper, scale = limits
    iterations, rounds, converged, violation = 0, 0, False, np.inf
    for _ in range(max_rounds):
        rounds += 1
        i, s, k = rows[:, 0], rows[:, 1], rows[:, 2]
        row_scale = scale[k]
        offset = condensed.path_offset[i, s, k]
        result = solve_dense_qp(
            p_matrix, q_vector, condensed.end_matrix, condensed.end_target,
            condensed.path_rows(i, s, k) / row_scale[:, None],
            (lower[k] - offset) / row_scale, (upper[k] - offset) / row_scale,
            u_low, u_high,
        )  # fmt: skip
        iterations += result.iterations
        excess = _violation(condensed, result.u, limits)
        worst, sub = excess.max(axis=1), excess.argmax(axis=1)
        violation = float(worst.max())
        if bar is not None:
            bar.set_postfix_str(f"rows {len(rows)}, violation {violation:.1e}")
            bar.update()
        new_i, new_k = np.nonzero(worst > tolerance)
        if new_i.size == 0:
            converged = result.converged
            break
        if rounds <= drop_rounds and len(rows):
            rows = rows[excess[rows[:, 0], rows[:, 1], rows[:, 2]] > -DROP_MARGIN]
        rows = np.vstack([rows, np.column_stack([new_i, sub[new_i, new_k], new_k])])
    return result, rows, iterations, rounds, violation, converged


def solve_constrained_bound(
    problem: BoundProblem,
    lq: LinearQuadratic | None = None,
    *,
    working_set: np.ndarray | None = None,
    tolerance: float = PATH_TOLERANCE,
    max_rounds: int = 40,
    drop_rounds: int = DROP_ROUNDS,
    progress: bool = False,
) -> ConstrainedBound:
    """Solve the constrained linear bound of ``problem`` (module notes).

    Parameters
    ----------
    problem : BoundProblem
        Grid, road and limits.
    lq : LinearQuadratic, optional
        The lifted problem (default: built from ``problem``).
    working_set : numpy.ndarray, optional
        (rows, 3) path rows to start with (interval, sub-period, signal).
    tolerance : float
        Largest violation accepted relative to each limit, in (0, 0.1].
    max_rounds : int
        Most constraint-generation rounds.
    drop_rounds : int
        Rounds after which rows far inside their limits (:data:`DROP_MARGIN`) are dropped.
    progress : bool
        Show a progress bar over the rounds.
    """
    if not 0.0 < tolerance <= 0.1:
        raise ValueError(f"tolerance must be in (0, 0.1]; got {tolerance!r}")
    if max_rounds < 1:
        raise ValueError(f"max_rounds must be >= 1; got {max_rounds!r}")
    from tqdm import tqdm

    start = time.perf_counter()
    lq = lq or linear_quadratic(problem)
    condensed = condense(lq, problem.hold_periods)
    limits = path_limits(problem)
    static = limits[0]
    n = condensed.intervals
    shape = condensed.path_offset.shape
    rows = np.zeros((0, 3), dtype=int) if working_set is None else np.asarray(working_set, int)
    rows = rows[(rows[:, 0] < shape[0]) & (rows[:, 1] < shape[1])]
    p_matrix = 2.0 * condensed.hessian / lq.count
    q_vector = 2.0 * condensed.gradient / lq.count
    u_low = (problem.u_bounds[0] - problem.plant.u0) / lq.u_scale
    u_high = (problem.u_bounds[1] - problem.plant.u0) / lq.u_scale
    bar = tqdm(total=max_rounds, desc="constrained bound", unit="round", disable=not progress)
    with bar:
        result, rows, iterations, rounds, violation, converged = generate_constraints(
            condensed, p_matrix, q_vector, limits, u_low, u_high, rows,
            tolerance=tolerance, max_rounds=max_rounds, drop_rounds=drop_rounds, bar=bar,
        )  # fmt: skip
    u = result.u
    a_total, end_residual, seat = evaluate(lq, u, problem)
    path = condensed.path_values(u).reshape(n * problem.hold_periods, -1) + static
    return ConstrainedBound(
        command=u * lq.u_scale,
        a_total_m_s2=a_total,
        seat=seat,
        path=path,
        end_residual=end_residual,
        iterations=iterations,
        rounds=rounds,
        working_set=rows,
        max_violation=violation,
        solve_s=time.perf_counter() - start,
        converged=converged,
    )
