r"""The LQ problem of :mod:`~loader_model.bound.linear` condensed onto the command values alone.

The lifted plant z_{j+1} = A z_j + B u_j + d_j (z_0 = 0) is time invariant, so the node states are
a convolution of the commands with its impulse response g_m = A^m B plus the free response ζ_j
(the road acting alone):

.. math:: z_j = \sum_{i<j} g_{j-1-i} u_i + \zeta_j, \qquad \zeta_{j+1} = A\zeta_j + d_j.

Substituted into the cost (a_total² of Eq. 49, 50 times K_s) the problem is the dense QP

.. math:: \min_u\; u^T H u + 2 f^T u + c \quad \text{s.t.}\quad E u = e,

with H_ij = Σ_{l ≤ N−2−j} g_{l+j−i}ᵀ Q g_l + (g_{j−1−i}ᵀ S for i < j) + R δ_ij (i ≤ j; H is the
cumulative sum along each diagonal of W = G Q Gᵀ, G the impulse response stacked), built in
O(N² n_z) without the N n_z × N lifted matrix. Every bounded signal of
:data:`~loader_model.bound.problem.PATH_SIGNALS` and V̇_p at sub-period i of interval j is
likewise a lower-triangular Toeplitz row in u (its own impulse response h_i[0] = p_u,i,
h_i[m] = p_z,i g_{m−1}) plus a known offset, so all K_s samples of it are one convolution
(:meth:`CondensedProblem.path_values`) and any one of them is a row the solver can take
(:meth:`CondensedProblem.path_rows`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.signal

from loader_model.bound.linear import LinearQuadratic

__all__ = ["CondensedProblem", "condense"]


@dataclass(frozen=True)
class CondensedProblem:
    """The condensed QP in the scaled units of :class:`~loader_model.bound.linear.LinearQuadratic`.

    Attributes
    ----------
    hessian : numpy.ndarray
        (N, N) H (module notes).
    gradient : numpy.ndarray
        (N,) f.
    constant : float
        c, the cost of u = 0.
    end_matrix, end_target : numpy.ndarray
        E (n_e, N) and e: the end condition E u = e.
    path_impulse : numpy.ndarray
        (M, n_p, N) impulse response h of each path signal at each sub-period.
    path_offset : numpy.ndarray
        (N, M, n_p) each path signal's value for u = 0 (deviation from the static value).
    """

    hessian: np.ndarray
    gradient: np.ndarray
    constant: float
    end_matrix: np.ndarray
    end_target: np.ndarray
    path_impulse: np.ndarray
    path_offset: np.ndarray

    @property
    def intervals(self) -> int:
        """N, command values."""
        return self.gradient.size

    def cost(self, u: np.ndarray) -> float:
        """uᵀ H u + 2 fᵀ u + c of scaled commands (K_s a_total² of the linear plant)."""
        return float(u @ self.hessian @ u + 2.0 * self.gradient @ u + self.constant)

    def path_values(self, u: np.ndarray) -> np.ndarray:
        """(N, M, n_p) every path signal at every period (deviation from the static value)."""
        n = self.intervals
        response = scipy.signal.fftconvolve(self.path_impulse, u[None, None, :], axes=2)[..., :n]
        return np.moveaxis(response, 2, 0) + self.path_offset

    def path_rows(self, interval: np.ndarray, sub: np.ndarray, signal: np.ndarray) -> np.ndarray:
        """(len(interval), N) the rows of the given samples: value = row @ u + offset."""
        interval = np.asarray(interval, dtype=int)
        lag = interval[:, None] - np.arange(self.intervals)[None, :]
        impulse = self.path_impulse[np.asarray(sub), np.asarray(signal)]  # (rows, N)
        rows = np.take_along_axis(impulse, np.clip(lag, 0, None), axis=1)
        return np.where(lag >= 0, rows, 0.0)


def _impulse_response(lq: LinearQuadratic, count: int) -> np.ndarray:
    g = np.empty((count, lq.a.shape[0]))
    g[0] = lq.b
    for m in range(1, count):
        g[m] = lq.a @ g[m - 1]
    return g


def _hessian(lq: LinearQuadratic, g: np.ndarray) -> np.ndarray:
    """H of the module notes from the impulse response g (N, n_z)."""
    n = g.shape[0]
    w = g @ lq.q @ g.T  # W[a, b] = g_a' Q g_b
    cross = g @ lq.s  # g_m' S
    h = np.zeros((n, n))
    for d in range(n):
        diagonal = np.cumsum(np.diagonal(w, offset=-d))  # sum_{l<=L} W[l+d, l]
        j = np.arange(d, n)  # H[j-d, j], L = N-2-j
        last = n - 2 - j
        values = np.where(last >= 0, diagonal[np.clip(last, 0, None)], 0.0)
        if d > 0:
            values = values + cross[d - 1]
        h[j - d, j] = values
        h[j, j - d] = values
    h[np.diag_indices(n)] += lq.r
    return h


def condense(lq: LinearQuadratic, hold_periods: int) -> CondensedProblem:
    """The condensed QP of the lifted problem ``lq`` (module notes)."""
    n, nz = lq.d.shape[0], lq.a.shape[0]
    g = _impulse_response(lq, n)
    zeta = np.zeros((n + 1, nz))
    for j in range(n):
        zeta[j + 1] = lq.a @ zeta[j] + lq.d[j]
    # f_i = S' zeta_i + r_i + sum_{k > i} g_{k-1-i}' (Q zeta_k + q_k): one adjoint sweep
    forcing = zeta[:n] @ lq.q + lq.q_lin
    gradient = zeta[:n] @ lq.s + lq.r_lin
    adjoint = np.zeros(nz)
    for i in range(n - 2, -1, -1):
        adjoint = lq.a.T @ adjoint + forcing[i + 1]
        gradient[i] += lq.b @ adjoint
    constant = float(np.sum(zeta[:n] @ lq.q * zeta[:n]) + 2 * np.sum(lq.q_lin * zeta[:n]))
    constant += lq.constant
    end_matrix = (g[::-1] @ lq.end.T).T
    p_z, p_u, p_offset = lq.path
    rows = p_u.size
    impulse = np.empty((rows, n))
    impulse[:, 0] = p_u
    impulse[:, 1:] = (g[: n - 1] @ p_z.T).T
    offset = zeta[:n] @ p_z.T + p_offset  # (N, M n_p)
    return CondensedProblem(
        hessian=_hessian(lq, g),
        gradient=gradient,
        constant=constant,
        end_matrix=end_matrix,
        end_target=-lq.end @ zeta[n],
        path_impulse=impulse.reshape(hold_periods, -1, n),
        path_offset=offset.reshape(n, hold_periods, -1),
    )
