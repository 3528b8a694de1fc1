"""Output-feedback LQR (paper section 3.2, Eq. 41, 42; Lewis 1992; Moerder and Calise 1985).

python-control has no static output feedback design; :func:`output_feedback_lqr` fills that gap and
returns a gain that plugs into python-control interconnections (:meth:`OutputFeedbackResult.controller`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from loader_model.control._checks import (
    finite_matrix,
    gain_mask,
    select_channels,
    spectral_abscissa,
    symmetric_matrix,
)
from loader_model.control._sof_descent import descend

__all__ = ["NoStabilisingGainError", "OutputFeedbackResult", "output_feedback_lqr"]


class NoStabilisingGainError(RuntimeError):
    """No static output feedback u = −K y with the allowed entries was found that stabilises."""

    def __init__(self, message: str, best_abscissa: float, gain: np.ndarray) -> None:
        super().__init__(message)
        self.best_abscissa = best_abscissa
        """Smallest spectral abscissa max Re λ(A − B K C) reached by the search."""
        self.gain = gain
        """The gain that reached it."""


@dataclass(frozen=True)
class OutputFeedbackResult:
    """Optimal static output feedback u = −K y (Eq. 41, 42).

    ``residuals`` are the relative residuals of the three conditions of Eq. 42 in the order
    (Lyapunov equation of P, Lyapunov equation of S, stationarity R K C S Cᵀ − Bᵀ P S Cᵀ on the
    free entries); ``decrement`` is the decrease of J that the last Newton step predicted,
    ½ gᵀ H⁻¹ g / |J| (inf where no Newton step was taken); ``converged`` says that the
    stationarity residual is below ``rtol`` or that this decrement is at most
    ``DECREMENT_RTOL``; ``cost_history`` starts with the cost of the stabilising initial gain.
    """

    gain: np.ndarray
    input_names: tuple[str, ...]
    output_names: tuple[str, ...]
    cost: float
    poles: np.ndarray
    residuals: tuple[float, float, float]
    decrement: float
    iterations: int
    converged: bool
    cost_history: tuple[float, ...]
    initial_gain_source: str
    P: np.ndarray = field(repr=False)
    S: np.ndarray = field(repr=False)

    def controller(self, name: str = "output_feedback") -> Any:
        """The static controller u = −K y as a python-control ``StateSpace`` with named signals."""
        import control

        return control.ss(
            [],
            [],
            [],
            -self.gain,
            inputs=list(self.output_names),
            outputs=list(self.input_names),
            name=name,
        )


def _stabilise(
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    k: np.ndarray,
    mask: np.ndarray,
    max_rounds: int = 200,
) -> np.ndarray:
    """Shifted-system homotopy: lower the spectral abscissa α(A − B K C) below zero.

    With α the current abscissa and shift s = α + δ, the shifted loop A − s I − B K C is
    Hurwitz, so its output-feedback cost (Q = R = X0 = I) is finite and the descent above can
    minimise it; that pushes the slowest poles left. Repeated until α < 0, or raises when α has
    not decreased by 1e-6 (relative to ‖A‖) in 8 consecutive rounds.
    """
    n, m = a.shape[0], b.shape[1]
    eye_n, eye_m = np.eye(n), np.eye(m)
    scale = max(np.linalg.norm(a, 2), 1e-12)
    alpha = spectral_abscissa(a - b @ k @ c)
    best, best_k, stalled = alpha, k, 0
    for _ in range(max_rounds):
        if alpha < 0.0:
            return k
        shift = alpha + max(0.1 * abs(alpha), 1e-3 * scale)
        k = descend(a - shift * eye_n, b, c, eye_n, eye_m, eye_n, k, mask, 1e-6, 20, [], False).gain
        alpha = spectral_abscissa(a - b @ k @ c)
        if alpha < best - 1e-6 * scale:
            best, best_k, stalled = alpha, k, 0
        else:
            stalled += 1
            if stalled >= 8:
                break
    raise NoStabilisingGainError(
        f"no stabilising static output feedback found: the spectral abscissa max Re λ(A − B K C) "
        f"stalled at {best:.6g} (must be < 0); the system may not be stabilisable by static "
        "output feedback with the allowed gain entries",
        best,
        best_k,
    )


def output_feedback_lqr(
    system: Any,
    Q: Any,
    R: Any,
    X0: Any = None,
    *,
    inputs: Sequence[str | int] | None = None,
    outputs: Sequence[str | int] | None = None,
    gain0: Any = None,
    mask: Any = None,
    rtol: float = 1e-9,
    max_iterations: int = 5000,
) -> OutputFeedbackResult:
    r"""Optimal static output feedback u = −K y for ẋ = A x + B u, y = C x (Eq. 41, 42).

    Minimises the quadratic cost averaged over initial states of covariance X0,

    .. math::
        J = \tfrac12 \int_0^\infty (x^T Q x + u^T R u)\,dt = \tfrac12 \operatorname{tr}(P X_0),

    whose stationary points satisfy the three coupled conditions of Eq. 42 with
    :math:`A_c = A - B K C`:

    .. math::
        A_c^T P + P A_c + Q + C^T K^T R K C = 0, \quad
        A_c S + S A_c^T + X_0 = 0, \quad
        R K C S C^T - B^T P S C^T = 0 .

    The last one is the gradient :math:`\partial J / \partial K`.

    Parameters
    ----------
    system
        python-control ``StateSpace`` (its D must vanish on the selected channels) or (A, B, C).
    Q, R
        State weight (n x n, symmetric positive semidefinite), input weight (m x m, positive definite).
    X0
        Initial-state covariance (n x n, symmetric positive semidefinite with C S Cᵀ ≻ 0); default I.
    inputs, outputs
        Names or indices of the control inputs u and fed-back outputs y (default: all).
    gain0
        Initial gain (m x p). If None, or not stabilising, a stabilising gain is searched from it
        (from zero when None) by a shifted-system homotopy; fixed entries keep their values.
    mask
        Boolean m x p array, True where a gain entry is free; others stay at ``gain0``'s value.
    rtol
        Converged when the relative residual of the stationarity condition is below this, or
        when the Newton decrement puts the decrease still to be had below
        ``DECREMENT_RTOL`` |J| (J at its optimum to what its evaluation resolves: the
        residual, a difference of two terms, has a floor that depends on the machine's
        rounding); iterations continue past rtol (to 1e-3 rtol) while they make progress.
    max_iterations
        Limit on the Moerder-Calise iterations.

    Returns
    -------
    OutputFeedbackResult

    Raises
    ------
    NoStabilisingGainError
        When the homotopy cannot push the spectral abscissa below zero.
    ValueError
        For malformed arguments (shape, non-finite, not symmetric/definite, unknown channel).

    Notes
    -----
    Each iteration takes the Newton step of J on the free entries (exact Hessian from the
    differentiated Eq. 42) where the Hessian is positive definite, else the Moerder-Calise step
    (the minimiser over K of the stationarity condition with P, S frozen, a preconditioned
    gradient direction), and backtracks until the closed loop is Hurwitz and the Armijo condition
    holds, so every iterate is stabilising and the cost never increases (up to a rounding
    allowance of 1e-14 |J|). Where J is flat to rounding (the predicted decrease below
    ``DECREMENT_RTOL`` |J|), full Newton steps polish the gain while they halve the
    stationarity residual and raise J by no more than that allowance: the residual's floor
    depends on the machine's rounding, and without this step it stalled at 4e-8 on OpenBLAS's
    SkylakeX kernel where the Haswell kernel reached 2e-13. Without a stabilising initial gain,
    a shifted-system homotopy lowers the spectral abscissa first: with α = max Re λ(A − B K C)
    and s = α + δ, Moerder-Calise steps on the cost of the shifted system A − s I (finite
    there) push the slowest poles left; this is repeated until α < 0, or
    :class:`NoStabilisingGainError` is raised when α stalls.
    """
    a, b, c, d, in_names, out_names = select_channels(system, inputs, outputs)
    n, m, p = a.shape[0], b.shape[1], c.shape[0]
    if np.any(d != 0.0):
        raise ValueError("system must have D = 0 from the selected inputs to the selected outputs")
    q = symmetric_matrix("Q", Q, n, definite=False)
    r = symmetric_matrix("R", R, m, definite=True)
    x0 = np.eye(n) if X0 is None else symmetric_matrix("X0", X0, n, definite=False)
    k = np.zeros((m, p)) if gain0 is None else finite_matrix("gain0", gain0, (m, p))
    mask = gain_mask(mask, (m, p))
    rank = np.linalg.matrix_rank(c)
    if rank < p:
        raise ValueError(f"C must have full row rank {p} (independent outputs); got rank {rank}")
    source = "given" if gain0 is not None else "zero"
    if spectral_abscissa(a - b @ k @ c) >= 0.0:
        k, source = _stabilise(a, b, c, k, mask), "homotopy"
    history: list[float] = []
    found = descend(a, b, c, q, r, x0, k, mask, rtol, max_iterations, history)
    return OutputFeedbackResult(
        gain=found.gain,
        input_names=tuple(in_names),
        output_names=tuple(out_names),
        cost=history[-1],
        poles=np.linalg.eigvals(a - b @ found.gain @ c),
        residuals=found.residuals,
        decrement=found.decrement,
        iterations=found.iterations,
        converged=found.converged,
        cost_history=tuple(history),
        initial_gain_source=source,
        P=found.p,
        S=found.s,
    )
