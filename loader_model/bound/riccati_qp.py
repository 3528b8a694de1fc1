r"""A convex QP in stage form solved by a primal-dual interior point with a Riccati recursion.

.. math:: \min_{v} \sum_{j=0}^{N-1} \tfrac12 w_j^T H_j w_j + g_j^T w_j, \qquad
    w_j = (z_j, v_j),\; z_0 = 0,\; z_{j+1} = F_j z_j + G_j v_j,

    \text{s.t.}\quad l_j \le D_j w_j \le h_j,\quad v_{lo,j} \le v_j \le v_{hi,j},\quad
    E z_N = e

with one input per stage (the command) and n_z states. It is the algorithm of
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
1e-8). Measured on the development machine (2 cores): the nonlinear bound's Gauss-Newton QP of
the 3 s, 5 mm course (N = 300) in 21 iterations, 0.7 s (the dense interior point with constraint
generation on the condensed form 0.85 s, the same objective to 6e-8); 6 s of the paper course
(N = 600) 30 iterations, 2.1 s (dense 7.6 s); 12 s (N = 1200) 30 iterations, 4.5-5 s; a random
property test against qpOASES on the explicit condensation.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from loader_model.bound.dense_qp import QPResult
from loader_model.bound.riccati_kernels import recur, riccati_factor, riccati_solve

__all__ = ["StageQP", "condensed_gradient", "mean_condensed_curvature", "solve_riccati_qp"]

#: Iterative-refinement steps of each Newton direction (module notes).
REFINEMENTS = 1


@dataclass(frozen=True)
class StageQP:
    """The QP of the module notes (one input per stage).

    Attributes
    ----------
    transition, command_map : numpy.ndarray
        (N, n_z, n_z) F_j and (N, n_z) G_j.
    hessian, gradient : numpy.ndarray
        (N, n_z + 1, n_z + 1) H_j and (N, n_z + 1) g_j, in w_j = (z_j, v_j).
    rows, row_low, row_high : numpy.ndarray
        (N, n_r, n_z + 1) D_j and (N, n_r) l_j, h_j (finite).
    v_low, v_high : numpy.ndarray
        (N,) the bounds on v_j.
    end_rows, end_target : numpy.ndarray
        (n_e, n_z) E and (n_e,) e.
    """

    transition: np.ndarray
    command_map: np.ndarray
    hessian: np.ndarray
    gradient: np.ndarray
    rows: np.ndarray
    row_low: np.ndarray
    row_high: np.ndarray
    v_low: np.ndarray
    v_high: np.ndarray
    end_rows: np.ndarray
    end_target: np.ndarray

    @cached_property
    def transposed(self) -> np.ndarray:
        """(N, n_z, n_z) F_jᵀ, contiguous (the forward sweep's columns, :func:`_recur`)."""
        return np.ascontiguousarray(self.transition.transpose(0, 2, 1))

    @cached_property
    def reversed(self) -> np.ndarray:
        """(N, n_z, n_z) F_{N−1−i}, contiguous (the adjoint sweep's columns, :func:`_recur`)."""
        return np.ascontiguousarray(self.transition[::-1])

    @cached_property
    def contiguous_transition(self) -> np.ndarray:
        """(N, n_z, n_z) F_j, C-contiguous (the compiled Riccati sweeps read it)."""
        return np.ascontiguousarray(self.transition, dtype=float)

    @cached_property
    def stacked(self) -> np.ndarray:
        """(N, n_z, n_z + 1) [F_j G_j], the dynamics' map of w_j."""
        return np.concatenate([self.transition, self.command_map[:, :, None]], axis=2)


def _recur(columns: np.ndarray, offsets: np.ndarray, first: np.ndarray) -> np.ndarray:
    """x_0 = ``first``, x_{i+1} = A_i x_i + b_i: all (N + 1, n_z[, c]) x_i, with ``columns``
    (N, n_z, n_z) holding A_iᵀ and ``offsets`` (N, n_z[, c]) the b_i (compiled:
    :func:`~loader_model.bound.riccati_kernels.recur`; in NumPy it took 3-7 µs per stage of 43
    states, and CasADi's compiled mapaccum of the same step 3.6 µs)."""
    return recur(columns, offsets, first)


def _forward(qp: StageQP, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """w_j (N, n_z + 1) and z_N of the commands ``v``."""
    n, nz = qp.command_map.shape
    z = _recur(qp.transposed, qp.command_map * v[:, None], np.zeros(nz))
    return np.concatenate([z[:n], v[:, None]], axis=1), z[n]


def _adjoint(qp: StageQP, h: np.ndarray, h_end: np.ndarray) -> np.ndarray:
    """The condensed gradient Tᵀ h of stage vectors h (N, n_z + 1) and h_end on z_N."""
    nz = qp.command_map.shape[1]
    # costate_j = h_{j,z} + F_jᵀ costate_{j+1}, swept from costate_N = h_end
    costate = _recur(qp.reversed, h[::-1, :nz], h_end)[::-1]
    return h[:, nz] + np.einsum("jk,jk->j", qp.command_map, costate[1:])


def condensed_gradient(qp: StageQP) -> np.ndarray:
    """(N,) the gradient of the cost in v at v = 0 (the condensed form's q)."""
    return _adjoint(qp, qp.gradient, np.zeros(qp.command_map.shape[1]))


def mean_condensed_curvature(qp: StageQP) -> float:
    """The mean diagonal entry of the condensed Hessian Tᵀ H T, exactly: its trace is
    Σ_j tr(H_j Cov w_j) for unit white v, with Cov z_{j+1} = F_j Cov z_j F_jᵀ + G_j G_jᵀ (the
    scale of a Levenberg-Marquardt damping term, as the dense form's mean of diag P)."""
    n, nz = qp.command_map.shape
    covariance, trace = np.zeros((nz, nz)), 0.0
    for j in range(n):
        trace += float(np.sum(qp.hessian[j, :nz, :nz] * covariance)) + qp.hessian[j, nz, nz]
        f, g = qp.transition[j], qp.command_map[j]
        covariance = f @ covariance @ f.T + np.outer(g, g)
    return trace / n


@dataclass(frozen=True)
class _Factor:
    """The Riccati recursion of one set of stage Hessians: S̄_j (N, n_z) and R̄_j (N,)."""

    s_bar: np.ndarray
    r_bar: np.ndarray


def _factor(qp: StageQP, hessian: np.ndarray) -> _Factor:
    """The Riccati recursion of stage Hessians ``hessian``.

    The cost-to-go P_j is carried as a factor L_j (P_j = L_j L_jᵀ, the square-root form), so
    that every M_j = H̃_j + [F_j G_j]ᵀ P_{j+1} [F_j G_j] is a sum of Gram matrices: R̄_j, its
    command entry, is positive whatever the round-off, and P_j stays semi-definite; the next
    factor is the Cholesky factor of M_j's Schur complement, or, where round-off made a pivot
    negative (rows of a near-active limit nearly along the command, whose barrier term cancels
    in the Schur complement), its eigenvalues clipped at zero
    (:func:`~loader_model.bound.riccati_kernels.riccati_factor`)."""
    s_bar, r_bar, failed = riccati_factor(qp.stacked, np.ascontiguousarray(hessian))
    if failed >= 0 or not (np.all(np.isfinite(s_bar)) and np.all(np.isfinite(r_bar))):
        stage = failed if failed >= 0 else int(np.argmin(np.isfinite(r_bar)))
        raise np.linalg.LinAlgError(f"stage {stage}: the Riccati recursion's R̄ is {r_bar[stage]:g}")
    return _Factor(s_bar, r_bar)


def _solve(
    qp: StageQP, factor: _Factor, linear: np.ndarray, end: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Minimise ½ Σ wᵀ H̃ w + Σ linear_jᵀ w_j + endᵀ z_N for each column: (N, n_z + 1, c), (n_z, c).

    With the value's linear term p_j and the feedforward k_j = −(r_j + G_jᵀ p_{j+1}) / R̄_j,
    p_j = q_j − S̄_jᵀ r_j / R̄_j + (F_j − G_j S̄_j / R̄_j)ᵀ p_{j+1}, and forward
    z_{j+1} = (F_j − G_j S̄_j / R̄_j) z_j + G_j k_j, v_j = k_j − S̄_j z_j / R̄_j
    (:func:`~loader_model.bound.riccati_kernels.riccati_solve`)."""
    return riccati_solve(
        qp.contiguous_transition, qp.command_map, factor.s_bar, factor.r_bar,
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
        (QPResult with u = v and ``row_multipliers`` (N, n_r), the stage variables w (N, n_z + 1)).
    """
    n, nz = qp.command_map.shape
    rows = qp.rows
    rows_t = np.ascontiguousarray(rows.transpose(0, 2, 1))
    n_e = qp.end_target.size
    zero_columns = np.zeros((n, nz + 1, n_e))

    def row_values(w: np.ndarray) -> np.ndarray:
        return (rows @ w[:, :, None])[:, :, 0]

    def row_adjoint(values: np.ndarray) -> np.ndarray:
        return (rows_t @ values[:, :, None])[:, :, 0]

    v = np.clip(np.zeros(n), qp.v_low, qp.v_high)
    w, z_end = _forward(qp, v)
    bounds = (qp.row_high, -qp.row_low, qp.v_high, -qp.v_low)

    def constraint(w: np.ndarray) -> tuple[np.ndarray, ...]:
        values = row_values(w)
        return values, -values, w[:, nz], -w[:, nz]

    slack = [np.maximum(b - c, 1.0) for b, c in zip(bounds, constraint(w), strict=True)]
    dual = [np.ones_like(s) for s in slack]
    y = np.zeros(n_e)
    # the dense form's scale of the dual residual, max(1, |q|, diag P), with diag P's mean
    scale = max(1.0, float(np.max(np.abs(condensed_gradient(qp)))), mean_condensed_curvature(qp))
    count = sum(s.size for s in slack)
    converged, iteration = False, 0

    def stage_terms(values: list[np.ndarray]) -> np.ndarray:
        """Cᵀ values in stage form."""
        out = row_adjoint(values[0] - values[1])
        out[:, nz] += values[2] - values[3]
        return out

    for _ in range(max_iterations):
        iteration += 1
        h = (qp.hessian @ w[:, :, None])[:, :, 0] + qp.gradient + stage_terms(dual)
        r_dual = _adjoint(qp, h, qp.end_rows.T @ y)
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
        ratio = [d / s for d, s in zip(dual, slack, strict=True)]
        normal = qp.hessian + rows_t @ (rows * (ratio[0] + ratio[1])[:, :, None])
        normal[:, nz, nz] += ratio[2] + ratio[3]
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
            step = np.zeros((n, nz + 1)), np.zeros(nz), np.zeros(n_e)
            residual_linear, residual_end = linear, end_target
            for refinement in range(1 + REFINEMENTS):
                if refinement:  # the condensed residual, put on the commands
                    gradient = (normal @ step[0][:, :, None])[:, :, 0] + linear
                    residual_linear = np.zeros((n, nz + 1))
                    residual_linear[:, nz] = _adjoint(qp, gradient, qp.end_rows.T @ step[2])
                    residual_end = end_target - qp.end_rows @ step[1]
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
        target = [sigma * mu - a * b for a, b in zip(ds, dd, strict=True)]
        dw, dz_end, nu, ds, dd = direction(target)
        alpha = 0.99 * min(
            min(_step(s, x) for s, x in zip(slack, ds, strict=True)),
            min(_step(d, x) for d, x in zip(dual, dd, strict=True)),
        )
        w, z_end, y = w + alpha * dw, z_end + alpha * dz_end, y + alpha * (nu - y)
        slack = [s + alpha * x for s, x in zip(slack, ds, strict=True)]
        dual = [d + alpha * x for d, x in zip(dual, dd, strict=True)]
    h = (qp.hessian @ w[:, :, None])[:, :, 0] + qp.gradient + stage_terms(dual)
    r_in = [c + s - b for c, s, b in zip(constraint(w), slack, bounds, strict=True)]
    result = QPResult(
        u=w[:, nz].copy(),
        iterations=iteration,
        primal_residual=max(float(np.max(np.abs(qp.end_rows @ z_end - qp.end_target))),
                            *(float(np.max(np.abs(r))) for r in r_in)),
        dual_residual=float(np.max(np.abs(_adjoint(qp, h, qp.end_rows.T @ y)))) / scale,
        complementarity=float(sum(np.sum(s * d) for s, d in zip(slack, dual, strict=True))) / count,
        converged=converged,
        equality_multipliers=y,
        row_multipliers=dual[0] - dual[1],
    )  # fmt: skip
    return result, w
