r"""The Gauss-Newton model of the bound along a simulated trajectory: a condensed QP in the commands.

Along the trajectory of :mod:`~loader_model.bound.trajectory` the plant state and the seat's
weighting-filter state (:mod:`~loader_model.bound.weighting`) stacked, z = (x, ξ), have the
sensitivities Z_k = ∂z_k/∂u (n_z × N) with

.. math:: Z_{k+1} = \begin{pmatrix} A_k & 0 \\ \Gamma C_{s,k} & \Phi \end{pmatrix} Z_k
    + \begin{pmatrix} B_k \\ 0 \end{pmatrix} e_{\lfloor k/M \rfloor}^T ,

swept forward in batched matrix products (only the columns of commands already applied are
non-zero). The weighted seat residuals r_k = K (c ξ_k + d a_k) of a_total² = Σ_k ‖r_k‖² / K_s
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

_ROWS_PER_BLOCK = 250


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
    k_diag = np.diag(weighting.k_factors)
    seat = trajectory.seat()
    residual = weighting.weighted(seat)  # (K_s, axes), k-weighted
    z_sens = np.zeros((nz, n))
    hessian, gradient = np.zeros((n, n)), np.zeros(n)
    n_p = len(PATH_SIGNALS) + 1
    impulse = np.zeros((count, n_p, n))
    block = np.zeros((_ROWS_PER_BLOCK * na, n))
    block_r = np.zeros(_ROWS_PER_BLOCK * na)
    out = np.zeros((na + n_p, nz))
    out[na + n_p - 1, rate] = 1.0
    aug = np.zeros((nz, nz))
    aug[nx:, nx:] = weighting.phi
    used, width = 0, 0
    for k in range(count):
        cols = k // m + 1
        c_seat = linearisation.c[k, seat_rows]
        out[:na, :nx] = k_diag @ weighting.d @ c_seat
        out[:na, nx:] = k_diag @ weighting.c
        out[na : na + n_p - 1, :nx] = linearisation.c[k, path_rows]
        rows = out @ z_sens[:, :cols]
        block[used * na : (used + 1) * na, :cols] = rows[:na]
        block_r[used * na : (used + 1) * na] = residual[k]
        impulse[k, :, :cols] = rows[na:]
        used, width = used + 1, cols
        if used == _ROWS_PER_BLOCK or k == count - 1:
            j = block[: used * na, :width]
            hessian[:width, :width] += j.T @ j
            gradient[:width] += j.T @ block_r[: used * na]
            block[:, :width] = 0.0
            used = 0
        aug[:nx, :nx] = linearisation.a[k]
        aug[nx:, :nx] = weighting.gamma @ c_seat
        z_sens[:, :cols] = aug @ z_sens[:, :cols]
        z_sens[:nx, cols - 1] += linearisation.b[k]
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
