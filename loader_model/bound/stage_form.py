r"""The stage-form QP of :mod:`~loader_model.bound.riccati_qp`: its data and its sweeps.

.. math:: \min_{v} \sum_{j=0}^{N-1} \tfrac12 w_j^T H_j w_j + g_j^T w_j, \qquad
    w_j = (z_j, v_j),\; z_0 = 0,\; z_{j+1} = F_j z_j + G_j v_j,

    \text{s.t.}\quad l_j \le D_j w_j \le h_j,\quad v_{lo,j} \le v_j \le v_{hi,j},\quad
    E z_N = e

:class:`StageQP` holds it (n_u inputs per stage, n_z states); the forward sweep of the dynamics
(:func:`forward`) and the adjoint sweep (:func:`adjoint`) are the products with the condensed
form's maps that the interior point uses instead of forming them; :func:`condensed_gradient` and
:func:`mean_condensed_curvature` are the condensed form's gradient and mean curvature, exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from loader_model.bound.riccati_kernels import recur

__all__ = ["StageQP", "adjoint", "condensed_gradient", "forward", "mean_condensed_curvature"]


@dataclass(frozen=True)
class StageQP:
    """The QP of the module notes (n_u inputs per stage).

    Attributes
    ----------
    transition, command_map : numpy.ndarray
        (N, n_z, n_z) F_j and (N, n_z, n_u) G_j.
    hessian, gradient : numpy.ndarray
        (N, n_z + n_u, n_z + n_u) H_j and (N, n_z + n_u) g_j, in w_j = (z_j, v_j).
    rows, row_low, row_high : numpy.ndarray
        (N, n_r, n_z + n_u) D_j and (N, n_r) l_j, h_j (finite).
    v_low, v_high : numpy.ndarray
        (N, n_u) the bounds on v_j.
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

    @property
    def inputs(self) -> int:
        """n_u, inputs per stage."""
        return self.command_map.shape[2]

    @property
    def states(self) -> int:
        """n_z, states per stage."""
        return self.command_map.shape[1]

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
    def contiguous_command_map(self) -> np.ndarray:
        """(N, n_z, n_u) G_j, C-contiguous (the compiled Riccati sweeps read it)."""
        return np.ascontiguousarray(self.command_map, dtype=float)

    @cached_property
    def stacked(self) -> np.ndarray:
        """(N, n_z, n_z + n_u) [F_j G_j], the dynamics' map of w_j."""
        return np.ascontiguousarray(np.concatenate([self.transition, self.command_map], axis=2))


def _recur(columns: np.ndarray, offsets: np.ndarray, first: np.ndarray) -> np.ndarray:
    """x_0 = ``first``, x_{i+1} = A_i x_i + b_i: all (N + 1, n_z[, c]) x_i, with ``columns``
    (N, n_z, n_z) holding A_iᵀ and ``offsets`` (N, n_z[, c]) the b_i (compiled:
    :func:`~loader_model.bound.riccati_kernels.recur`; in NumPy it took 3-7 µs per stage of 43
    states, and CasADi's compiled mapaccum of the same step 3.6 µs)."""
    return recur(columns, offsets, first)


def forward(qp: StageQP, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """w_j (N, n_z + n_u) and z_N of the commands ``v`` (N, n_u)."""
    n, nz = qp.transition.shape[:2]
    z = _recur(qp.transposed, np.einsum("jau,ju->ja", qp.command_map, v), np.zeros(nz))
    return np.concatenate([z[:n], v], axis=1), z[n]


def adjoint(qp: StageQP, h: np.ndarray, h_end: np.ndarray) -> np.ndarray:
    """The condensed gradient Tᵀ h (N, n_u) of stage vectors h (N, n_z + n_u) and h_end on z_N."""
    nz = qp.states
    # costate_j = h_{j,z} + F_jᵀ costate_{j+1}, swept from costate_N = h_end
    costate = _recur(qp.reversed, h[::-1, :nz], h_end)[::-1]
    return h[:, nz:] + np.einsum("jau,ja->ju", qp.command_map, costate[1:])


def condensed_gradient(qp: StageQP) -> np.ndarray:
    """(N n_u,) the gradient of the cost in the commands at v = 0 (the condensed form's q),
    stage by stage."""
    return adjoint(qp, qp.gradient, np.zeros(qp.states)).ravel()


def mean_condensed_curvature(qp: StageQP) -> float:
    """The mean diagonal entry of the condensed Hessian Tᵀ H T, exactly: its trace is
    Σ_j tr(H_j Cov w_j) for unit white v, with Cov z_{j+1} = F_j Cov z_j F_jᵀ + G_j G_jᵀ (the
    scale of a Levenberg-Marquardt damping term, as the dense form's mean of diag P)."""
    n, nz = qp.transition.shape[:2]
    covariance, trace = np.zeros((nz, nz)), 0.0
    for j in range(n):
        trace += float(np.sum(qp.hessian[j, :nz, :nz] * covariance))
        trace += float(np.trace(qp.hessian[j, nz:, nz:]))
        f, g = qp.transition[j], qp.command_map[j]
        covariance = f @ covariance @ f.T + g @ g.T
    return trace / (n * qp.inputs)
