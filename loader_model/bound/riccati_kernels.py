"""The stage loops of :mod:`~loader_model.bound.riccati_qp`, compiled by Numba.

Two loops run over every stage of the course in each interior-point iteration: the linear
recurrence x_{i+1} = A_i x_i + b_i of the forward, adjoint and Riccati sweeps
(:func:`recur`), about 13 sweeps per iteration, and the backward Riccati factorisation in
square-root form (:func:`riccati_factor`), once. With 43 states per stage, their arithmetic is
small matrix products whose cost in NumPy is the call overhead of each product (3-7 µs per
stage); compiled, the loops run without it. Measured on the development machine on the 12 s
problem (N = 1200 stages, the Gauss-Newton QP at the static command): a recurrence 0.64 ms
against 9.9 ms with NumPy, the factorisation 39 ms against 146 ms (under the load of a second
job). ``cache=True`` keeps the machine code beside the module (or in ``NUMBA_CACHE_DIR``), so
the compilation (a few seconds) is paid once per machine.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["recur", "riccati_factor", "riccati_solve"]


@njit(cache=True)
def _recur_vectors(columns: np.ndarray, offsets: np.ndarray, first: np.ndarray) -> np.ndarray:
    n, nz = offsets.shape
    out = np.empty((n + 1, nz))
    out[0] = first
    for i in range(n):
        a = columns[i]
        for r in range(nz):
            out[i + 1, r] = offsets[i, r]
        for k in range(nz):
            xk = out[i, k]
            for r in range(nz):
                out[i + 1, r] += a[k, r] * xk
    return out


@njit(cache=True)
def _recur_columns(columns: np.ndarray, offsets: np.ndarray, first: np.ndarray) -> np.ndarray:
    n, nz, c = offsets.shape
    out = np.empty((n + 1, nz, c))
    out[0] = first
    for i in range(n):
        a = columns[i]
        for r in range(nz):
            for q in range(c):
                out[i + 1, r, q] = offsets[i, r, q]
        for k in range(nz):
            for r in range(nz):
                akr = a[k, r]
                for q in range(c):
                    out[i + 1, r, q] += akr * out[i, k, q]
    return out


def recur(columns: np.ndarray, offsets: np.ndarray, first: np.ndarray) -> np.ndarray:
    """x_0 = ``first``, x_{i+1} = A_i x_i + b_i: all (N + 1, n_z[, c]) x_i, with ``columns``
    (N, n_z, n_z) holding A_iᵀ (C-contiguous) and ``offsets`` (N, n_z[, c]) the b_i."""
    first = np.asarray(first, dtype=float)
    if offsets.ndim == 2:
        return _recur_vectors(columns, np.ascontiguousarray(offsets, dtype=float), first.copy())
    if offsets.shape[2] == 1:
        return _recur_vectors(
            columns, np.ascontiguousarray(offsets[:, :, 0], dtype=float), first[:, 0].copy()
        )[:, :, None]
    return _recur_columns(columns, np.ascontiguousarray(offsets, dtype=float), first.copy())


@njit(cache=True)
def _cholesky(matrix: np.ndarray, out: np.ndarray) -> bool:
    """Lower Cholesky factor of ``matrix`` into ``out``; False where a pivot is not positive."""
    nz = matrix.shape[0]
    for j in range(nz):
        pivot = matrix[j, j]
        for k in range(j):
            pivot -= out[j, k] * out[j, k]
        if not pivot > 0.0:
            return False
        d = np.sqrt(pivot)
        out[j, j] = d
        for i in range(j + 1, nz):
            t = matrix[i, j]
            for k in range(j):
                t -= out[i, k] * out[j, k]
            out[i, j] = t / d
        for i in range(j):
            out[i, j] = 0.0
    return True


@njit(cache=True)
def _cholesky_solve(low: np.ndarray, rhs: np.ndarray, out: np.ndarray) -> None:
    """``out`` = (L Lᵀ)⁻¹ ``rhs`` for the lower factor ``low`` (forward, then back substitution)."""
    nu = low.shape[0]
    for a in range(nu):
        t = rhs[a]
        for b in range(a):
            t -= low[a, b] * out[b]
        out[a] = t / low[a, a]
    for a in range(nu - 1, -1, -1):
        t = out[a]
        for b in range(a + 1, nu):
            t -= low[b, a] * out[b]
        out[a] = t / low[a, a]


@njit(cache=True)
def riccati_factor(stacked: np.ndarray, hessian: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """The backward Riccati recursion in square-root form (:func:`~loader_model.bound.
    riccati_qp._factor`): S̄_j (N, n_u, n_z), the lower Cholesky factors of R̄_j (N, n_u, n_u)
    and a status, −1 when it ran through, else the stage j whose R̄_j was not positive definite.

    ``stacked`` (N, n_z, n_z + n_u) holds [F_j G_j], ``hessian`` (N, n_z + n_u, n_z + n_u) the
    stage Hessians. The cost-to-go P_{j+1} = L Lᵀ is carried as L: M_j = H_j + [F_j G_j]ᵀ L Lᵀ
    [F_j G_j], and the next L is the Cholesky factor of the Schur complement of M_j's command
    block, M_zz − S̄ᵀ R̄⁻¹ S̄ = M_zz − Xᵀ X with X = L_R⁻¹ S̄, or, where round-off made a pivot
    negative, its eigen-decomposition with the negative eigenvalues clipped at zero.
    """
    n, nz = stacked.shape[0], stacked.shape[1]
    nu = stacked.shape[2] - nz
    s_bar, r_low = np.empty((n, nu, nz)), np.zeros((n, nu, nu))
    factor = np.zeros((nz, nz))
    schur = np.empty((nz, nz))
    x = np.empty((nu, nz))
    for j in range(n - 1, -1, -1):
        mapped = np.dot(factor.T, stacked[j])
        m = hessian[j] + np.dot(mapped.T, mapped)
        for a in range(nu):
            for b in range(nz):
                s_bar[j, a, b] = m[nz + a, b]
        if not _cholesky(m[nz:, nz:].copy(), r_low[j]):
            return s_bar, r_low, j
        for b in range(nz):  # X = L_R⁻¹ S̄, column by column
            for a in range(nu):
                t = m[nz + a, b]
                for k in range(a):
                    t -= r_low[j, a, k] * x[k, b]
                x[a, b] = t / r_low[j, a, a]
        for a in range(nz):
            for b in range(nz):
                t = m[a, b]
                for k in range(nu):
                    t -= x[k, a] * x[k, b]
                schur[a, b] = t
        if not _cholesky(schur, factor):
            values, vectors = np.linalg.eigh(0.5 * (schur + schur.T))
            for a in range(nz):
                root = np.sqrt(max(values[a], 0.0))
                for b in range(nz):
                    factor[b, a] = vectors[b, a] * root
    return s_bar, r_low, -1


@njit(cache=True)
def riccati_solve(
    transition: np.ndarray,
    command_map: np.ndarray,
    s_bar: np.ndarray,
    r_low: np.ndarray,
    linear: np.ndarray,
    end: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The LQ step of :func:`~loader_model.bound.riccati_qp._solve` for each column c of
    ``linear`` (N, n_z + n_u, c) and ``end`` (n_z, c): w (N, n_z + n_u, c) and z_N (n_z, c).

    Backwards, with r̃_j = r_j + G_jᵀ p_{j+1}, the feedforward k_j = −R̄_j⁻¹ r̃_j and
    p_j = q_j + F_jᵀ p_{j+1} + S̄_jᵀ k_j; forwards v_j = k_j − R̄_j⁻¹ S̄_j z_j and
    z_{j+1} = F_j z_j + G_j v_j. The closed-loop maps are never formed.
    """
    n, nz, nu = command_map.shape
    columns = linear.shape[2]
    w = np.empty((n, nz + nu, columns))
    z_end = np.empty((nz, columns))
    p_next = np.empty(nz)
    p = np.empty(nz)
    feed = np.empty((n, nu))
    rhs, k = np.empty(nu), np.empty(nu)
    z = np.empty(nz)
    z_new = np.empty(nz)
    for c in range(columns):
        for a in range(nz):
            p_next[a] = end[a, c]
        for j in range(n - 1, -1, -1):
            g = command_map[j]
            for u in range(nu):
                t = linear[j, nz + u, c]
                for a in range(nz):
                    t += g[a, u] * p_next[a]
                rhs[u] = -t
            _cholesky_solve(r_low[j], rhs, k)
            for u in range(nu):
                feed[j, u] = k[u]
            for a in range(nz):
                t = linear[j, a, c]
                for u in range(nu):
                    t += s_bar[j, u, a] * k[u]
                p[a] = t
            f = transition[j]
            for row in range(nz):
                pr = p_next[row]
                for a in range(nz):
                    p[a] += f[row, a] * pr
            for a in range(nz):
                p_next[a] = p[a]
        for a in range(nz):
            z[a] = 0.0
        for j in range(n):
            for u in range(nu):
                t = 0.0
                for a in range(nz):
                    t += s_bar[j, u, a] * z[a]
                rhs[u] = t
            _cholesky_solve(r_low[j], rhs, k)
            for a in range(nz):
                w[j, a, c] = z[a]
            for u in range(nu):
                w[j, nz + u, c] = feed[j, u] - k[u]
            f = transition[j]
            g = command_map[j]
            for row in range(nz):
                acc = 0.0
                for u in range(nu):
                    acc += g[row, u] * w[j, nz + u, c]
                for a in range(nz):
                    acc += f[row, a] * z[a]
                z_new[row] = acc
            for a in range(nz):
                z[a] = z_new[a]
        for a in range(nz):
            z_end[a, c] = z[a]
    return w, z_end
