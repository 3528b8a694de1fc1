"""The descent of the output-feedback LQR (Eq. 42): Newton or Moerder-Calise steps, backtracking.

Helper of :mod:`loader_model.control.output_feedback`, with its scale-aware stopping rule
(:data:`DECREMENT_RTOL`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from loader_model.control import _sof_derivatives as eq42

__all__ = ["DECREMENT_RTOL", "Descent", "descend"]


#: Converged on the cost when the Newton decrement says that the decrease still to be had,
#: ½ gᵀ H⁻¹ g, is below this multiple of |J|: J is evaluated from Lyapunov solutions whose
#: relative round-off is about cond · ε (at the optimum of the 13-state loader design plant the
#: cost came out 8e-13 apart, relative, on the Haswell, SkylakeX and Sandybridge kernels of
#: OpenBLAS), so a smaller decrease cannot be resolved; the allowance has a margin of 10.
DECREMENT_RTOL = 1e-11


@dataclass(frozen=True)
class Descent:
    gain: np.ndarray
    p: np.ndarray
    s: np.ndarray
    residuals: tuple[float, float, float]
    decrement: float
    iterations: int
    converged: bool


def _direction(
    b: np.ndarray,
    c: np.ndarray,
    k: np.ndarray,
    r: np.ndarray,
    p: np.ndarray,
    s: np.ndarray,
    solver: Any,
    mask: np.ndarray,
    g: np.ndarray,
    newton: bool,
) -> tuple[np.ndarray, bool]:
    """Newton step where the exact Hessian is positive definite, else Moerder-Calise."""
    free = mask.ravel(order="F")
    if newton:
        try:
            hessian = eq42.hessian(b, c, k, r, p, s, solver, mask)
            if np.all(np.linalg.eigvalsh(hessian) > 0):
                return -np.linalg.solve(hessian, g), True
        except np.linalg.LinAlgError:
            pass
    preconditioner = np.kron(c @ s @ c.T, r)[np.ix_(free, free)]
    if np.linalg.cond(preconditioner) > 1e14:
        raise np.linalg.LinAlgError("C S Cᵀ is singular: check that C has full row rank and X0 ≻ 0")
    return -np.linalg.solve(preconditioner, g), False


def descend(
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    q: np.ndarray,
    r: np.ndarray,
    x0: np.ndarray,
    k: np.ndarray,
    mask: np.ndarray,
    rtol: float,
    max_iterations: int,
    history: list[float],
    newton: bool = True,
) -> Descent:
    """Newton or Moerder-Calise steps with Armijo backtracking (monotone, stays stabilising).

    The Moerder-Calise step solves the stationarity condition with P and S frozen on the free
    entries, ΔK = −H_ff⁻¹ g_f with H = (C S Cᵀ) ⊗ R ≻ 0: a preconditioned gradient direction.
    Where the exact Hessian is positive definite the Newton step is taken instead (quadratic
    convergence). Backtracking keeps A − B K C Hurwitz (cost finite) and J decreasing (Armijo,
    with a rounding allowance of 1e-14 |J|). Where J is flat to rounding, the decrease of a
    Newton step cannot be seen in J; the full step is then taken if it shrinks the stationarity
    residual (the gradient is resolved far better than J near the optimum).

    Stops when the stationarity residual is 1e-3 rtol, or when the Newton decrement's predicted
    decrease ½ gᵀ H⁻¹ g is at most :data:`DECREMENT_RTOL` |J| and no step makes progress.
    Converged: residual ≤ rtol, or a predicted decrease ≤ DECREMENT_RTOL |J| (the cost is at
    its optimum to what its evaluation resolves).
    """
    free = mask.ravel(order="F")
    cost, p, s, weight, solver = eq42.evaluate(a, b, c, k, q, r, x0)
    history.append(cost)
    decrement, flat = np.inf, 0
    for iteration in range(max_iterations + 1):
        residuals, gradient = eq42.residuals(a - b @ k @ c, b, c, k, r, x0, p, s, weight, mask)
        if residuals[2] <= 1e-3 * rtol or iteration == max_iterations:
            break  # polished: iterations go on past rtol while the cost still decreases
        g = gradient.ravel(order="F")[free]
        direction, is_newton = _direction(b, c, k, r, p, s, solver, mask, g, newton)
        step = np.zeros(k.size)
        step[free] = direction
        step = step.reshape(k.shape, order="F")
        slope = float(np.sum(gradient * step))
        decrement = -0.5 * slope / abs(cost) if is_newton else np.inf
        alpha, trial = 1.0, None
        while alpha > 1e-14:
            trial = eq42.evaluate(a, b, c, k + alpha * step, q, r, x0, need_s=False)
            if trial is not None and trial[0] <= cost + 1e-4 * alpha * slope + 1e-14 * abs(cost):
                break
            trial, alpha = None, 0.5 * alpha
        flat = flat + 1 if trial is not None and trial[0] >= cost else 0
        if (trial is None or flat > 3) and decrement <= DECREMENT_RTOL:
            polished = eq42.evaluate(a, b, c, k + step, q, r, x0)
            if polished is None:
                break
            new = eq42.residuals(
                a - b @ (k + step) @ c, b, c, k + step, r, x0, *polished[1:4], mask
            )
            if new[0][2] >= 0.5 * residuals[2] or polished[0] > cost + DECREMENT_RTOL * abs(cost):
                break  # the full Newton step no longer shrinks the residual: at round-off
            k, alpha, flat = k + step, 1.0, 0
            cost, p, s, weight, solver = polished
            history.append(cost)
            continue
        if trial is None or flat > 3:
            break  # no decrease within rounding and no Newton polish: stationary numerically
        k = k + alpha * step
        cost, p, s, weight, solver = eq42.evaluate(a, b, c, k, q, r, x0)
        history.append(cost)
    converged = residuals[2] <= rtol or decrement <= DECREMENT_RTOL
    return Descent(k, p, s, residuals, decrement, iteration, converged)
