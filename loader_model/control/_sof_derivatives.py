"""Cost, residuals and exact Hessian of the output-feedback LQR conditions (Eq. 42).

Helpers of :mod:`loader_model.control.output_feedback`; every closed-loop Lyapunov equation is
solved from one real Schur form (:class:`~loader_model.control._lyapunov.SchurLyapunov`).
"""

from __future__ import annotations

import numpy as np

from loader_model.control._lyapunov import SchurLyapunov

__all__ = ["evaluate", "hessian", "residuals"]


def evaluate(
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    k: np.ndarray,
    q: np.ndarray,
    r: np.ndarray,
    x0: np.ndarray,
    need_s: bool = True,
) -> tuple[float, np.ndarray, np.ndarray | None, np.ndarray, SchurLyapunov] | None:
    """Cost, P, S and Schur solver of the closed loop A − B K C; None when it is not Hurwitz."""
    solver = SchurLyapunov(a - b @ k @ c)
    if solver.abscissa >= 0.0:
        return None
    weight = q + c.T @ k.T @ r @ k @ c
    p = solver.observability(-weight)
    s = solver.controllability(-x0) if need_s else None
    return 0.5 * float(np.sum(p * x0)), p, s, weight, solver


def residuals(
    a_c: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    k: np.ndarray,
    r: np.ndarray,
    x0: np.ndarray,
    p: np.ndarray,
    s: np.ndarray,
    weight: np.ndarray,
    mask: np.ndarray,
) -> tuple[tuple[float, float, float], np.ndarray]:
    def relative(residual: np.ndarray, *terms: np.ndarray) -> float:
        return float(np.linalg.norm(residual) / max(sum(np.linalg.norm(t) for t in terms), 1e-300))

    norm_a = np.linalg.norm(a_c)
    r_p = relative(a_c.T @ p + p @ a_c + weight, norm_a * p, norm_a * p, weight)
    r_s = relative(a_c @ s + s @ a_c.T + x0, norm_a * s, norm_a * s, x0)
    left, right = r @ k @ c @ s @ c.T, b.T @ p @ s @ c.T
    return (r_p, r_s, relative(np.where(mask, left - right, 0.0), left, right)), left - right


def hessian(
    b: np.ndarray,
    c: np.ndarray,
    k: np.ndarray,
    r: np.ndarray,
    p: np.ndarray,
    s: np.ndarray,
    solver: SchurLyapunov,
    mask: np.ndarray,
) -> np.ndarray:
    """Exact Hessian of J on the free entries: the derivative of the gradient along each entry.

    Along a gain direction E, with dA_c = −B E C, dP and dS solve the differentiated Lyapunov
    equations of Eq. 42 and dG = R E C S Cᵀ + R K C dS Cᵀ − Bᵀ dP S Cᵀ − Bᵀ P dS Cᵀ.
    """
    free = np.argwhere(mask.T)[:, ::-1]  # column-major order, matching ravel(order="F")
    columns = []
    css = c @ s @ c.T
    for i, j in free:
        e = np.zeros_like(k)
        e[i, j] = 1.0
        d_a = -b @ e @ c
        term = c.T @ e.T @ r @ k @ c
        d_p = solver.observability(-(d_a.T @ p + p @ d_a + term + term.T))
        d_s = solver.controllability(-(d_a @ s + s @ d_a.T))
        d_g = r @ e @ css + r @ k @ c @ d_s @ c.T - b.T @ (d_p @ s + p @ d_s) @ c.T
        columns.append(d_g.ravel(order="F")[mask.ravel(order="F")])
    hessian = np.array(columns).T
    return 0.5 * (hessian + hessian.T)
