r"""CasADi gain optimisation: static output feedback minimising a weighted sum of H2 norms.

For design plants i (:class:`~loader_model.control.design_plant.DesignPlant`) and u = −K y,

.. math::
    J(K) = \sum_i w_i \left[ \operatorname{tr}(C_{z,i}^{cl} P_i C_{z,i}^{cl\,T})
        + \operatorname{tr}(R K C_{y,i} P_i C_{y,i}^T K^T) \right],
    \quad A_i^{cl} P_i + P_i A_i^{cl\,T} + B_{w,i} B_{w,i}^T = 0,

with :math:`A^{cl} = A - B_u K C_y`, :math:`C_z^{cl} = C_z - D_{zu} K C_y`: the squared H2 norm
from the white noise w to z plus an effort penalty (the stochastic form of Eq. 41 with
X0 = B_w B_wᵀ, Q = C_zᵀ C_z). :func:`h2_cost_function` exposes J(K) as a CasADi Function;
The gain designs (:func:`loader_model.control.comfort_design.optimise_gain`) minimise the
same J from its adjoint gradient (:mod:`~loader_model.control.feasible_descent`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import casadi as ca
import numpy as np
from scipy.linalg import matrix_balance, solve_continuous_lyapunov

from loader_model.control._checks import finite_matrix, symmetric_matrix
from loader_model.control.design_plant import DesignPlant

__all__ = ["check_plants", "closed_loop", "h2_cost_function", "h2_costs", "plant_terms_mx"]


def check_plants(plants: Sequence[DesignPlant] | DesignPlant, effort_weight: Any) -> tuple:
    """Validated tuple of plants with one gain shape, and the effort weight R (m x m, ⪰ 0)."""
    plants = (plants,) if isinstance(plants, DesignPlant) else tuple(plants)
    if not plants or not all(isinstance(p, DesignPlant) for p in plants):
        raise ValueError(f"plants must be one or more DesignPlant; got {plants!r}")
    shapes = {p.gain_shape for p in plants}
    if len(shapes) != 1:
        raise ValueError(
            f"plants must share the gain shape (inputs, measured outputs); got {shapes}"
        )
    m = plants[0].gain_shape[0]
    r = (
        np.zeros((m, m))
        if effort_weight is None
        else symmetric_matrix("effort_weight", effort_weight, m, definite=False)
    )
    return plants, r


def closed_loop(plant: DesignPlant, gain: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A_cl, C_z^cl, C_e^cl of u = −K y (numpy)."""
    kc = gain @ plant.C_y
    return plant.A - plant.B_u @ kc, plant.C_z - plant.D_zu @ kc, plant.C_e - plant.D_eu @ kc


def h2_costs(plants: Sequence[DesignPlant], gain: Any, effort_weight: Any = None) -> dict[str, Any]:
    """Per-plant weighted costs, Gramians and r.m.s. values by scipy (inf cost when unstable)."""
    plants, r = check_plants(plants, effort_weight)
    gain = finite_matrix("gain", gain, plants[0].gain_shape)
    costs, gramians, u_rms, e_rms, poles = [], [], [], [], []
    for plant in plants:
        a_cl, c_z, c_e = closed_loop(plant, gain)
        poles.append(np.linalg.eigvals(a_cl))
        if np.max(poles[-1].real) >= 0.0:
            costs.append(np.inf)
            gramians.append(None)
            u_rms.append(np.full(gain.shape[0], np.inf))
            e_rms.append(np.full(c_e.shape[0], np.inf))
            continue
        p = solve_continuous_lyapunov(a_cl, -plant.B_w @ plant.B_w.T)
        u_cov = gain @ plant.C_y @ p @ plant.C_y.T @ gain.T
        costs.append(plant.weight * float(np.trace(c_z @ p @ c_z.T) + np.trace(r @ u_cov)))
        gramians.append(p)
        u_rms.append(np.sqrt(np.maximum(np.diag(u_cov), 0.0)))
        e_rms.append(np.sqrt(np.maximum(np.diag(c_e @ p @ c_e.T), 0.0)))
    return {"costs": costs, "gramians": gramians, "u_rms": u_rms, "e_rms": e_rms, "poles": poles}


def plant_terms_mx(plant: DesignPlant, k: ca.MX, r: np.ndarray) -> tuple[ca.MX, ca.MX, ca.MX]:
    """Weighted cost, var(u) and var(e) of one plant as MX expressions of the gain K.

    The Gramian solves the Lyapunov equation in vectorised (Kronecker) form with ``casadi.solve``.
    """
    n = plant.A.shape[0]
    # A diagonal similarity that balances A (exact powers of 2) takes the condition number of
    # the Kronecker operator of the loader test plant from 2e14 to 3e4; H2 norms are unchanged.
    _, (scale, _) = matrix_balance(plant.A, permute=False, separate=True)
    a, b_u, b_w = (
        plant.A * scale / scale[:, None],
        plant.B_u / scale[:, None],
        plant.B_w / scale[:, None],
    )
    c_y, c_z, c_e = plant.C_y * scale, plant.C_z * scale, plant.C_e * scale
    kc = k @ c_y
    a_cl = a - b_u @ kc
    eye = ca.MX.eye(n)
    operator = ca.kron(eye, a_cl) + ca.kron(a_cl, eye)  # vec(A P + P Aᵀ) = operator vec(P)
    rhs = -ca.DM(b_w @ b_w.T).reshape((n * n, 1))
    p = ca.reshape(ca.solve(operator, rhs), n, n)
    c_z = c_z - plant.D_zu @ kc
    c_e = c_e - plant.D_eu @ kc
    cost = plant.weight * (ca.trace(c_z @ p @ c_z.T) + ca.trace(r @ kc @ p @ kc.T))
    return cost, ca.diag(kc @ p @ kc.T), ca.diag(c_e @ p @ c_e.T)


def h2_cost_function(
    plants: Sequence[DesignPlant] | DesignPlant, effort_weight: Any = None
) -> ca.Function:
    """J(K) of the module docstring as a CasADi Function ``h2_cost``.

    Parameters
    ----------
    plants
        One or more :class:`DesignPlant` sharing the gain shape (m, p).
    effort_weight
        R (m x m, symmetric ⪰ 0) of the effort term; default 0.

    Returns
    -------
    casadi.Function
        Input ``K`` (m x p); outputs ``J`` (scalar) and ``J_plants`` (weighted cost per plant).

    Notes
    -----
    The Lyapunov equations are solved in vectorised (Kronecker) form with ``casadi.solve`` on
    balanced states, so the Function can be differentiated to any order by CasADi's AD. It is
    meaningful only where every closed loop is Hurwitz (elsewhere it returns the indefinite
    Lyapunov solution); :func:`h2_costs` checks stability.
    """
    plants, r = check_plants(plants, effort_weight)
    k = ca.MX.sym("K", *plants[0].gain_shape)
    costs = ca.vertcat(*[plant_terms_mx(plant, k, r)[0] for plant in plants])
    return ca.Function("h2_cost", [k], [ca.sum1(costs), costs], ["K"], ["J", "J_plants"])
