"""Building blocks of the H2 design NLP: gain unknowns, Cholesky-factor unknowns, warm starts.

See :mod:`loader_model.control.h2_design` for the formulation and why it is used.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
from scipy.linalg import cholesky, solve_continuous_lyapunov

from loader_model.control.design_plant import DesignPlant
from loader_model.control.h2_cost import closed_loop

__all__ = ["PlantBlock", "gain_expression"]


def _tril(n: int) -> list[tuple[int, int]]:
    return [(i, j) for j in range(n) for i in range(j, n)]


def _lower(vector: ca.SX, n: int) -> ca.SX:
    matrix = ca.SX(n, n)
    for index, (i, j) in enumerate(_tril(n)):
        matrix[i, j] = vector[index]
    return matrix


def _vech(matrix: ca.SX, n: int) -> ca.SX:
    return ca.vertcat(*[matrix[i, j] for i, j in _tril(n)])


def _factor(matrix: np.ndarray) -> np.ndarray:
    """vech of the Cholesky factor of a symmetric PSD matrix (tiny jitter for singular ones)."""
    n = matrix.shape[0]
    jitter = 1e-12 * max(np.trace(matrix), 1e-300) * np.eye(n)
    lower = cholesky(0.5 * (matrix + matrix.T) + jitter, lower=True)
    return np.array([lower[i, j] for i, j in _tril(n)])


def gain_expression(gain0: np.ndarray, mask: np.ndarray) -> tuple[ca.SX, ca.SX]:
    """Unknowns k (the free entries, row-major) and K with the fixed entries of gain0."""
    free = np.argwhere(mask)
    k_free = ca.SX.sym("k", len(free))
    k = ca.SX(ca.DM(np.where(mask, 0.0, gain0)))
    for index, (i, j) in enumerate(free):
        k[i, j] = k_free[index]
    return k_free, k


class PlantBlock:
    """One plant in states scaled by its warm-start certificate (x̃ = x / d, d = sqrt(diag Π0):
    a similarity, so poles and H2 norms are unchanged), with unknowns and constraint expressions.

    The warm start must meet the margin (A_cl + σ I Hurwitz); its certificate Π0 and Gramian P0
    are then exact solutions, and their Cholesky factors the initial guesses.
    """

    def __init__(
        self, plant: DesignPlant, gain0: np.ndarray, margin: float, epsilon: float
    ) -> None:
        a_cl = closed_loop(plant, gain0)[0]
        n = self.n = a_cl.shape[0]
        bb = plant.B_w @ plant.B_w.T
        rhs = bb + epsilon * max(np.trace(bb) / n, 1e-300) * np.eye(n)
        certificate = solve_continuous_lyapunov(a_cl + margin * np.eye(n), -rhs)
        scale = np.sqrt(np.diag(certificate))
        d, d_inv = np.diag(scale), np.diag(1.0 / scale)
        self.plant, self.margin = plant, margin
        self.A, self.B_u, self.B_w = d_inv @ plant.A @ d, d_inv @ plant.B_u, d_inv @ plant.B_w
        self.C_y, self.C_z, self.C_e = plant.C_y @ d, plant.C_z @ d, plant.C_e @ d
        self.rhs = d_inv @ rhs @ d_inv
        # Row scaling of the two equalities by the size of their constant terms.
        self.row_scale = (np.linalg.norm(self.B_w @ self.B_w.T), np.linalg.norm(self.rhs))
        self.l_cert = ca.SX.sym(f"Lc_{plant.name}", n * (n + 1) // 2)
        self.l_cost = ca.SX.sym(f"Lp_{plant.name}", n * (n + 1) // 2)
        self.guess_cert = _factor(d_inv @ certificate @ d_inv)
        self.guess_cost = _factor(d_inv @ solve_continuous_lyapunov(a_cl, -bb) @ d_inv)

    def terms(self, k: ca.SX, r: np.ndarray) -> tuple[ca.SX, ca.SX, ca.SX, ca.SX, ca.SX]:
        """Equalities (Gramian, certificate; vech), weighted cost, var(u), var(e), tr(Π) / n."""
        n, kc = self.n, k @ self.C_y
        a_cl = self.A - self.B_u @ kc
        a_sigma = a_cl + self.margin * np.eye(n)
        low_p, low_c = _lower(self.l_cost, n), _lower(self.l_cert, n)
        p, pi = low_p @ low_p.T, low_c @ low_c.T
        equalities = ca.vertcat(
            _vech(a_cl @ p + p @ a_cl.T + self.B_w @ self.B_w.T, n) / self.row_scale[0],
            _vech(a_sigma @ pi + pi @ a_sigma.T + self.rhs, n) / self.row_scale[1],
        )
        c_z = self.C_z - self.plant.D_zu @ kc
        u_cov = kc @ p @ kc.T
        cost = self.plant.weight * (ca.trace(c_z @ p @ c_z.T) + ca.trace(r @ u_cov))
        c_e = self.C_e - self.plant.D_eu @ kc
        return (
            equalities,
            cost,
            ca.diag(u_cov),
            ca.diag(c_e @ p @ c_e.T),
            ca.sumsqr(self.l_cert) / n,
        )
