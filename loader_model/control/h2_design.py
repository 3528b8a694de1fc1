r"""H2 gain optimisation with IPOPT through CasADi, with a stability margin for every plant.

Minimises J(K) of :mod:`loader_model.control.h2_cost` over the free entries of K subject to
all closed-loop poles having real part < −σ for every plant, and r.m.s. bounds on the control
inputs and on constrained outputs, which are H2 quantities too:
:math:`u_{rms,j}^2 = (K C_y P C_y^T K^T)_{jj}`, :math:`e_{rms,j}^2 = (C_e^{cl} P C_e^{cl\,T})_{jj}`.

Formulation (why it cannot end at an unstable point). Unknowns per plant: Cholesky factors
L_P and L of the cost Gramian P = L_P L_Pᵀ and of a stability certificate Π = L Lᵀ, with

.. math::
    A^{cl} P + P A^{cl\,T} + B_w B_w^T = 0, \qquad
    A_\sigma \Pi + \Pi A_\sigma^T + B_w B_w^T + \varepsilon I = 0,
    \quad A_\sigma = A^{cl} + \sigma I .

Let vᴴ A_σ = λ vᴴ (a left eigenvector). Multiplying the second equation by vᴴ and v gives
2 Re λ · vᴴ Π v = −vᴴ (B_w B_wᵀ + ε I) v < 0 (ε > 0, so no controllability of (A_σ, B_w) is
needed). Since Π = L Lᵀ ⪰ 0 this forces vᴴ Π v > 0 and Re λ < 0: every feasible point has all
poles of A_cl left of −σ, and then the first equation has a unique solution, the true Gramian,
so the cost is the true H2 cost. P = L_P L_Pᵀ keeps the objective ≥ 0 even at infeasible
iterates: with P free, IPOPT diverged to unstable points where the indefinite Lyapunov
solution makes the cost arbitrarily negative (DESIGN.md, Performance). A log-det barrier was
not used: it needs a strictly feasible start and returns no multiplier for an active margin.

The certificate alone makes the feasible set open: towards the margin boundary Π grows without
bound, so an active margin would have no minimiser. The inequality tr(Π)/n ≤ 100 (in states
scaled so that Π has unit diagonal at the start) closes it; with the margin active the result's
margin is then slightly above σ. A warm start closer than δ = 0.5 σ + 0.01 to the margin (or
unstable) is first moved to margin σ + δ by a Nelder-Mead search on the spectral abscissa
max_i max Re λ(A_cl,i) (phase 1, numpy), so IPOPT starts from an exactly feasible point.
States are scaled by the diagonal of the warm-start certificate (a similarity), the equalities
by the size of their constant terms, and IPOPT is retried with other barrier settings if it
fails (:data:`IPOPT_ATTEMPTS`); the formulation is non-convex, so the result is a local optimum.
After the solve, stability and margin are checked with numpy eigenvalues.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
from scipy.optimize import minimize

from loader_model.control._checks import finite_matrix, gain_mask
from loader_model.control._h2_nlp import PlantBlock, gain_expression
from loader_model.control.design_plant import DesignPlant
from loader_model.control.h2_cost import check_plants, closed_loop, h2_costs

__all__ = ["H2DesignError", "H2DesignResult", "design_h2_gain"]

#: IPOPT settings tried in turn until one succeeds. On the two-load test plant (8 warm starts
#: and margins) the default settings converged in 1 of 8 cases, mu_init = 1e-3 in 7 of 8; with
#: this retry list the slow sweep (5 starts x 3 margins) succeeds in 14 of 15 and reports the 15th.
IPOPT_ATTEMPTS: tuple[dict[str, Any], ...] = ({"mu_init": 1e-3}, {"mu_strategy": "adaptive"})

#: Bound on tr(Π) / n in the scaled states (1 at the warm start), closing the feasible set.
CERTIFICATE_BOUND = 100.0


@dataclass(frozen=True)
class H2DesignResult:
    """Gain and diagnostics of :func:`design_h2_gain` (per-plant tuples in the plants' order)."""

    gain: np.ndarray
    input_names: tuple[str, ...]
    measured_names: tuple[str, ...]
    cost: float
    plant_costs: tuple[float, ...]
    initial_cost: float
    poles: tuple[np.ndarray, ...]
    margin: float
    required_margin: float
    input_rms: tuple[np.ndarray, ...]
    output_rms: tuple[np.ndarray, ...]
    solver_status: str
    success: bool
    iterations: int
    solve_time_s: float


class H2DesignError(RuntimeError):
    """IPOPT did not succeed, or the result misses the stability margin; ``result`` has details."""

    def __init__(self, message: str, result: H2DesignResult) -> None:
        super().__init__(message)
        self.result = result


def design_h2_gain(
    plants: Sequence[DesignPlant] | DesignPlant,
    gain0: Any,
    *,
    mask: Any = None,
    effort_weight: Any = None,
    input_rms_limits: Sequence[float] | None = None,
    margin: float = 0.0,
    epsilon: float = 1e-2,
    ipopt_options: dict[str, Any] | None = None,
    raise_on_failure: bool = True,
) -> H2DesignResult:
    """Static gain K (u = −K y) minimising Σ w_i H2² + effort with all poles left of −σ.

    Parameters
    ----------
    plants
        One or more :class:`DesignPlant` sharing the gain shape (m, p).
    gain0
        Warm start (m x p), e.g. from :func:`loader_model.control.output_feedback_lqr`; fixed
        entries (``mask`` False) keep its values. It may be destabilising.
    mask
        Boolean m x p array of free entries (default all).
    effort_weight
        R (m x m, ⪰ 0) of the effort penalty tr(R K C_y P C_yᵀ Kᵀ) (default 0).
    input_rms_limits
        Upper bounds of the r.m.s. of each control input, per plant (default none).
    margin
        σ ≥ 0: every pole of every closed loop must have real part < −σ.
    epsilon
        Relative size ε of the εI added in the certificate equation (module docstring).
    ipopt_options
        Extra IPOPT options (e.g. ``{"tol": 1e-10}``).
    raise_on_failure
        Raise :class:`H2DesignError` when IPOPT fails or the numpy check misses the margin;
        otherwise return the result with ``success`` False.

    Returns
    -------
    H2DesignResult
        Gain, total and per-plant cost (checked with scipy), poles per plant, achieved margin
        min_i(−max Re λ_i), r.m.s. values, IPOPT status, iterations and wall time.

    Raises
    ------
    H2DesignError
        With ``raise_on_failure``, when IPOPT fails (after the retries), phase 1 cannot reach
        the margin, or the eigenvalue check or an r.m.s. bound fails.
    ValueError
        For malformed arguments (shapes, non-finite values, mask, margin, limits).
    """
    plants, r = check_plants(plants, effort_weight)
    shape = plants[0].gain_shape
    gain0 = finite_matrix("gain0", gain0, shape)
    mask = gain_mask(mask, shape)
    if not (np.isfinite(margin) and margin >= 0.0):
        raise ValueError(f"margin must be finite and >= 0; got {margin}")
    if not (np.isfinite(epsilon) and epsilon > 0.0):
        raise ValueError(f"epsilon must be finite and > 0; got {epsilon}")
    limits = None
    if input_rms_limits is not None:
        limits = np.asarray(input_rms_limits, dtype=float)
        if limits.shape != (shape[0],) or not np.all(np.isfinite(limits) & (limits > 0)):
            raise ValueError(
                f"input_rms_limits must be {shape[0]} positive finite numbers; got {input_rms_limits}"
            )
    started = time.perf_counter()
    initial_cost = float(sum(h2_costs(plants, gain0, r)["costs"]))
    gain, stats = _reach_margin(plants, gain0, mask, margin + 0.5 * margin + 0.01)
    if stats is None:
        if limits is not None or any(p.e_rms_limits for p in plants):
            # From starts that violate an r.m.s. bound IPOPT often failed: start the bounded
            # problem from the unbounded optimum instead (when that one is found).
            unbounded, check = _minimise(
                plants, gain, mask, r, None, margin, epsilon, ipopt_options, False
            )
            gain = unbounded if check["success"] else gain
        gain, stats = _minimise(plants, gain, mask, r, limits, margin, epsilon, ipopt_options, True)
    elapsed = time.perf_counter() - started
    return _result(plants, gain, r, limits, initial_cost, margin, stats, elapsed, raise_on_failure)


def _abscissa(plants: Sequence[DesignPlant], gain: np.ndarray) -> float:
    return max(float(np.max(np.linalg.eigvals(closed_loop(p, gain)[0]).real)) for p in plants)


class _Reached(Exception):
    pass


def _reach_margin(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    mask: np.ndarray,
    target: float,
    max_evaluations: int = 4000,
) -> tuple[np.ndarray, dict[str, Any] | None]:
    """Phase 1: the warm start, or a gain from a Nelder-Mead search with max Re λ ≤ −target.

    Returns (gain, None) on success, (best gain, stats naming the failure) otherwise.
    """
    if _abscissa(plants, gain0) <= -target:
        return gain0, None
    x0 = gain0[mask]

    def objective(x: np.ndarray) -> float:
        gain = gain0.copy()
        gain[mask] = x
        value = _abscissa(plants, gain)
        if value <= -target:
            raise _Reached(gain)
        return value

    step = np.maximum(0.5 * np.abs(x0), max(0.5 * float(np.mean(np.abs(x0))), 0.1))
    simplex = np.vstack([x0, x0 + np.diag(step)])
    try:
        for _ in range(3):  # restarts from the best point with a fresh simplex
            best = minimize(
                objective,
                simplex[0],
                method="Nelder-Mead",
                options={
                    "initial_simplex": simplex,
                    "maxfev": max_evaluations // 3,
                    "xatol": 1e-10,
                    "fatol": 1e-12,
                },
            )
            simplex = np.vstack([best.x, best.x + np.diag(step)])
    except _Reached as reached:
        return reached.args[0], None
    gain = gain0.copy()
    gain[mask] = best.x
    status = f"margin not reached in phase 1: max Re λ = {best.fun:.6g}, needed ≤ {-target:.6g}"
    return gain, {"return_status": status, "iter_count": 0}


def _minimise(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    mask: np.ndarray,
    r: np.ndarray,
    limits: np.ndarray | None,
    margin: float,
    epsilon: float,
    ipopt_options: dict[str, Any] | None,
    bounded: bool,
) -> tuple[np.ndarray, dict[str, Any]]:
    """Phase 2: IPOPT on the formulation of the module docstring from a start meeting the margin."""
    k_free, k = gain_expression(gain0, mask)
    blocks = [PlantBlock(plant, gain0, margin, epsilon) for plant in plants]
    scale = float(sum(h2_costs(plants, gain0, r)["costs"]))
    equalities, inequalities, objective = [], [], 0
    for block in blocks:
        equality, cost, u_var, e_var, size = block.terms(k, r)
        equalities.append(equality)
        inequalities.append(size / CERTIFICATE_BOUND)
        objective += cost / scale
        if limits is not None:
            inequalities.append(u_var / limits**2)
        if bounded and block.plant.e_rms_limits:
            inequalities.append(e_var / np.asarray(block.plant.e_rms_limits) ** 2)
    x = ca.vertcat(k_free, *[v for b in blocks for v in (b.l_cost, b.l_cert)])
    x0 = np.concatenate([gain0[mask], *[v for b in blocks for v in (b.guess_cost, b.guess_cert)]])
    g = ca.vertcat(*equalities, *inequalities)
    n_eq, n_in = sum(e.shape[0] for e in equalities), sum(e.shape[0] for e in inequalities)
    bounds = {
        "lbg": np.concatenate([np.zeros(n_eq), np.full(n_in, -np.inf)]),
        "ubg": np.concatenate([np.zeros(n_eq), np.ones(n_in)]),
    }
    for settings in IPOPT_ATTEMPTS:  # the problem is non-convex: retry on failure
        options = {
            "print_time": False,
            "ipopt": {"print_level": 0, "sb": "yes", "tol": 1e-9, "max_iter": 300},
        }
        options["ipopt"].update({**settings, **(ipopt_options or {})})
        solver = ca.nlpsol("h2_design", "ipopt", {"x": x, "f": objective, "g": g}, options)
        solution = solver(x0=x0, **bounds)
        if solver.stats()["success"]:
            break
    gain = gain0.copy()
    gain[mask] = np.asarray(solution["x"]).ravel()[: int(mask.sum())]
    return gain, {**solver.stats(), "attempts": IPOPT_ATTEMPTS.index(settings) + 1}


def _result(
    plants: Sequence[DesignPlant],
    gain: np.ndarray,
    r: np.ndarray,
    limits: np.ndarray | None,
    initial_cost: float,
    margin: float,
    stats: dict[str, Any],
    elapsed: float,
    raise_on_failure: bool,
) -> H2DesignResult:
    check = h2_costs(plants, gain, r)
    achieved = float(min(-np.max(p.real) for p in check["poles"]))
    status = str(stats["return_status"])
    solved = status in ("Solve_Succeeded", "Solved_To_Acceptable_Level")
    tolerance = 1e-6 * max(1.0, margin)
    within = limits is None or all(np.all(u <= limits * (1 + 1e-6)) for u in check["u_rms"])
    within &= all(
        np.all(e <= np.asarray(p.e_rms_limits) * (1 + 1e-6))
        for p, e in zip(plants, check["e_rms"], strict=True)
    )
    result = H2DesignResult(
        gain=gain,
        input_names=plants[0].input_names,
        measured_names=plants[0].measured_names,
        cost=float(sum(check["costs"])),
        plant_costs=tuple(check["costs"]),
        initial_cost=initial_cost,
        poles=tuple(check["poles"]),
        margin=achieved,
        required_margin=margin,
        input_rms=tuple(check["u_rms"]),
        output_rms=tuple(check["e_rms"]),
        solver_status=status,
        success=solved and achieved > margin - tolerance and within,
        iterations=int(stats["iter_count"]),
        solve_time_s=elapsed,
    )
    if raise_on_failure and not result.success:
        raise H2DesignError(
            f"H2 gain design failed: IPOPT status {status}, stability margin {achieved:.6g} "
            f"(required > {margin:.6g}), r.m.s. limits {'met' if within else 'violated'}",
            result,
        )
    return result
