r"""A convex QP in stage form solved by a primal-dual interior point with a Riccati recursion.

.. math:: \min_{v} \sum_{j=0}^{N-1} \tfrac12 w_j^T H_j w_j + g_j^T w_j, \qquad
    w_j = (z_j, v_j),\; z_0 = 0,\; z_{j+1} = F_j z_j + G_j v_j,

    \text{s.t.}\quad l_j \le D_j w_j \le h_j,\quad v_{lo,j} \le v_j \le v_{hi,j},\quad
    E z_N = e

with n_u inputs per stage (commands: the nonlinear bound puts several command intervals in one
stage, :mod:`~loader_model.bound.stage_model`) and n_z states. It is the algorithm of
:mod:`~loader_model.bound.dense_qp` (Mehrotra predictor-corrector on the same residuals and
the same relative tolerances, the variables the commands v) with the dense algebra replaced by
the stage structure: the products with the condensed Hessian and rows are forward and adjoint
sweeps of the dynamics, and the Newton system, the condensed normal matrix, is never formed: it
is the LQ problem with the stage Hessians H_j + D_jᵀ Σ_j D_j (Σ_j the barrier terms), solved
by one backward Riccati factorisation and a forward sweep per right-hand side. The end
condition's n_e multipliers come from n_e further columns of the same sweeps and their
n_e × n_e Schur complement. Every iteration costs O(N (n_z³ + rows n_z²)), linear in N,
against O(N³ + rows N²) for the condensed form; every row is kept, so no constraint generation.

Near the end of the iteration the barrier terms of active rows grow by many orders, and a row
nearly along the command cancels in the recursion's Schur complement: the plain recursion
P_j = Q̄_j − S̄_jᵀ S̄_j / R̄_j then lost definiteness to round-off (R̄ = −1e11 on the nonlinear
bound's 6 s problem). The recursion is therefore carried in square-root form (P_j = L_j L_jᵀ,
:func:`_factor`), with eigenvalues clipped at zero where even the Cholesky factor of the Schur
complement fails, and each Newton direction gets one step of iterative refinement against the
exact stage Hessians; without it the dual residual stalled at 2e-2 (with it: 30 iterations to
1e-8). Where one step leaves more than :data:`REFINE_RTOL` of the right-hand side (late
iterations of ill-conditioned problems: 1e-9 ... 3e-9 after one step, 1e-11 after two, on a
random stage QP whose dual residual then stalled at 3e-9 above a tolerance of 1e-9), up to
:data:`EXTRA_REFINEMENTS` further steps follow; over 360 random stage QPs 360 converged
against 358 with one step, in the same CPU time. Measured on the development machine
(2 cores): the nonlinear bound's Gauss-Newton QP of
the 3 s, 5 mm course (N = 300) in 21 iterations, 0.7 s (the dense interior point with constraint
generation on the condensed form 0.85 s, the same objective to 6e-8); 6 s of the paper course
(N = 600) 30 iterations, 2.1 s (dense 7.6 s); 12 s (N = 1200) 30 iterations, 4.5-5 s (one
interval per stage); a random property test against qpOASES on the explicit condensation. With
five command intervals per stage the QP of the 11.55 s paper course at 18 km/h (231 stages)
takes 27 iterations, 1.7 s, against 4.5 s with one (development machine; per iteration the
factorisation 15 ms, the stage normal matrices 15 ms, the rows' products 16 ms, the sweeps
9 ms).

An infeasible QP (the nonlinear bound's second-order correction can shift the rows past what
the command can meet) shows as a primal residual that stops falling while μ stops falling or
grows: measured on the 11.5 s course at 18 km/h, the residual stayed at 6e-2 from the fourth
iteration while μ grew to 5e15 at the iteration limit (80 iterations, 9 s). The iteration
therefore stops, not converged, when over :data:`STALL_WINDOW` iterations neither the primal
residual (while above the tolerance) nor μ fell by :data:`STALL_FACTOR`; a converging solve
lowers μ by more than that every two iterations. At the other end, once the primal residual
and the gap meet the tolerance, the barrier terms of the active rows reach 1e16 and the dual
residual has a round-off floor: on the same course it fell to 4e-11, then rose to 4e-8 ... 0.5
as μ fell to 1e-20 and the solve ran to its 80 iterations (12-14 s) with tolerance 1e-8. It
stops there too (the dual residual not halved over :data:`STALL_WINDOW` iterations, the rest
met), and a solve that stops without converging returns its best iterate (the smallest
largest scaled residual), not its last.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.bound.dense_qp import QPResult
from loader_model.bound.riccati_kernels import riccati_factor, riccati_solve
from loader_model.bound.stage_form import (
    StageQP,
    adjoint,
    condensed_gradient,
    forward,
    mean_condensed_curvature,
)

__all__ = ["solve_riccati_qp"]

#: Iterative-refinement steps of each Newton direction (module notes).
REFINEMENTS = 1
#: Further refinement steps at most, each taken while the condensed residual after the last one
#: is above :data:`REFINE_RTOL` of the right-hand side (module notes).
EXTRA_REFINEMENTS = 2
#: Relative residual of a refined Newton direction below which no further step is taken.
REFINE_RTOL = 1e-10
#: The centring target's floor, relative to the μ at which the gap meets the tolerance.
MU_FLOOR = 0.1
#: Iterations over which a QP without progress is given up as infeasible (module notes).
STALL_WINDOW = 5
#: Least decrease of the primal residual or of μ over :data:`STALL_WINDOW` iterations.
STALL_FACTOR = 0.5


@dataclass(frozen=True)
class _Factor:
    """The Riccati recursion of one set of stage Hessians: S̄_j (N, n_u, n_z) and the lower
    Cholesky factors of R̄_j (N, n_u, n_u)."""

    s_bar: np.ndarray
    r_low: np.ndarray


def _factor(qp: StageQP, hessian: np.ndarray) -> _Factor:
    """The Riccati recursion of stage Hessians ``hessian``.

    The cost-to-go P_j is carried as a factor L_j (P_j = L_j L_jᵀ, the square-root form), so
    that every M_j = H̃_j + [F_j G_j]ᵀ P_{j+1} [F_j G_j] is a sum of Gram matrices: R̄_j, its
    command block, is positive definite whatever the round-off, and P_j stays semi-definite; the next
    factor is the Cholesky factor of M_j's Schur complement, or, where round-off made a pivot
    negative (rows of a near-active limit nearly along the command, whose barrier term cancels
    in the Schur complement), its eigenvalues clipped at zero
    (:func:`~loader_model.bound.riccati_kernels.riccati_factor`)."""
    s_bar, r_low, failed = riccati_factor(qp.stacked, np.ascontiguousarray(hessian))
    finite = np.all(np.isfinite(r_low), axis=(1, 2)) & np.all(np.isfinite(s_bar), axis=(1, 2))
    if failed >= 0 or not np.all(finite):
        stage = failed if failed >= 0 else int(np.argmin(finite))
        raise np.linalg.LinAlgError(
            f"stage {stage}: the Riccati recursion's R̄ is not positive definite (or not finite)"
        )
    return _Factor(s_bar, r_low)


def _solve(
    qp: StageQP, factor: _Factor, linear: np.ndarray, end: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Minimise ½ Σ wᵀ H̃ w + Σ linear_jᵀ w_j + endᵀ z_N for each column: (N, n_z + n_u, c),
    (n_z, c).

    With the value's linear term p_j and the feedforward k_j = −R̄_j⁻¹ (r_j + G_jᵀ p_{j+1}),
    p_j = q_j + F_jᵀ p_{j+1} + S̄_jᵀ k_j, and forward v_j = k_j − R̄_j⁻¹ S̄_j z_j,
    z_{j+1} = F_j z_j + G_j v_j (:func:`~loader_model.bound.riccati_kernels.riccati_solve`)."""
    return riccati_solve(
        qp.contiguous_transition, qp.contiguous_command_map, factor.s_bar, factor.r_low,
        np.ascontiguousarray(linear, dtype=float), np.ascontiguousarray(end, dtype=float),
    )  # fmt: skip


def _step(values: np.ndarray, steps: np.ndarray) -> float:
    negative = steps < 0
    if not np.any(negative):
        return 1.0
    return float(min(1.0, np.min(-values[negative] / steps[negative])))


def solve_riccati_qp(
    qp: StageQP, *, tolerance: float = 1e-9, max_iterations: int = 80
) -> tuple[QPResult, np.ndarray]:
    """Solve ``qp`` (module notes); ``tolerance`` relative as in :mod:`~loader_model.bound.
    dense_qp`.

    Returns
    -------
    tuple
        (QPResult with u = v stage by stage (N n_u,) and ``row_multipliers`` (N, n_r), the stage
        variables w (N, n_z + n_u)).
    """
    n, nz, n_in = qp.command_map.shape
    inputs = np.arange(nz, nz + n_in)
    rows = qp.rows
    rows_t = np.ascontiguousarray(rows.transpose(0, 2, 1))
    n_e = qp.end_target.size
    zero_columns = np.zeros((n, nz + n_in, n_e))

    def row_values(w: np.ndarray) -> np.ndarray:
        return (rows @ w[:, :, None])[:, :, 0]

    def rowadjoint(values: np.ndarray) -> np.ndarray:
        return (rows_t @ values[:, :, None])[:, :, 0]

    v = np.clip(np.zeros((n, n_in)), qp.v_low, qp.v_high)
    w, z_end = forward(qp, v)
    bounds = (qp.row_high, -qp.row_low, qp.v_high, -qp.v_low)

    def constraint(w: np.ndarray) -> tuple[np.ndarray, ...]:
        values = row_values(w)
        return values, -values, w[:, nz:], -w[:, nz:]

    slack = [np.maximum(b - c, 1.0) for b, c in zip(bounds, constraint(w), strict=True)]
    dual = [np.ones_like(s) for s in slack]
    y = np.zeros(n_e)
    # the dense form's scale of the dual residual, max(1, |q|, diag P), with diag P's mean
    scale = max(1.0, float(np.max(np.abs(condensed_gradient(qp)))), mean_condensed_curvature(qp))
    count = sum(s.size for s in slack)
    converged, iteration = False, 0
    history: list[tuple[float, float, float]] = []
    best: tuple = (np.inf,)

    def stage_terms(values: list[np.ndarray]) -> np.ndarray:
        """Cᵀ values in stage form."""
        out = rowadjoint(values[0] - values[1])
        out[:, nz:] += values[2] - values[3]
        return out

    for _ in range(max_iterations):
        iteration += 1
        h = (qp.hessian @ w[:, :, None])[:, :, 0] + qp.gradient + stage_terms(dual)
        r_dual = adjoint(qp, h, qp.end_rows.T @ y)
        r_eq = qp.end_rows @ z_end - qp.end_target
        r_in = [c + s - b for c, s, b in zip(constraint(w), slack, bounds, strict=True)]
        gap = float(sum(np.sum(s * d) for s, d in zip(slack, dual, strict=True)))
        mu = gap / count
        primal = max(
            float(np.max(np.abs(r_eq), initial=0.0)), *(float(np.max(np.abs(r))) for r in r_in)
        )
        dual_res = float(np.max(np.abs(r_dual))) / scale
        objective = abs(
            float(np.sum(w * (0.5 * (qp.hessian @ w[:, :, None])[:, :, 0] + qp.gradient)))
        )
        if primal < tolerance and dual_res < tolerance and gap < tolerance * max(1.0, objective):
            converged = True
            break
        error = max(primal, dual_res, gap / max(1.0, objective))
        if error < best[0]:
            best = (error, w, z_end, y, slack, dual)
        history.append((primal, mu, dual_res))
        if len(history) > STALL_WINDOW:
            primal_before, mu_before, dual_before = history[-1 - STALL_WINDOW]
            if primal >= tolerance:
                if primal > STALL_FACTOR * primal_before and mu > STALL_FACTOR * mu_before:
                    break  # no progress: infeasible (module notes)
            elif gap < tolerance * max(1.0, objective) and dual_res > STALL_FACTOR * dual_before:
                break  # the dual residual's round-off floor (module notes)
        ratio = [d / s for d, s in zip(dual, slack, strict=True)]
        normal = qp.hessian + rows_t @ (rows * (ratio[0] + ratio[1])[:, :, None])
        normal[:, inputs, inputs] += ratio[2] + ratio[3]
        factor = _factor(qp, normal)
        # the end condition's columns: the responses to a unit multiplier on each end row
        end_w, end_z = _solve(qp, factor, zero_columns, qp.end_rows.T)
        schur = qp.end_rows @ end_z
        h_base = h - stage_terms(dual)

        def newton(
            linear: np.ndarray,
            end_target: np.ndarray,
            factor: tuple = factor,
            end_w: np.ndarray = end_w,
            end_z: np.ndarray = end_z,
            schur: np.ndarray = schur,
            normal: np.ndarray = normal,
        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            """The LQ step (dw, dz_N, ν) of linear terms ``linear`` with E dz_N = end_target,
            refined against the exact stage Hessians (the factor is of a semi-definite
            repair where round-off made the recursion indefinite: :func:`_factor`)."""
            step = np.zeros((n, nz + n_in)), np.zeros(nz), np.zeros(n_e)
            residual_linear, residual_end = linear, end_target
            size = max(
                float(np.max(np.abs(linear))), float(np.max(np.abs(end_target), initial=0.0))
            )
            for refinement in range(1 + REFINEMENTS + EXTRA_REFINEMENTS):
                if refinement:  # the condensed residual, put on the commands
                    gradient = (normal @ step[0][:, :, None])[:, :, 0] + linear
                    residual_linear = np.zeros((n, nz + n_in))
                    residual_linear[:, nz:] = adjoint(qp, gradient, qp.end_rows.T @ step[2])
                    residual_end = end_target - qp.end_rows @ step[1]
                    left = max(
                        float(np.max(np.abs(residual_linear))),
                        float(np.max(np.abs(residual_end), initial=0.0)),
                    )
                    if refinement > REFINEMENTS and left <= REFINE_RTOL * size:
                        break
                base_w, base_z = _solve(qp, factor, residual_linear[:, :, None], np.zeros((nz, 1)))
                nu = np.linalg.solve(schur, residual_end - qp.end_rows @ base_z[:, 0])
                step = (
                    step[0] + base_w[:, :, 0] + end_w @ nu,
                    step[1] + base_z[:, 0] + end_z @ nu,
                    step[2] + nu,
                )
            return step

        def direction(
            target: list[np.ndarray],
            slack: list[np.ndarray] = slack,
            dual: list[np.ndarray] = dual,
            r_in: list[np.ndarray] = r_in,
            h_base: np.ndarray = h_base,
            r_eq: np.ndarray = r_eq,
        ) -> tuple:
            """Newton step towards slack * dual = target (module notes)."""
            shifted = [
                d + (d * r + t - s * d) / s
                for d, r, t, s in zip(dual, r_in, target, slack, strict=True)
            ]
            dw, dz_end, nu = newton(h_base + stage_terms(shifted), -r_eq)
            ds = [-r - c for r, c in zip(r_in, constraint(dw), strict=True)]
            dd = [
                (t - s * d - d * x) / s for t, s, d, x in zip(target, slack, dual, ds, strict=True)
            ]
            return dw, dz_end, nu, ds, dd

        zeros = [np.zeros_like(s) for s in slack]
        dw, dz_end, _, ds, dd = direction(zeros)
        alpha = min(
            min(_step(s, x) for s, x in zip(slack, ds, strict=True)),
            min(_step(d, x) for d, x in zip(dual, dd, strict=True)),
        )
        mu_affine = (
            float(
                sum(
                    np.sum((s + alpha * a) * (d + alpha * b))
                    for s, a, d, b in zip(slack, ds, dual, dd, strict=True)
                )
            )
            / count
        )
        sigma = (mu_affine / mu) ** 3
        # μ no lower than what the gap test needs (module notes)
        centre = max(sigma * mu, MU_FLOOR * tolerance * max(1.0, objective) / count)
        target = [centre - a * b for a, b in zip(ds, dd, strict=True)]
        dw, dz_end, nu, ds, dd = direction(target)
        alpha = 0.99 * min(
            min(_step(s, x) for s, x in zip(slack, ds, strict=True)),
            min(_step(d, x) for d, x in zip(dual, dd, strict=True)),
        )
        w, z_end, y = w + alpha * dw, z_end + alpha * dz_end, y + alpha * (nu - y)
        slack = [s + alpha * x for s, x in zip(slack, ds, strict=True)]
        dual = [d + alpha * x for d, x in zip(dual, dd, strict=True)]
    if not converged and len(best) > 1:
        w, z_end, y, slack, dual = best[1:]
    h = (qp.hessian @ w[:, :, None])[:, :, 0] + qp.gradient + stage_terms(dual)
    r_in = [c + s - b for c, s, b in zip(constraint(w), slack, bounds, strict=True)]
    result = QPResult(
        u=w[:, nz:].ravel(),
        iterations=iteration,
        primal_residual=max(float(np.max(np.abs(qp.end_rows @ z_end - qp.end_target))),
                            *(float(np.max(np.abs(r))) for r in r_in)),
        dual_residual=float(np.max(np.abs(adjoint(qp, h, qp.end_rows.T @ y)))) / scale,
        complementarity=float(sum(np.sum(s * d) for s, d in zip(slack, dual, strict=True))) / count,
        converged=converged,
        equality_multipliers=y,
        row_multipliers=dual[0] - dual[1],
    )  # fmt: skip
    return result, w
