r"""The non-causal linear-quadratic bound on the linearised plant, solved exactly.

The plant of :func:`~loader_model.plant.linear.linearise_plant` (Eq. 38-40 extended, at the
static equilibrium; tyre anchors dropped) is sampled at h = 1 ms exactly, the command held over
each period and the road linear inside it (as the simulator interpolates it), and augmented with
the sampled ISO 2631 filters of :mod:`~loader_model.bound.weighting`; the command is held over M
periods (the nonlinear bound's grid). Over one control interval the samples are affine in the
node state z_j and the command u_j, so the cost a_total² (Eq. 49, 50) is the LQ problem

.. math::

    \min_u \frac{1}{K_s}\sum_j \left( z_j^T \bar Q z_j + 2 z_j^T \bar S u_j + \bar R u_j^2
    + 2 q_j^T z_j + 2 r_j u_j + c_j \right), \quad z_{j+1} = \bar A z_j + \bar B u_j + d_j,
    \quad z_0 = 0, \quad C_T z_N = 0

with the road known in advance (d, q, r: non-causal). :func:`solve_riccati` solves it by a
backward Riccati sweep whose affine terms carry the end condition's multiplier ν, a forward
sweep, and one small solve for ν; :func:`solve_kkt` solves the same problem as one sparse KKT
system (the reference the tests compare with). No pump, pressure or stroke limits: the linear
bound is the plant's, the nonlinear one the machine's.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

from loader_model.bound.problem import PATH_SIGNALS, BoundProblem, pump_states
from loader_model.bound.weighting import SeatWeighting, seat_weighting
from loader_model.plant.linear import linearise_plant

__all__ = ["LinearBound", "LinearQuadratic", "linear_quadratic", "solve_kkt", "solve_riccati"]

#: Command weight relative to the cost's own curvature in u (keeps the sweep regular).
_REGULARISATION = 1e-9


@dataclass(frozen=True)
class LinearQuadratic:
    """The lifted LQ problem (module notes), in scaled units z = T ẑ, u = s_u û."""

    a: np.ndarray
    b: np.ndarray
    d: np.ndarray
    q: np.ndarray
    s: np.ndarray
    r: float
    q_lin: np.ndarray
    r_lin: np.ndarray
    constant: float
    end: np.ndarray
    count: int
    u_scale: float
    sample: tuple[np.ndarray, ...]
    path: tuple[np.ndarray, ...] = ()


@dataclass(frozen=True)
class LinearBound:
    """The LQ bound: command deviation from u0 (m³/rev) and a_total (Eq. 50) of the linear plant."""

    command: np.ndarray
    a_total_m_s2: float
    end_residual: np.ndarray
    seat: np.ndarray
    solve_s: float = 0.0


def _sampled_plant(problem: BoundProblem, weighting: SeatWeighting) -> tuple[np.ndarray, ...]:
    """Per-sample z_{k+1} = A z + B u + F0 w_k + F1 w_{k+1}, residual r = H z + G w (scaled)."""
    plant = problem.plant
    linearisation = linearise_plant(plant.params, plant.x0, plant.u0, machine=plant.layout)
    system = linearisation.state_space(exogenous=True)
    a, bw, c, dw = (np.asarray(m) for m in (system.A, system.B, system.C, system.D))
    n, nw, h = a.shape[0], len(plant.layout.exogenous_names), problem.period_s
    displacement, rate = pump_states(plant.layout)
    seat = [system.output_labels.index(s) for s in weighting.signals]
    big = np.zeros((n + 1 + 2 * nw, n + 1 + 2 * nw))
    big[:n, :n], big[:n, n : n + 1 + nw] = a * h, bw * h
    big[n + 1 : n + 1 + nw, n + 1 + nw :] = np.eye(nw)
    e = scipy.linalg.expm(big)
    phi, gu = e[:n, :n], e[:n, n : n + 1]
    g0, g1 = e[:n, n + 1 : n + 1 + nw], e[:n, n + 1 + nw :]
    cs, ds = c[seat], dw[seat, 1:]
    nf = weighting.order
    az = np.block([[phi, np.zeros((n, nf))], [weighting.gamma @ cs, weighting.phi]])
    bz = np.vstack([gu, weighting.gamma @ dw[seat, :1]])
    f0 = np.vstack([g0 - g1, weighting.gamma @ ds])
    f1 = np.vstack([g1, np.zeros((nf, nw))])
    k = np.diag(weighting.k_factors)
    hz = k @ np.hstack([weighting.d @ cs, weighting.c])
    gw = k @ weighting.d @ ds
    end_rows = [system.output_labels.index("x_piston")]
    end = np.vstack(
        [c[end_rows], *(np.eye(n)[[system.state_labels.index(s)]] for s in (displacement, rate))]
    )
    end = np.hstack([end, np.zeros((end.shape[0], nf))])
    seat_z = np.hstack([cs, np.zeros((cs.shape[0], nf))])
    rows = [system.output_labels.index(name) for name in PATH_SIGNALS]
    path_x = np.vstack([c[rows], np.eye(n)[[system.state_labels.index(rate)]]])
    path_z = np.hstack([path_x, np.zeros((path_x.shape[0], nf))])
    path_w = np.vstack([dw[rows, 1:], np.zeros((1, nw))])
    return az, bz, f0, f1, hz, gw, end, seat_z, ds, path_z, path_w


def linear_quadratic(
    problem: BoundProblem, weighting: SeatWeighting | None = None
) -> LinearQuadratic:
    """The lifted LQ problem of ``problem`` on the linearised plant (module notes)."""
    weighting = weighting or seat_weighting(problem.period_s)
    az, bz, f0, f1, hz, gw, end, seat_z, seat_w, path_z, path_w = _sampled_plant(problem, weighting)
    m, n_int = problem.hold_periods, problem.intervals
    w = problem.exogenous
    disturbance = w[:-1] @ f0.T + w[1:] @ f1.T  # (K_s, nz)
    response = np.zeros(az.shape[0])
    peak = np.zeros(az.shape[0])
    for k in range(problem.periods):  # state scales: the free response to the road
        response = az @ response + disturbance[k]
        peak = np.maximum(peak, np.abs(response))
    t = np.maximum(peak, 1e-12 * max(peak.max(), 1e-30))
    su = problem.u_bounds[1]
    a_s = az / t[:, None] * t[None, :]
    b_s = bz[:, 0] / t * su
    h_s = hz * t[None, :]
    hu = np.zeros(hz.shape[0])
    d_s = disturbance / t[None, :]
    nz = az.shape[0]
    p_i, q_i = np.eye(nz), np.zeros(nz)
    omega = np.zeros((n_int, nz))
    qbar, sbar, rbar = np.zeros((nz, nz)), np.zeros(nz), 0.0
    q_lin, r_lin, constant = np.zeros((n_int, nz)), np.zeros(n_int), 0.0
    path_s = path_z * t[None, :]
    p_z, p_u, p_offset = [], [], []
    for i in range(m):
        p_z.append(path_s @ p_i)
        p_u.append(path_s @ q_i)
        p_offset.append(omega @ path_s.T + w[i : problem.periods : m] @ path_w.T)
        hp, hq = h_s @ p_i, h_s @ q_i + hu
        c = omega @ h_s.T + w[i : problem.periods : m] @ gw.T  # (N, axes)
        qbar += hp.T @ hp
        sbar += hp.T @ hq
        rbar += hq @ hq
        q_lin += c @ hp
        r_lin += c @ hq
        constant += float(np.sum(c * c))
        p_i, q_i = a_s @ p_i, a_s @ q_i + b_s
        omega = omega @ a_s.T + d_s[i : problem.periods : m]
    return LinearQuadratic(
        a=p_i, b=q_i, d=omega, q=qbar, s=sbar, r=rbar * (1 + _REGULARISATION),
        q_lin=q_lin, r_lin=r_lin, constant=constant, end=end * t[None, :],
        count=problem.periods, u_scale=su,
        sample=(a_s, b_s, h_s, d_s, gw, seat_z * t[None, :], seat_w),
        path=(np.vstack(p_z), np.concatenate(p_u), np.hstack(p_offset)),
    )  # fmt: skip


def evaluate(
    lq: LinearQuadratic, command: np.ndarray, problem: BoundProblem
) -> tuple[float, np.ndarray, np.ndarray]:
    """a_total of scaled commands û_j sample by sample, the end residual C_T z_N and the seat
    samples (K_s, axes) of the linear plant (vibration about rest)."""
    a_s, b_s, h_s, d_s, gw, seat_z, seat_w = lq.sample
    m, w = problem.hold_periods, problem.exogenous
    z, total = np.zeros(a_s.shape[0]), 0.0
    seat = np.empty((lq.count, seat_z.shape[0]))
    for k in range(lq.count):
        residual = h_s @ z + gw @ w[k]
        seat[k] = seat_z @ z + seat_w @ w[k]
        total += float(residual @ residual)
        z = a_s @ z + b_s * command[k // m] + d_s[k]
    return float(np.sqrt(total / lq.count)), lq.end @ z, seat


def solve_riccati(lq: LinearQuadratic) -> np.ndarray:
    """Scaled optimal commands û_j by the Riccati sweep with the end multiplier (module notes)."""
    n, nz, ne = lq.d.shape[0], lq.a.shape[0], lq.end.shape[0]
    p, p0, g = np.zeros((nz, nz)), np.zeros(nz), lq.end.T.copy()
    gains, k0, kv = np.zeros((n, nz)), np.zeros(n), np.zeros((n, ne))
    for j in range(n - 1, -1, -1):
        pb = p @ lq.b
        huu = lq.r + lq.b @ pb
        huz = lq.s + pb @ lq.a
        hu0 = lq.r_lin[j] + lq.b @ (p @ lq.d[j] + p0)
        gains[j] = -huz / huu
        k0[j] = -hu0 / huu
        kv[j] = -(lq.b @ g) / huu
        closed = lq.a + np.outer(lq.b, gains[j])
        p0 = lq.q_lin[j] + lq.a.T @ (p @ lq.d[j] + p0) + gains[j] * hu0
        p = lq.q + lq.a.T @ p @ lq.a - np.outer(huz, huz) / huu
        p = 0.5 * (p + p.T)
        g = closed.T @ g
    z, zv = np.zeros(nz), np.zeros((nz, ne))
    for j in range(n):
        z = lq.a @ z + lq.b * (gains[j] @ z + k0[j]) + lq.d[j]
        zv = (lq.a + np.outer(lq.b, gains[j])) @ zv + np.outer(lq.b, kv[j])
    nu = np.linalg.lstsq(lq.end @ zv, -lq.end @ z, rcond=None)[0]
    u, z = np.zeros(n), np.zeros(nz)
    for j in range(n):
        u[j] = gains[j] @ z + k0[j] + kv[j] @ nu
        z = lq.a @ z + lq.b * u[j] + lq.d[j]
    return u


def solve_kkt(lq: LinearQuadratic) -> np.ndarray:
    """The same optimum as one sparse KKT solve over (z_1 … z_N, u_0 … u_{N−1}) (reference)."""
    n, nz = lq.d.shape[0], lq.a.shape[0]
    eye = scipy.sparse.identity(n, format="csr")
    shift = scipy.sparse.eye(n, n, k=-1, format="csr")
    # z_j for j = 0..N-1 is shift @ Z (z_0 = 0); stage costs on z_0..z_{N-1}
    hzz = scipy.sparse.kron(shift.T @ shift, lq.q)
    hzu = scipy.sparse.kron(shift.T, lq.s[:, None])
    huu = lq.r * eye
    hess = scipy.sparse.bmat([[hzz, hzu], [hzu.T, huu]], format="csc")
    grad = np.concatenate([(shift.T @ lq.q_lin).ravel(), lq.r_lin])
    dyn_z = scipy.sparse.kron(eye, scipy.sparse.identity(nz)) - scipy.sparse.kron(shift, lq.a)
    dyn_u = -scipy.sparse.kron(eye, lq.b[:, None])
    end = scipy.sparse.hstack(
        [scipy.sparse.kron(scipy.sparse.csr_matrix(([1.0], ([0], [n - 1])), shape=(1, n)), lq.end),
         scipy.sparse.csr_matrix((lq.end.shape[0], n))]
    )  # fmt: skip
    constraints = scipy.sparse.vstack([scipy.sparse.hstack([dyn_z, dyn_u]), end])
    rhs = np.concatenate([lq.d.ravel(), np.zeros(lq.end.shape[0])])
    kkt = scipy.sparse.bmat([[hess, constraints.T], [constraints, None]], format="csc")
    solution = scipy.sparse.linalg.spsolve(kkt, np.concatenate([-grad, rhs]))
    return solution[n * nz : n * nz + n]


def solve_linear_bound(problem: BoundProblem, method: str = "riccati") -> LinearBound:
    """The LQ bound of ``problem``: ``method`` ``"riccati"`` (fast) or ``"kkt"`` (reference)."""
    if method not in ("riccati", "kkt"):
        raise ValueError(f"method must be 'riccati' or 'kkt'; got {method!r}")
    start = time.perf_counter()
    lq = linear_quadratic(problem)
    scaled = solve_riccati(lq) if method == "riccati" else solve_kkt(lq)
    a_total, end, seat = evaluate(lq, scaled, problem)
    return LinearBound(scaled * lq.u_scale, a_total, end, seat, time.perf_counter() - start)
