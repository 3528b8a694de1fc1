"""Lyapunov equations of one closed loop solved from one real Schur form (Bartels-Stewart).

Output-feedback design solves several Lyapunov equations with the same closed-loop matrix (P, S
and their directional derivatives); factoring once and calling LAPACK ``dtrsyl`` for each right
side is several times faster than ``scipy.linalg.solve_continuous_lyapunov`` per equation.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import schur
from scipy.linalg.lapack import dtrsyl

__all__ = ["SchurLyapunov"]


class SchurLyapunov:
    """Solver of A X + X Aᵀ = Y and Aᵀ X + X A = Y for one real square matrix A.

    ``abscissa`` is max Re λ(A), read from the diagonal of LAPACK's standardised real Schur
    form (its 2 x 2 blocks have equal diagonal entries, the real part of their eigenvalues).
    """

    def __init__(self, a: np.ndarray) -> None:
        self.t, self.u = schur(a, output="real")
        self.abscissa = float(np.max(np.diag(self.t)))

    def _solve(self, y: np.ndarray, trana: str, tranb: str) -> np.ndarray:
        x, scale, info = dtrsyl(self.t, self.t, self.u.T @ y @ self.u, trana=trana, tranb=tranb)
        if info < 0:
            raise np.linalg.LinAlgError(f"dtrsyl failed with info = {info}")
        x = self.u @ x @ self.u.T / scale
        return 0.5 * (x + x.T)

    def controllability(self, y: np.ndarray) -> np.ndarray:
        """X with A X + X Aᵀ = y (y symmetric)."""
        return self._solve(y, "N", "T")

    def observability(self, y: np.ndarray) -> np.ndarray:
        """X with Aᵀ X + X A = y (y symmetric)."""
        return self._solve(y, "T", "N")
