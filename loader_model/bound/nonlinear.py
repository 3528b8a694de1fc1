r"""The clairvoyant bound on the nonlinear plant: direct multiple shooting solved by IPOPT.

Decision variables (:mod:`~loader_model.bound.problem` for the grid and limits): the plant state
X_j and the weighting-filter state Ξ_j at each control node t = j M h, j = 0 … N, and the command
u_j. Each shooting interval is M periods of the simulator's own step
(:func:`~loader_model.simulation.stepper.period_function`: ROS2 at 1 ms on
:func:`~loader_model.plant.plant.plant_function`, the road interpolated linearly inside each
period, the command held), so the optimiser's trajectory is the one the simulator computes for
the same command table. The seat samples a_k (:func:`~loader_model.simulation.result.
seat_signal_names`, minus their static values) drive the sampled ISO 2631 filters of
:mod:`~loader_model.bound.weighting`, linear in (Ξ_j, a), and the cost is

.. math:: J = a_{total}^2 = \frac{1}{K_s} \sum_{k<K_s} \sum_a k_a^2 a_{w,a,k}^2
    \quad \text{(Eq. 49, 50)},

a sum of squares: IPOPT gets CasADi's exact constraint Jacobian and the Gauss-Newton Hessian
2 J_rᵀ J_r of the residuals r (the plant's second derivatives are left out: exact for the
linear part, the usual choice for least squares).

Status (work in progress): on a 1 s course (100 intervals) IPOPT lowers a_total from the
baseline's 1.76 to 0.70 m/s² in 30 iterations without converging, at about 3 s per iteration
(CasADi's SX virtual machine evaluates the mapped intervals' derivatives); compiled derivative
functions and a better-conditioned formulation are needed before the 12 s course is practical.

Path constraints (pressures, stroke, pump rate) hold at every controller period, the command
bounds on u_j; the scaled variables are deviations from the equilibrium over their range in the
warm start (the best controller's run), the pump's states over its limits.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from loader_model.bound.problem import PATH_SIGNALS, BoundProblem
from loader_model.bound.weighting import SeatWeighting, seat_weighting
from loader_model.plant.plant import EXOGENOUS_NAMES, OUTPUT_NAMES, STATE_NAMES, plant_function
from loader_model.simulation.controllers import hold_command_controller
from loader_model.simulation.result import SimulationResult, seat_signal_names
from loader_model.simulation.stepper import period_function

__all__ = ["NonlinearBound", "interval_function", "solve_nonlinear_bound"]

#: IPOPT settings: tolerances on the scaled problem.
IPOPT_OPTIONS = {"tol": 1e-9, "constr_viol_tol": 1e-9, "max_iter": 300, "print_level": 0}


@dataclass(frozen=True)
class NonlinearBound:
    """The optimum of the nonlinear bound problem.

    Attributes
    ----------
    command : numpy.ndarray
        (N,) optimal u_j in m³/rev.
    a_total_m_s2 : float
        The optimiser's a_total (Eq. 50) of the optimal trajectory.
    nodes : numpy.ndarray
        (N + 1, nx) plant state at the control nodes.
    path : numpy.ndarray
        (K_s, len(PATH_SIGNALS) + 1) the bounded signals and V̇_p at every period.
    iterations : int
        IPOPT iterations.
    solve_s : float
        Wall time of the IPOPT solve in s (the set-up excluded).
    setup_s : float
        Wall time of building the problem in s.
    status : str
        IPOPT's return status.
    warm_a_total_m_s2 : float
        a_total of the warm start's command on the optimiser's grid.
    stats : dict
        IPOPT statistics.
    """

    command: np.ndarray
    a_total_m_s2: float
    nodes: np.ndarray
    path: np.ndarray
    iterations: int
    solve_s: float
    setup_s: float
    status: str
    warm_a_total_m_s2: float
    stats: dict = field(default_factory=dict)

    @property
    def time_per_iteration_s(self) -> float:
        """IPOPT's wall time per iteration in s."""
        return self.solve_s / max(self.iterations, 1)


_INTERVALS: dict[int, ca.Function] = {}
#: Scale of an end condition on an output (the piston position, m).
_OUTPUT_END_SCALE = 1e-3


def interval_function(hold_periods: int) -> ca.Function:
    """One shooting interval: M simulator periods with the command held (module notes).

    ``interval(x, u, w, params) -> (x_next, seat, path)`` with w the (11, M + 1) exogenous
    samples at the periods' ends, seat the (axes, M) seat outputs and path the
    (len(PATH_SIGNALS) + 1, M) bounded outputs and V̇_p at the periods' starts.
    """
    if hold_periods not in _INTERVALS:
        period = period_function(hold_command_controller())
        nx, nw = len(STATE_NAMES), len(EXOGENOUS_NAMES)
        x, u = ca.SX.sym("x", nx), ca.SX.sym("u")
        w = ca.SX.sym("w", nw, hold_periods + 1)
        params = ca.SX.sym("params", period.size1_in(3))
        seat_rows = [OUTPUT_NAMES.index(s) for s in seat_signal_names().values()]
        path_rows = [OUTPUT_NAMES.index(s) for s in PATH_SIGNALS]
        rate = STATE_NAMES.index("Vd_p")
        zeros = ca.SX.zeros(len(OUTPUT_NAMES))
        carry, seats, paths = ca.vertcat(x, u), [], []
        for i in range(hold_periods):
            carry_next, y, _ = period(carry, w[:, i], w[:, i + 1], params, u, zeros, zeros)
            seats.append(y[seat_rows])
            paths.append(ca.vertcat(y[path_rows], carry[rate]))
            carry = carry_next
        _INTERVALS[hold_periods] = ca.Function(
            "bound_interval",
            [x, u, w, params],
            [carry[:nx], ca.horzcat(*seats), ca.horzcat(*paths)],
            ["x", "u", "w", "params"],
            ["x_next", "seat", "path"],
        )
    return _INTERVALS[hold_periods]


def _scales(values: np.ndarray, centre: np.ndarray, floor: float) -> np.ndarray:
    """Each column's largest deviation from ``centre`` (at least ``floor``)."""
    return np.maximum(np.max(np.abs(values - centre), axis=0), floor)


def solve_nonlinear_bound(
    problem: BoundProblem,
    warm: SimulationResult,
    *,
    weighting: SeatWeighting | None = None,
    ipopt: dict | None = None,
) -> NonlinearBound:
    """Solve the bound problem with IPOPT from the warm start ``warm`` (module notes).

    Parameters
    ----------
    problem : BoundProblem
        Grid, road, limits.
    warm : SimulationResult
        A run of the same plant over the same road with at least K_s rows (the best
        controller's): its states at the nodes and its command averaged over each interval.
    weighting : SeatWeighting, optional
        Default :func:`~loader_model.bound.weighting.seat_weighting` at the problem's period.
    ipopt : dict, optional
        IPOPT options overriding :data:`IPOPT_OPTIONS`.
    """
    start = time.perf_counter()
    weighting = weighting or seat_weighting(problem.period_s)
    m, n, count = problem.hold_periods, problem.intervals, problem.periods
    nx, nf, na = len(STATE_NAMES), weighting.order, len(weighting.axes)
    plant = problem.plant
    x0, u0, params = plant.x0, plant.u0, plant.params
    seat_static = np.array([plant.output(s) for s in weighting.signals])
    if warm.time_s.size < count:
        raise ValueError(f"warm start has {warm.time_s.size} rows; the problem needs {count}")
    states = np.column_stack([warm[s] for s in STATE_NAMES])[:count]
    states = np.vstack([states, warm.final_state if warm.time_s.size == count else states[-1:]])
    seat = np.column_stack([warm[s] - warm[s][0] for s in weighting.signals])[:count]
    filters = weighting.states(seat)
    x_warm, xi_warm = states[::m], filters[::m]
    u_warm = np.clip(warm["V_p_ref"][:count].reshape(n, m).mean(axis=1), *problem.u_bounds)
    sx = _scales(states, x0, 1e-9)
    for name, limit in (("V_p", problem.u_bounds[1]), ("Vd_p", problem.rate_limit)):
        index = STATE_NAMES.index(name)  # the pump may move where the warm start's did not
        sx[index] = max(sx[index], limit)
    sxi = _scales(filters, 0.0, 1e-9)
    su = problem.u_bounds[1]
    a_ref = max(weighting.a_total(seat), 1e-6)

    xs, xis, us = ca.MX.sym("X", nx, n + 1), ca.MX.sym("XI", nf, n + 1), ca.MX.sym("U", 1, n)
    variables = ca.vertcat(ca.vec(xs), ca.vec(xis), ca.vec(us))
    big_x = x0[:, None] + sx[:, None] * xs
    big_xi = sxi[:, None] * xis
    big_u = u0 + su * us
    exo = problem.exogenous
    w_blocks = np.hstack([exo[j * m : j * m + m + 1].T for j in range(n)])
    mapped = interval_function(m).map(n)
    x_next, seat_mx, path = mapped(big_x[:, :n], big_u, w_blocks, ca.repmat(params, 1, n))
    samples = ca.reshape(seat_mx - ca.repmat(seat_static, 1, m * n), na * m, n)
    l_xi, l_a, r_xi, r_a = weighting.interval_maps(m)
    residual = ca.vec(ca.mtimes(r_xi, big_xi[:, :n]) + ca.mtimes(r_a, samples))
    residual = residual / np.sqrt(count * a_ref**2)
    g_dyn = (x_next - big_x[:, 1:]) / sx[:, None]
    g_fil = ca.mtimes(l_xi, big_xi[:, :n]) + ca.mtimes(l_a, samples) - big_xi[:, 1:]
    g_fil = g_fil / sxi[:, None]
    path_scale = np.concatenate([np.maximum(np.abs(problem.path_upper), 1e-3), [su * 100]])
    g_path = path / path_scale[:, None]
    targets = problem.end_targets
    _, y_end = plant_function()(big_x[:, n], u0, exo[count], params)
    end = []
    for name, value in targets.items():
        if name in STATE_NAMES:
            index = STATE_NAMES.index(name)
            end.append((big_x[index, n] - value) / sx[index])
        else:
            end.append((y_end[OUTPUT_NAMES.index(name)] - value) / _OUTPUT_END_SCALE)
    constraints = ca.vertcat(ca.vec(g_dyn), ca.vec(g_fil), ca.vec(g_path), *end)
    lower_path = np.concatenate([problem.path_lower, [-problem.rate_limit]]) / path_scale
    upper_path = np.concatenate([problem.path_upper, [problem.rate_limit]]) / path_scale
    n_eq = nx * n + nf * n
    lbg = np.concatenate([np.zeros(n_eq), np.tile(lower_path, m * n), np.zeros(len(end))])
    ubg = np.concatenate([np.zeros(n_eq), np.tile(upper_path, m * n), np.zeros(len(end))])
    objective = ca.sumsqr(residual)
    jac = ca.jacobian(residual, variables)
    sigma = ca.MX.sym("sigma")
    hessian = ca.Function(
        "bound_gauss_newton",
        [variables, ca.MX(0, 1), sigma, ca.MX.sym("lam_g", constraints.size1())],
        [sigma * ca.triu(2.0 * ca.mtimes(jac.T, jac))],
        ["x", "p", "lam_f", "lam_g"],
        ["triu_hess_gamma_x_x"],
    )
    options = {**IPOPT_OPTIONS, **(ipopt or {})}
    exact = options.pop("exact_hessian", False)
    solver = ca.nlpsol(
        "bound",
        "ipopt",
        {"x": variables, "f": objective, "g": constraints},
        {
            **({} if exact else {"hess_lag": hessian}),
            "print_time": False,
            "ipopt": {f"{k}": v for k, v in options.items()},
        },
    )
    lbx = np.full(variables.size1(), -np.inf)
    ubx = np.full(variables.size1(), np.inf)
    fixed = np.r_[np.arange(nx), nx * (n + 1) + np.arange(nf)]
    lbx[fixed] = ubx[fixed] = 0.0
    offset = (nx + nf) * (n + 1)
    lbx[offset:] = (problem.u_bounds[0] - u0) / su
    ubx[offset:] = (problem.u_bounds[1] - u0) / su
    guess = np.concatenate(
        [
            ((x_warm - x0) / sx).ravel(),
            (xi_warm / sxi).ravel(),
            (u_warm - u0) / su,
        ]
    )
    guess[fixed] = 0.0
    setup_s = time.perf_counter() - start
    warm_cost = float(ca.Function("f", [variables], [objective])(guess))
    start = time.perf_counter()
    solution = solver(x0=guess, lbx=lbx, ubx=ubx, lbg=lbg, ubg=ubg)
    solve_s = time.perf_counter() - start
    stats = solver.stats()
    optimum = np.asarray(solution["x"]).ravel()
    nodes = x0 + sx * optimum[: nx * (n + 1)].reshape(n + 1, nx)
    command = u0 + su * optimum[offset:]
    path_values = np.asarray(ca.Function("path", [variables], [path])(optimum)).T
    return NonlinearBound(
        command=command,
        a_total_m_s2=a_ref * float(np.sqrt(max(float(solution["f"]), 0.0))),
        nodes=nodes,
        path=path_values,
        iterations=int(stats.get("iter_count", 0)),
        solve_s=solve_s,
        setup_s=setup_s,
        status=str(stats.get("return_status", "")),
        warm_a_total_m_s2=a_ref * float(np.sqrt(warm_cost)),
        stats={k: v for k, v in stats.items() if isinstance(v, int | float | str | bool)},
    )
