r"""The bound of the linearised plant with the machine's limits: a convex QP solved by IPOPT.

The LQ problem of :mod:`~loader_model.bound.linear` (lifted to the command grid, exact in the
linear model) with the limits of :mod:`~loader_model.bound.problem` added: the command bounds
on u_j and, at every controller period, the displacement rate |V̇_p| ≤ 0.99 V̇_p,max, the chamber
pressures between cavitation and relief and the piston inside its stroke, each affine in the
node state and command. The problem is a convex quadratic programme (constant Hessian, linear
constraints), so IPOPT's interior point solves it to its global optimum in a few tens of
iterations; its a_total is the pump's bound in the linear regime (the unconstrained LQ bound
asks for many times the pump's displacement on the 40 mm boards).

Status (work in progress): IPOPT converges slowly here (it regularises the KKT system at every
iteration; 40 iterations on a 3 s course did not reach its tolerance), so no command uses it yet.
Measured on the 3 s, 5 mm test course (300 command values, 12 300 variables, 24 003 rows of
which 12 000 path rows; the unconstrained LQ command peaks at 1.47 × V_p,max there):

- CasADi's ``conic`` with OSQP (eps 1e-9, polish) stopped at 20 000 iterations after 650 s,
  not converged (largest scaled row violation 5e-5; a_total 0.34643 against the
  unconstrained 0.34631 m/s², command peak 0.95 × V_p,max);
- HiGHS' QP solver had not finished after 300 s; this module's IPOPT (tol 1e-8, at most
  300 iterations) had not returned after 400 s;
- a primal-dual active-set iteration on the sparse KKT system of
  :func:`~loader_model.bound.linear.solve_kkt` cycles between two active sets: the
  M = 10 path rows of one interval are nearly linearly dependent (one command value moves all
  of them), so the active constraints' Jacobian is rank deficient.

What should work: one rate and pressure row per interval (not per period) where the rows of an
interval are dependent, or a structure-exploiting interior point (HPIPM, shipped with CasADi,
takes the stage-wise form z_{j+1} = A z_j + B u_j + d_j directly).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import casadi as ca
import numpy as np

from loader_model.bound.linear import LinearQuadratic, evaluate, linear_quadratic
from loader_model.bound.problem import BoundProblem

__all__ = ["ConstrainedBound", "solve_constrained_bound"]

#: IPOPT settings of the convex QP.
QP_OPTIONS = {
    "tol": 1e-10,
    "print_level": 0,
    "hessian_constant": "yes",
    "jac_c_constant": "yes",
    "jac_d_constant": "yes",
    "mu_strategy": "adaptive",
    "max_iter": 500,
}


#: Weight of û² per interval in the scaled cost a_total² (keeps the reduced Hessian definite
#: where the last commands act after the horizon; at most N × 1e-9 of a_total²).
_COMMAND_WEIGHT = 1e-9


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
        IPOPT iterations.
    solve_s : float
        Wall time of building and solving, s.
    status : str
        IPOPT's return status.
    """

    command: np.ndarray
    a_total_m_s2: float
    seat: np.ndarray
    path: np.ndarray
    end_residual: np.ndarray
    iterations: int
    solve_s: float
    status: str


def _static_path(problem: BoundProblem) -> np.ndarray:
    from loader_model.bound.problem import PATH_SIGNALS

    plant = problem.plant
    return np.array([*(plant.output(name) for name in PATH_SIGNALS), 0.0])


def solve_constrained_bound(
    problem: BoundProblem, lq: LinearQuadratic | None = None, ipopt: dict | None = None
) -> ConstrainedBound:
    """Solve the constrained linear bound of ``problem`` (module notes)."""
    start = time.perf_counter()
    lq = lq or linear_quadratic(problem)
    n, nz, m = problem.intervals, lq.a.shape[0], problem.hold_periods
    p_z, p_u, p_offset = lq.path
    static = _static_path(problem)
    lower = np.concatenate([problem.path_lower, [-problem.rate_limit]]) - static
    upper = np.concatenate([problem.path_upper, [problem.rate_limit]]) - static
    scale = np.maximum(np.abs(upper), np.abs(lower))
    scale = np.tile(np.where(scale > 0, scale, 1.0), m)
    zs, us = ca.MX.sym("Z", nz, n), ca.MX.sym("U", 1, n)  # z_1 .. z_N; z_0 = 0
    previous = ca.horzcat(ca.MX.zeros(nz, 1), zs[:, : n - 1])
    cost = (
        ca.sum1(ca.sum2(previous * ca.mtimes(lq.q, previous)))
        + 2.0 * ca.sum1(ca.sum2(previous * ca.mtimes(lq.s[:, None], us)))
        + (lq.r + _COMMAND_WEIGHT * lq.count) * ca.sumsqr(us)
        + 2.0 * ca.sum1(ca.sum2(previous * lq.q_lin.T))
        + 2.0 * ca.mtimes(us, lq.r_lin)
    )
    dynamics = ca.mtimes(lq.a, previous) + ca.mtimes(lq.b[:, None], us) + lq.d.T - zs
    path = (ca.mtimes(p_z, previous) + ca.mtimes(p_u[:, None], us) + p_offset.T) / scale[:, None]
    end = ca.mtimes(lq.end, zs[:, n - 1])
    variables = ca.vertcat(ca.vec(zs), ca.vec(us))
    constraints = ca.vertcat(ca.vec(dynamics), ca.vec(path), end)
    options = {**QP_OPTIONS, **(ipopt or {})}
    solver = ca.nlpsol(
        "constrained_bound",
        "ipopt",
        {"x": variables, "f": cost / lq.count, "g": constraints},
        {"print_time": False, "ipopt": options},
    )
    path_low = np.tile(lower, m) / scale
    path_high = np.tile(upper, m) / scale
    zeros_dyn = np.zeros(nz * n)
    zeros_end = np.zeros(lq.end.shape[0])
    lbx = np.concatenate([np.full(nz * n, -np.inf), np.full(n, problem.u_bounds[0])])
    ubx = np.concatenate([np.full(nz * n, np.inf), np.full(n, problem.u_bounds[1])])
    u_offset = problem.plant.u0
    lbx[nz * n :] = (problem.u_bounds[0] - u_offset) / lq.u_scale
    ubx[nz * n :] = (problem.u_bounds[1] - u_offset) / lq.u_scale
    solution = solver(
        x0=np.zeros(variables.size1()),
        lbx=lbx,
        ubx=ubx,
        lbg=np.concatenate([zeros_dyn, np.tile(path_low, n), zeros_end]),
        ubg=np.concatenate([zeros_dyn, np.tile(path_high, n), zeros_end]),
    )
    stats = solver.stats()
    optimum = np.asarray(solution["x"]).ravel()
    scaled = optimum[nz * n :]
    a_total, end_residual, seat = evaluate(lq, scaled, problem)
    path_values = np.asarray(ca.Function("path", [variables], [path * scale[:, None]])(optimum))
    path_series = path_values.T.reshape(n * m, -1) + static
    return ConstrainedBound(
        command=scaled * lq.u_scale,
        a_total_m_s2=a_total,
        seat=seat,
        path=path_series,
        end_residual=end_residual,
        iterations=int(stats.get("iter_count", 0)),
        solve_s=time.perf_counter() - start,
        status=str(stats.get("return_status", "")),
    )
