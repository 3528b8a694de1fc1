r"""A dense convex QP solved by a primal-dual interior point (Mehrotra predictor-corrector).

.. math:: \min_u \tfrac12 u^T P u + q^T u \quad \text{s.t.}\quad E u = e,\;
    l \le G u \le h,\; u_{lo} \le u \le u_{hi}

for the condensed bound (:mod:`~loader_model.bound.condensed`): P dense and definite (N up to a
few thousand), a handful of equality rows, simple bounds and a few thousand general rows. Each
iteration forms P + diag(D_u) + Gᵀ diag(D_G) G once (the bounds' barrier terms stay diagonal),
factors it by Cholesky and eliminates the equality rows by their small Schur complement. An
interior point does not mind nearly dependent rows (the active-set difficulty of
:mod:`~loader_model.bound.constrained`'s notes). Tolerances are relative: the residuals on the
scaled rows, the dual residual against the largest entry of q and diag P, and the duality gap
sᵀλ (which bounds the objective's error) against max(1, |objective|).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

__all__ = ["QPResult", "solve_dense_qp"]


@dataclass(frozen=True)
class QPResult:
    """The solution: u, iterations, the largest scaled residual, the mean complementarity and
    the multipliers of the equality rows (E u = e) and of the general rows (l ≤ G u ≤ h; positive
    on the upper bound, negative on the lower)."""

    u: np.ndarray
    iterations: int
    primal_residual: float
    dual_residual: float
    complementarity: float
    converged: bool
    equality_multipliers: np.ndarray | None = None
    row_multipliers: np.ndarray | None = None


def _step(values: np.ndarray, steps: np.ndarray) -> float:
    negative = steps < 0
    if not np.any(negative):
        return 1.0
    return float(min(1.0, np.min(-values[negative] / steps[negative])))


def _factor(normal: np.ndarray) -> tuple:
    """Cholesky factor of the normal matrix; near the end of the iteration the barrier terms of
    active rows reach 1e16 and round-off can make it indefinite: then the diagonal is raised by
    1e-14, 1e-12, … of its largest entry until the factorisation succeeds (a Newton step of a
    slightly regularised system, still a descent direction)."""
    try:
        return scipy.linalg.cho_factor(normal)
    except np.linalg.LinAlgError:
        pass
    largest = float(np.max(np.abs(np.diag(normal))))
    for exponent in range(-14, -5, 2):
        shifted = normal.copy()
        shifted[np.diag_indices_from(shifted)] += largest * 10.0**exponent
        try:
            return scipy.linalg.cho_factor(shifted)
        except np.linalg.LinAlgError:
            continue
    raise np.linalg.LinAlgError("the QP's normal matrix is not definite even regularised")


def solve_dense_qp(
    p: np.ndarray,
    q: np.ndarray,
    e_matrix: np.ndarray,
    e_target: np.ndarray,
    g: np.ndarray,
    lower: np.ndarray,
    upper: np.ndarray,
    u_lower: float,
    u_upper: float,
    *,
    tolerance: float = 1e-9,
    max_iterations: int = 80,
) -> QPResult:
    """Solve the QP of the module notes; ``tolerance`` relative (module notes)."""
    n, m = q.size, g.shape[0]
    # inequalities c(u) = b - C u >= 0 stacked: G u <= h, -G u <= -l, u <= u_hi, -u <= -u_lo
    b = np.concatenate([upper, -lower, np.full(n, u_upper), np.full(n, -u_lower)])

    def c_times(u: np.ndarray) -> np.ndarray:
        gu = g @ u
        return np.concatenate([gu, -gu, u, -u])

    def ct_times(v: np.ndarray) -> np.ndarray:
        return g.T @ (v[:m] - v[m : 2 * m]) + v[2 * m : 2 * m + n] - v[2 * m + n :]

    u = np.clip(np.zeros(n), u_lower, u_upper)
    slack = np.maximum(b - c_times(u), 1.0)
    dual = np.ones_like(slack)
    y = np.zeros(e_target.size)
    scale = max(1.0, float(np.max(np.abs(q))), float(np.max(np.abs(np.diag(p)))))
    converged, iteration = False, 0
    for _ in range(max_iterations):
        iteration += 1
        r_dual = p @ u + q + e_matrix.T @ y + ct_times(dual)
        r_eq = e_matrix @ u - e_target
        r_in = c_times(u) + slack - b
        gap = float(slack @ dual)
        mu = gap / slack.size
        primal = max(float(np.max(np.abs(r_eq), initial=0.0)), float(np.max(np.abs(r_in))))
        dual_res = float(np.max(np.abs(r_dual))) / scale
        objective = abs(0.5 * float(u @ p @ u) + float(q @ u))
        if primal < tolerance and dual_res < tolerance and gap < tolerance * max(1.0, objective):
            converged = True
            break
        ratio = dual / slack
        normal = p + g.T @ ((ratio[:m] + ratio[m : 2 * m])[:, None] * g)
        normal[np.diag_indices(n)] += ratio[2 * m : 2 * m + n] + ratio[2 * m + n :]
        factor = _factor(normal)
        inv_et = scipy.linalg.cho_solve(factor, e_matrix.T)
        schur = e_matrix @ inv_et

        def direction(
            target: np.ndarray,
            slack: np.ndarray = slack,
            dual: np.ndarray = dual,
            r_in: np.ndarray = r_in,
            r_dual: np.ndarray = r_dual,
            r_eq: np.ndarray = r_eq,
            factor: tuple = factor,
            inv_et: np.ndarray = inv_et,
            schur: np.ndarray = schur,
        ) -> tuple[np.ndarray, ...]:
            """Newton step towards slack * dual = target (the Schur complement of E)."""
            rhs_u = -r_dual - ct_times((dual * r_in + target - slack * dual) / slack)
            base = scipy.linalg.cho_solve(factor, rhs_u)
            dy = np.linalg.solve(schur, e_matrix @ base + r_eq)
            du = base - inv_et @ dy
            ds = -r_in - c_times(du)
            dz = (target - slack * dual - dual * ds) / slack
            return du, dy, ds, dz

        du, dy, ds, dz = direction(np.zeros_like(slack))
        alpha = min(_step(slack, ds), _step(dual, dz))
        mu_affine = float((slack + alpha * ds) @ (dual + alpha * dz)) / slack.size
        sigma = (mu_affine / mu) ** 3
        du, dy, ds, dz = direction(sigma * mu - ds * dz)
        alpha = 0.99 * min(_step(slack, ds), _step(dual, dz))
        u, y = u + alpha * du, y + alpha * dy
        slack, dual = slack + alpha * ds, dual + alpha * dz
    r_eq = e_matrix @ u - e_target
    return QPResult(
        u=u,
        iterations=iteration,
        primal_residual=max(float(np.max(np.abs(r_eq), initial=0.0)),
                            float(np.max(np.abs(c_times(u) + slack - b)))),
        dual_residual=float(np.max(np.abs(p @ u + q + e_matrix.T @ y + ct_times(dual)))) / scale,
        complementarity=float(slack @ dual) / slack.size,
        converged=converged,
        equality_multipliers=y,
        row_multipliers=dual[:m] - dual[m : 2 * m],
    )  # fmt: skip
