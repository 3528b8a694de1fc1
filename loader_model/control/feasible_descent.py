r"""Static-gain H2 optimisation: BFGS in the gains, every iterate certified.

An earlier design (``design_h2_gain``, retired) carried the Gramian and a stability certificate
as IPOPT unknowns: n(n+1) unknowns per plant with dense Jacobians. On the 38-state ride-comfort
plant (two loads: 2 964 unknowns, a dense KKT system) it had not finished after 13 minutes of
wall time (2 shared CPUs), and on the 13-state test plant its IPOPT runs ended in
Maximum_Iterations_Exceeded on one OpenBLAS kernel and converged on another. Here the only
unknowns are the free gains k:

.. math::

    \Phi(k) = \frac{J(K)}{J(K_0)} - \mu \sum_{i,j} \log\Big(1 - \frac{e_{rms,ij}^2}{\bar e_{ij}^2}\Big),

J the summed H2 cost of :mod:`~loader_model.control.h2_cost` (with effort), the log barrier keeping
the r.m.s. limits of every plant. Value and gradient by the adjoint Lyapunov equations (scipy):

.. math::

    A_c P + P A_c^T + B_w B_w^T = 0, \quad A_c^T L + L A_c + C_{z}^{cl\,T} C_z^{cl} + C_y^T K^T R K C_y = 0,
    \quad \frac{\partial J}{\partial K} = 2\,(R K C_y - B_u^T L - D_{zu}^T C_z^{cl})\, P\, C_y^T,

and the same with C_e rows for each variance. Quasi-Newton (BFGS) steps with backtracking: a
trial gain is accepted only if (1) every closed loop has all poles left of −σ (numpy
eigenvalues), (2) every r.m.s. value is inside its limit, (3) Φ decreases (Armijo). So every
iterate, and the result, meets the margin and the limits; the start must meet them too
(:func:`reach_margin` moves it there). A local optimum.
:mod:`~loader_model.control.comfort_ipopt` minimises the same Φ with IPOPT through CasADi.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from scipy.linalg import solve_continuous_lyapunov
from scipy.optimize import minimize

from loader_model.control.design_plant import DesignPlant
from loader_model.control.h2_cost import closed_loop

__all__ = [
    "BarrierObjective",
    "balanced_plant",
    "cost_and_gradient",
    "minimise_certified",
    "reach_margin",
]


def balanced_plant(plant: DesignPlant) -> DesignPlant:
    """The same plant in states scaled by the diagonal similarity that balances A.

    Poles, H2 norms and r.m.s. values are unchanged; the SI states of the loader span 1e-6 m³/rev
    to 1e7 Pa, which made scipy's Lyapunov solutions indefinite at stable gains.
    """
    from dataclasses import replace

    from scipy.linalg import matrix_balance

    _, (d, _) = matrix_balance(plant.A, permute=False, separate=True)
    return replace(
        plant,
        A=plant.A * d[None, :] / d[:, None],
        B_u=plant.B_u / d[:, None],
        B_w=plant.B_w / d[:, None],
        C_y=plant.C_y * d,
        C_z=plant.C_z * d,
        C_e=plant.C_e * d,
    )


def _adjoint(
    plant: DesignPlant,
    a_c: np.ndarray,
    p: np.ndarray,
    kc: np.ndarray,
    q: np.ndarray,
    c_cl: np.ndarray,
    d: np.ndarray,
    r: np.ndarray,
) -> np.ndarray:
    """∂ tr(Q P) / ∂K by the adjoint Lyapunov equation (module docstring)."""
    lam = solve_continuous_lyapunov(a_c.T, -q)
    return 2.0 * (r @ kc - plant.B_u.T @ lam - d.T @ c_cl) @ p @ plant.C_y.T


def cost_and_gradient(
    plants: Sequence[DesignPlant], gain: np.ndarray, effort: np.ndarray
) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """J, dJ/dK (m x p), var_e (stacked over plants) and d var_e / dK (each m x p), by adjoints.

    Meaningful only where every closed loop is Hurwitz.
    """
    total, grad, variances, var_grads = 0.0, np.zeros_like(gain), [], []
    for plant in plants:
        a_c, c_z, c_e = closed_loop(plant, gain)
        kc = gain @ plant.C_y
        p = solve_continuous_lyapunov(a_c, -plant.B_w @ plant.B_w.T)

        q = c_z.T @ c_z + kc.T @ effort @ kc
        total += plant.weight * float(np.trace(q @ p))
        grad += plant.weight * _adjoint(plant, a_c, p, kc, q, c_z, plant.D_zu, effort)
        zero_r = np.zeros_like(effort)
        for j in range(c_e.shape[0]):
            row, d_row = c_e[j : j + 1], plant.D_eu[j : j + 1]
            variances.append((row @ p @ row.T).item())
            var_grads.append(_adjoint(plant, a_c, p, kc, row.T @ row, row, d_row, zero_r))
    return total, grad, np.array(variances), np.array(var_grads)


def _margin(plants: Sequence[DesignPlant], gain: np.ndarray) -> float:
    return min(-float(np.max(np.linalg.eigvals(closed_loop(p, gain)[0]).real)) for p in plants)


class BarrierObjective:
    """Φ of the module docstring and its exact gradient in all gain entries; None outside the set.

    ``scale`` (J(K₀), set by the caller from a first evaluation; 1 until then) normalises J.
    Calling it returns (Φ, ∂Φ/∂K flattened row-major, J), or None when a closed loop has a pole
    at or right of −``margin`` or an r.m.s. value reaches its limit.
    """

    def __init__(
        self, plants: Sequence[DesignPlant], effort: np.ndarray, margin: float, mu: float
    ) -> None:
        self.plants, self.effort, self.margin, self.mu = tuple(plants), effort, margin, mu
        self.limits = np.concatenate([np.asarray(p.e_rms_limits, dtype=float) for p in plants])
        self.scale = 1.0

    def __call__(self, gain: np.ndarray) -> tuple[float, np.ndarray, float] | None:
        if _margin(self.plants, gain) <= self.margin:
            return None
        j, dj, var, dvar = cost_and_gradient(self.plants, gain, self.effort)
        limits = self.limits
        ratio = var / limits**2 if limits.size else np.zeros(0)
        if np.any(ratio >= 1.0):
            return None
        phi = float(j) / self.scale - self.mu * float(np.sum(np.log1p(-ratio)))
        grad = dj.ravel() / self.scale
        if limits.size:
            weights = self.mu / (limits**2 * (1.0 - ratio))
            grad = grad + np.tensordot(weights, dvar, axes=1).ravel()
        return phi, grad, float(j)


def minimise_certified(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    *,
    mask: np.ndarray,
    effort: np.ndarray,
    margin: float,
    mu: float = 1e-4,
    gtol: float = 1e-7,
    max_iterations: int = 200,
) -> dict[str, Any]:
    """Minimise Φ of the module docstring from ``gain0`` (which must meet margin and limits).

    Returns a dict: ``gain``, ``cost`` (J), ``iterations``, ``history`` (J per iterate),
    ``phi_history`` (Φ per iterate: what the line search decreases; J alone may rise where the
    barrier term falls more), ``converged`` (projected gradient norm ≤ ``gtol`` relative),
    ``status``, ``time_s``.
    """
    started = time.perf_counter()
    free = mask.ravel()
    objective = BarrierObjective(plants, effort, margin, mu)

    def evaluate(gain: np.ndarray) -> tuple[float, np.ndarray, float] | None:
        value = objective(gain)
        return None if value is None else (value[0], value[1][free], value[2])

    first = evaluate(gain0)
    if first is None:
        raise ValueError("the start gain misses the stability margin or an r.m.s. limit")
    objective.scale = first[2]
    phi, grad, j = evaluate(gain0)  # type: ignore[misc]
    gain, hessian_inv = gain0.copy(), np.eye(int(free.sum()))
    history, phi_history, status, converged = [j], [phi], "max_iterations", False
    g0 = max(float(np.linalg.norm(grad)), 1e-300)
    iteration = 0
    while iteration < max_iterations:
        iteration += 1
        if np.linalg.norm(grad) <= gtol * max(g0, 1.0):
            status, converged = "gradient below tolerance", True
            break
        direction = -hessian_inv @ grad
        if float(direction @ grad) >= 0.0:
            hessian_inv, direction = np.eye(len(grad)), -grad
        alpha, trial = 1.0, None
        while alpha > 1e-12:
            candidate = gain.copy()
            flat = candidate.ravel()
            flat[free] += alpha * direction
            candidate = flat.reshape(gain.shape)
            trial = evaluate(candidate)
            if trial is not None and trial[0] <= phi + 1e-4 * alpha * float(direction @ grad):
                break
            trial, alpha = None, 0.5 * alpha
        if trial is None:
            status = "no decrease along the search direction"
            converged = bool(np.linalg.norm(grad) <= 1e-4 * max(g0, 1.0))
            break
        step, change = alpha * direction, trial[1] - grad
        if float(step @ change) > 1e-16:
            rho = 1.0 / float(step @ change)
            eye = np.eye(len(step))
            hessian_inv = (eye - rho * np.outer(step, change)) @ hessian_inv @ (
                eye - rho * np.outer(change, step)
            ) + rho * np.outer(step, step)
        gain, (phi, grad, j) = candidate, trial
        history.append(j)
        phi_history.append(phi)
    return {
        "gain": gain,
        "cost": j,
        "iterations": iteration,
        "history": tuple(history),
        "phi_history": tuple(phi_history),
        "converged": converged,
        "status": status,
        "time_s": time.perf_counter() - started,
    }


def _abscissa(plants: Sequence[DesignPlant], gain: np.ndarray) -> float:
    return max(float(np.max(np.linalg.eigvals(closed_loop(p, gain)[0]).real)) for p in plants)


class _Reached(Exception):
    pass


def reach_margin(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    mask: np.ndarray,
    target: float,
    max_evaluations: int = 4000,
) -> tuple[np.ndarray, dict[str, Any] | None]:
    """Phase 1 of a design: ``gain0``, or a gain found by Nelder-Mead with max Re λ ≤ −target.

    The certified descents (:func:`minimise_certified`, and
    :func:`~loader_model.control.comfort_ipopt.minimise_ipopt`) need a start inside the
    σ-stable set; this moves a destabilising or too slow start there by minimising the largest
    spectral abscissa over ``plants`` in the free entries (``mask``), with up to 3 restarts.

    Parameters
    ----------
    plants : sequence of DesignPlant
        The closed loops u = −K y that must all meet the margin.
    gain0 : numpy.ndarray
        Start gain (m x p); fixed entries keep their values.
    mask : numpy.ndarray
        Boolean m x p array, True where an entry is free.
    target : float
        Required margin in rad/s: max_i max Re λ(A_cl,i) ≤ −target.
    max_evaluations : int
        Limit on eigenvalue evaluations over the restarts.

    Returns
    -------
    tuple
        (gain, None) on success; (best gain, dict with ``return_status`` naming the failure)
        otherwise.
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
