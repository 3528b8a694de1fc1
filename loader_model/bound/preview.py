r"""LQ control with road preview on the linear bound's plant and cost: the step from causal to clairvoyant.

The design model is the linear bound's (:mod:`~loader_model.bound.linear`): the linearised plant
sampled exactly at h = 1 ms with the ISO 2631 filter states (:mod:`~loader_model.bound.weighting`),
lifted to the command grid of M periods, with the cost a_total² of Eq. 49, 50 and the same command
weight. With z_j the lifted state at node j, the stage cost and dynamics are

.. math::

    \ell_j = z_j^T Q z_j + 2 z_j^T S u_j + R u_j^2 + 2 q_j^T z_j + 2 r_j u_j + c_j, \qquad
    z_{j+1} = A z_j + B u_j + d_j,

where (d_j, q_j, r_j) are linear in the road samples of interval j (both axles, the rear one the
front one's road a wheelbase b later, :mod:`~loader_model.simulation.travel`). The infinite-horizon
optimum with the road known is u_j = −K z_j + u_ff,j with P the stabilising solution of the
discrete algebraic Riccati equation with cross term S, H = R + BᵀPB, K = H⁻¹(Sᵀ + BᵀPA),
A_cl = A − BK. The value's linear term p_j obeys p_j = A_clᵀ(P d_j + p_{j+1}) + q_j − Kᵀ r_j, so

.. math::

    u_{ff,j} = -H^{-1}\Big[r_j + B^T P d_j + \sum_{m \ge 1} \big(g_m^T P d_{j+m}
    + g_{m-1}^T q_{j+m} - (K g_{m-1})\, r_{j+m}\big)\Big], \qquad g_m = A_{cl}^m B,

the feedforward gain on the road of the interval m ahead being H⁻¹ Bᵀ (A_clᵀ)^m P (the standard
preview gain) plus the cost's road cross terms. A preview of length L (metres ahead of the front
axle at the travel speed v) knows the road of intervals whose end lies within L / v: the sum is
truncated at n = ⌊L / (v M h)⌋ intervals for the front axle's terms and, with the wheelbase
preview (the road the front axle has crossed, which the rear axle meets b / v later),
n = ⌊(L + b) / (v M h)⌋ for the rear axle's. L = 0 without the wheelbase preview is the plain LQR.

The cost alone has no stabilising DARE solution: the weighted seat accelerations vanish for a
steady boom displacement (the transfer from u to the cost has zeros at z = 1), so the optimum lets
the boom drift (closed-loop poles at 1, commands of 1000 × the pump's limit for the plain LQR on the
paper course) and the symplectic pencil has eigenvalues on the unit circle (scipy refuses it on a
3 s course). In place of the bound's end condition (stroke position, pump displacement and rate back
at rest) the law weights those signals C_T z in every stage, Q_drift = ε tr(Q)/n_z C_TᵀC_T with
ε = :data:`DRIFT_WEIGHT`: on the paper course (9 km/h, empty) ε = 1 costs 0.3 % of a_total at 4 m
preview and brings the command's peak from 11 to 2.2 × the pump's limit.

The feedback is on the full lifted state (plant and filter states): this is a design bound on what
preview buys on the linear plant, not a sensor-realistic controller
(:mod:`~loader_model.bound.preview_report` runs it on the machine with an estimator).
:func:`evaluate_preview` reports the bound's end residual, which the law does not impose.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from loader_model.bound.linear import LinearQuadratic, _sampled_plant, evaluate, linear_quadratic
from loader_model.bound.problem import BoundProblem
from loader_model.bound.weighting import seat_weighting
from loader_model.plant.layout import SKID_STEER, PlantLayout

__all__ = [
    "FRONT_COLUMNS",
    "PreviewDesign",
    "PreviewRun",
    "evaluate_preview",
    "front_columns",
    "preview_design",
    "preview_intervals",
]


def front_columns(layout: PlantLayout) -> tuple[int, ...]:
    """Exogenous columns of ``layout`` read with the front axle's preview (the front axle's road
    w and ẇ, and the disturbance forces); the others are the rear axle's.

    Raises
    ------
    ValueError
        For a machine without exactly two axles (the preview knows one wheelbase).
    """
    axles = layout.machine.axles
    if len(axles) != 2:
        raise ValueError(
            f"machine {layout.name!r} has {len(axles)} axles ({', '.join(axles)}); the preview "
            "law previews the front axle's road and the rear one's a wheelbase later: allowed: "
            "a machine with two axles"
        )
    rear = {f"{kind}_{axles[1]}{axis}" for kind in ("w", "wd") for axis in "xy"}
    return tuple(k for k, name in enumerate(layout.exogenous_names) if name not in rear)


#: The skid-steer's :func:`front_columns` (w_A, ẇ_A and the disturbance forces; the others,
#: w_B and ẇ_B, are the rear axle's: :data:`~loader_model.plant.plant.EXOGENOUS_NAMES`).
FRONT_COLUMNS: tuple[int, ...] = front_columns(SKID_STEER)
#: Stage weight on the bound's end-condition signals (stroke position, pump displacement and rate)
#: relative to the mean diagonal of Q (module notes: the cost alone has zeros at z = 1).
DRIFT_WEIGHT = 1.0


@dataclass(frozen=True, eq=False)
class PreviewDesign:
    """The preview LQ law on one bound problem, in the lifted problem's scaled units.

    Attributes
    ----------
    lq : LinearQuadratic
        The lifted problem (its road terms summed over both axles).
    riccati : numpy.ndarray
        P, the stabilising DARE solution.
    gain : numpy.ndarray
        K (u = −K z + u_ff).
    closed_loop : numpy.ndarray
        A_cl = A − B K.
    road_terms : tuple of tuple of numpy.ndarray
        (d, q, r) of the front axle's and of the rear axle's road, each (N, nz), (N, nz), (N,).
    state_scale : numpy.ndarray
        T, the lifted problem's state scales (z = T⁻¹ × physical deviation).
    state_weight : numpy.ndarray
        The stage weight Q + Q_drift the DARE solved with (:data:`DRIFT_WEIGHT`).
    road_path : tuple of numpy.ndarray
        The front axle's and the rear axle's road in the path signals' offsets, each (N, M n_p)
        as the third entry of :attr:`~loader_model.bound.linear.LinearQuadratic.path` (their sum).
    """

    lq: LinearQuadratic
    riccati: np.ndarray
    gain: np.ndarray
    closed_loop: np.ndarray
    road_terms: tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...]
    state_scale: np.ndarray
    state_weight: np.ndarray
    road_path: tuple[np.ndarray, ...] = ()

    @property
    def hessian(self) -> float:
        """H = R + BᵀPB."""
        return float(self.lq.r + self.lq.b @ self.riccati @ self.lq.b)

    def feedforward(self, intervals: tuple[int, int]) -> np.ndarray:
        """u_ff,j (scaled, N values) with (front, rear) previews of ``intervals`` (module notes)."""
        n, nz = self.lq.d.shape
        total = np.zeros(n)
        g = [self.lq.b]
        for count, (d, q, r) in zip(intervals, self.road_terms, strict=True):
            while len(g) <= count:
                g.append(self.closed_loop @ g[-1])
            for m in range(count):
                coef_d = self.riccati @ g[m]
                coef_q = g[m - 1] if m else np.zeros(nz)
                coef_r = -(self.gain @ g[m - 1]) if m else 1.0
                rows = slice(m, n)
                total[: n - m] += d[rows] @ coef_d + q[rows] @ coef_q + coef_r * r[rows]
        return -total / self.hessian


@dataclass(frozen=True)
class PreviewRun:
    """The preview law on the linear plant over one course.

    Attributes
    ----------
    preview_m : float
        L, metres ahead of the front axle.
    intervals : tuple of int
        Command intervals previewed for the front and the rear axle.
    command : numpy.ndarray
        Command deviation from u0 per interval in m³/rev.
    a_total_m_s2 : float
        a_total (Eq. 50) of the linear plant, sample by sample as the bound's.
    end_residual : numpy.ndarray
        The bound's end condition C_T z_N (scaled; the preview law does not impose it).
    states : numpy.ndarray
        (N + 1, nz) lifted states z_j at the nodes (scaled).
    """

    preview_m: float
    intervals: tuple[int, int]
    command: np.ndarray
    a_total_m_s2: float
    end_residual: np.ndarray
    states: np.ndarray


def _scaling(problem: BoundProblem) -> tuple[np.ndarray, ...]:
    """F0, F1 of the sampled plant, the state scales T of :func:`linear_quadratic` (the peaks
    of the free response to the whole road, recomputed the same way) and the path signals' maps
    (state, road)."""
    az, _, f0, f1, *_, path_z, path_w = _sampled_plant(problem, seat_weighting(problem.period_s))
    w = problem.exogenous
    whole = w[:-1] @ f0.T + w[1:] @ f1.T
    response, peak = np.zeros(az.shape[0]), np.zeros(az.shape[0])
    for k in range(problem.periods):
        response = az @ response + whole[k]
        peak = np.maximum(peak, np.abs(response))
    return f0, f1, np.maximum(peak, 1e-12 * max(peak.max(), 1e-30)), path_z, path_w


def _road_terms(
    problem: BoundProblem, lq: LinearQuadratic, columns: tuple[int, ...], scaling: tuple
) -> tuple[np.ndarray, ...]:
    """(d, q, r) of the road in ``columns`` lifted as :func:`linear_quadratic` lifts the whole
    road, in its scaling, and its path signals' offsets (N, M n_p)."""
    f0, f1, t, path_z, path_w = scaling
    path_s = path_z * t[None, :]
    a_s, _, h_s, _, gw, *_ = lq.sample
    w = problem.exogenous
    part = np.zeros_like(w)
    part[:, list(columns)] = w[:, list(columns)]
    d_s = (part[:-1] @ f0.T + part[1:] @ f1.T) / t[None, :]
    m, n, nz = problem.hold_periods, problem.intervals, a_s.shape[0]
    p_i, q_i = np.eye(nz), np.zeros(nz)
    omega, q_lin, r_lin = np.zeros((n, nz)), np.zeros((n, nz)), np.zeros(n)
    offsets = []
    for i in range(m):
        offsets.append(omega @ path_s.T + part[i : problem.periods : m] @ path_w.T)
        hp, hq = h_s @ p_i, h_s @ q_i
        c = omega @ h_s.T + part[i : problem.periods : m] @ gw.T
        q_lin += c @ hp
        r_lin += c @ hq
        p_i, q_i = a_s @ p_i, a_s @ q_i + lq.sample[1]
        omega = omega @ a_s.T + d_s[i : problem.periods : m]
    return omega, q_lin, r_lin, np.hstack(offsets)


def preview_design(problem: BoundProblem, drift_weight: float = DRIFT_WEIGHT) -> PreviewDesign:
    """The preview LQ law (module notes) on ``problem``'s linear plant and cost."""
    if not np.isfinite(drift_weight) or drift_weight <= 0.0:
        raise ValueError(f"drift_weight must be > 0; got {drift_weight!r}")
    columns = front_columns(problem.layout)
    lq = linear_quadratic(problem)
    b = lq.b[:, None]
    r = np.array([[lq.r]])
    drift = drift_weight * np.trace(lq.q) / lq.q.shape[0] * lq.end.T @ lq.end
    p = scipy.linalg.solve_discrete_are(lq.a, b, lq.q + drift, r, s=lq.s[:, None])
    p = 0.5 * (p + p.T)
    gain = np.linalg.solve(r + b.T @ p @ b, b.T @ p @ lq.a + lq.s[None, :]).ravel()
    scaling = _scaling(problem)
    front = _road_terms(problem, lq, columns, scaling)
    rear_columns = tuple(c for c in range(problem.exogenous.shape[1]) if c not in columns)
    rear = _road_terms(problem, lq, rear_columns, scaling)
    closed = lq.a - np.outer(lq.b, gain)
    return PreviewDesign(
        lq, p, gain, closed, (front[:3], rear[:3]), scaling[2], lq.q + drift, (front[3], rear[3])
    )


def preview_intervals(
    problem: BoundProblem, preview_m: float, speed_m_s: float, wheelbase_m: float, *,
    wheelbase_preview: bool = True,
) -> tuple[int, int]:  # fmt: skip
    """Command intervals previewed (front, rear) for a preview of ``preview_m`` ahead of the front
    axle at ``speed_m_s`` (module notes).

    Raises
    ------
    ValueError
        If ``preview_m`` is negative or not finite or longer than the course's horizon, or the
        speed or wheelbase is not positive.
    """
    if not np.isfinite(preview_m) or preview_m < 0.0:
        raise ValueError(f"preview_m must be a finite length >= 0 m; got {preview_m!r}")
    if not speed_m_s > 0.0 or not wheelbase_m > 0.0:
        raise ValueError(
            f"speed_m_s and wheelbase_m must be > 0; got {speed_m_s!r}, {wheelbase_m!r}"
        )
    course_m = problem.duration_s * speed_m_s
    if preview_m > course_m:
        raise ValueError(
            f"preview_m: {preview_m:g} m is longer than the course's {course_m:g} m "
            f"({problem.duration_s:g} s at {speed_m_s:g} m/s)"
        )
    step_m = speed_m_s * problem.hold_periods * problem.period_s
    rear_m = preview_m + (wheelbase_m if wheelbase_preview else 0.0)
    return tuple(
        min(int(np.floor(x / step_m + 1e-9)), problem.intervals) for x in (preview_m, rear_m)
    )


def evaluate_preview(
    design: PreviewDesign, problem: BoundProblem, intervals: tuple[int, int], preview_m: float = 0.0
) -> PreviewRun:
    """Close the preview law on the lifted linear plant over ``problem``'s course and evaluate
    a_total sample by sample (:func:`~loader_model.bound.linear.evaluate`)."""
    lq = design.lq
    feedforward = design.feedforward(intervals)
    command = np.empty(lq.d.shape[0])
    states = np.zeros((command.size + 1, lq.a.shape[0]))
    for j in range(command.size):
        command[j] = feedforward[j] - design.gain @ states[j]
        states[j + 1] = lq.a @ states[j] + lq.b * command[j] + lq.d[j]
    a_total, end, _ = evaluate(lq, command, problem)
    return PreviewRun(float(preview_m), intervals, command * lq.u_scale, a_total, end, states)
