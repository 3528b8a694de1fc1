r"""The Gauss-Newton model of the bound along a simulated trajectory: a condensed QP in the commands.

Along the trajectory of :mod:`~loader_model.bound.trajectory` the plant state and the seat's
weighting-filter state (:mod:`~loader_model.bound.weighting`) stacked, z = (x, ξ), have the
sensitivities Z_k = ∂z_k/∂u (n_z × N) with

.. math:: Z_{k+1} = \begin{pmatrix} A_k & 0 \\ \Gamma C_{s,k} & \Phi \end{pmatrix} Z_k
    + \begin{pmatrix} B_k \\ 0 \end{pmatrix} e_{\lfloor k/M \rfloor}^T ,

swept forward in blocks of :data:`_INTERVALS_PER_BLOCK` command intervals: inside a block only
the transition products T_b = Ã_{k0+b−1} ⋯ Ã_{k0} (n_z × n_z) and the block's own commands'
columns are swept period by period, and every row of the commands applied before it is one
matrix product with Z_{k0} (only the columns of commands already applied are non-zero). On the
6 s paper course it gave the period-by-period sweep's model to 4e-14 in 4.4 s instead of 28 s
(measured on the development machine under load).

The weighted seat residuals r_k = K (c ξ_k + d a_k) of a_total² = Σ_k ‖r_k‖² / K_s
(Eq. 49, 50) have rows J_k = K (c Ξ_k + d C_{s,k} S_k), so the Gauss-Newton model of a_total²
about the commands v (scaled by the pump's limit) is ½ v'ᵀ P v' + qᵀ v' + const with
P = 2 Jᵀ J / K_s and q = 2 Jᵀ r / K_s − P v: the form of :mod:`~loader_model.bound.condensed`,
whose constraint generation (:func:`~loader_model.bound.constrained.generate_constraints`)
solves it. Every path sample (:data:`~loader_model.bound.problem.PATH_SIGNALS` and V̇_p) is
linear in v' with the row C_{p,k} S_k (all K_s × 4 × N kept: 460 MB for 12 s), the end
condition with C_T S_{K_s}.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.bound.problem import PATH_SIGNALS, BoundProblem
from loader_model.bound.trajectory import Linearisation, Trajectory
from loader_model.bound.weighting import SeatWeighting
from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES

__all__ = ["GaussNewtonModel", "gauss_newton_model"]

#: Command intervals per block of the sweep (module notes).
_INTERVALS_PER_BLOCK = 10


@dataclass(frozen=True)
class GaussNewtonModel:
    """The condensed Gauss-Newton QP in scaled commands v = u / u_scale (module notes).

    Has the attributes and methods :func:`~loader_model.bound.constrained.generate_constraints`
    reads from a :class:`~loader_model.bound.condensed.CondensedProblem`.
    """

    hessian: np.ndarray
    gradient: np.ndarray
    end_matrix: np.ndarray
    end_target: np.ndarray
    path_impulse: np.ndarray  # (K_s, n_p, N) rows
    path_offset: np.ndarray  # (N, M, n_p) value at v' = 0 (deviation from static)
    hold_periods: int

    @property
    def intervals(self) -> int:
        """N, command values."""
        return self.gradient.size

    def path_values(self, v: np.ndarray) -> np.ndarray:
        """(N, M, n_p) the linearised path signals (deviation from static) at commands ``v``."""
        values = np.einsum("kpn,n->kp", self.path_impulse, v)
        return values.reshape(self.path_offset.shape) + self.path_offset

    def path_rows(self, interval: np.ndarray, sub: np.ndarray, signal: np.ndarray) -> np.ndarray:
        """(rows, N) the rows of the given samples: value = row @ v + offset."""
        k = np.asarray(interval) * self.hold_periods + np.asarray(sub)
        return self.path_impulse[k, np.asarray(signal)]


def gauss_newton_model(
    problem: BoundProblem,
    trajectory: Trajectory,
    linearisation: Linearisation,
    weighting: SeatWeighting,
    u_scale: float,
) -> GaussNewtonModel:
    """The Gauss-Newton model about ``trajectory`` (module notes); v in units of ``u_scale``."""
    count, m, n = problem.periods, problem.hold_periods, problem.intervals
    nx, nf, na = len(STATE_NAMES), weighting.order, len(weighting.axes)
    nz = nx + nf
    seat_rows = [OUTPUT_NAMES.index(s) for s in weighting.signals]
    path_rows = [OUTPUT_NAMES.index(s) for s in PATH_SIGNALS]
    rate = STATE_NAMES.index("Vd_p")
    residual = weighting.weighted(trajectory.seat())  # (K_s, axes), k-weighted
    n_p = len(PATH_SIGNALS) + 1
    n_out = na + n_p
    k_diag = np.diag(weighting.k_factors)
    z_sens = np.zeros((nz, n))
    hessian, gradient = np.zeros((n, n)), np.zeros(n)
    impulse = np.zeros((count, n_p, n))
    block = m * _INTERVALS_PER_BLOCK
    for k0 in range(0, count, block):
        size = min(block, count - k0)
        ks = np.arange(k0, k0 + size)
        c_seat = linearisation.c[ks][:, seat_rows]  # (size, axes, nx)
        # the stage maps: outputs (seat residual rows, path signals, V̇_p) and the transition
        out = np.zeros((size, n_out, nz))
        out[:, :na, :nx] = np.einsum("ij,jk,bkl->bil", k_diag, weighting.d, c_seat)
        out[:, :na, nx:] = k_diag @ weighting.c
        out[:, na : n_out - 1, :nx] = linearisation.c[ks][:, path_rows]
        out[:, n_out - 1, rate] = 1.0
        aug = np.zeros((size, nz, nz))
        aug[:, :nx, :nx] = linearisation.a[ks]
        aug[:, nx:, :nx] = np.einsum("ij,bjk->bik", weighting.gamma, c_seat)
        aug[:, nx:, nx:] = weighting.phi
        # T_b = aug_{k0+b-1} ... aug_{k0} and the block's own commands' sensitivities L_b
        first, width = k0 // m, (k0 + size - 1) // m + 1  # columns: old < first <= new < width
        local = np.zeros((nz, width - first))
        transition = np.eye(nz)
        mapped = np.empty((size, n_out, nz))
        local_rows = np.empty((size, n_out, width - first))
        for b in range(size):
            mapped[b] = out[b] @ transition
            local_rows[b] = out[b] @ local
            transition = aug[b] @ transition
            local = aug[b] @ local
            local[:nx, (k0 + b) // m - first] += linearisation.b[k0 + b]
        rows = np.zeros((size, n_out, width))
        rows[:, :, :first] = (mapped.reshape(-1, nz) @ z_sens[:, :first]).reshape(size, n_out, -1)
        rows[:, :, first:width] = local_rows
        jac = rows[:, :na].reshape(size * na, width)
        hessian[:width, :width] += jac.T @ jac
        gradient[:width] += jac.T @ residual[ks].ravel()
        impulse[ks, :, :width] = rows[:, na:]
        z_sens[:, :first] = transition @ z_sens[:, :first]
        z_sens[:, first:width] = local
    scale = u_scale
    hessian *= 2.0 * scale**2 / count
    gradient *= 2.0 * scale / count
    impulse *= scale
    v = trajectory.command / scale
    end_rows, end_values = [], []
    targets = problem.end_targets
    for name, target in targets.items():
        if name in STATE_NAMES:
            row = z_sens[STATE_NAMES.index(name)]
            value = trajectory.states[-1, STATE_NAMES.index(name)]
        else:
            row = linearisation.c[count, OUTPUT_NAMES.index(name)] @ z_sens[:nx]
            value = trajectory.outputs[-1, OUTPUT_NAMES.index(name)]
        end_rows.append(row * scale)
        end_values.append(target - value)
    end_matrix = np.array(end_rows)
    static = np.array([*(problem.plant.output(s) for s in PATH_SIGNALS), 0.0])
    current = (trajectory.path() - static).reshape(n, m, n_p)
    shift = np.einsum("kpn,n->kp", impulse, v).reshape(n, m, n_p)
    return GaussNewtonModel(
        hessian=hessian,
        gradient=gradient - hessian @ v,
        end_matrix=end_matrix,
        end_target=np.array(end_values) + end_matrix @ v,
        path_impulse=impulse,
        path_offset=current - shift,
        hold_periods=m,
    )
