"""The compact wheel loader (derive/machines/compact_wheel_loader.toml) from its generated model:
energy and momentum balances, linearisation against finite differences, an independent mass
matrix (the tree's kinematics written out by hand with NumPy), and its undamped modes."""

from __future__ import annotations

import tomllib

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

import loader_model_generated.compact_wheel_loader as wl
from derive.description import MACHINES_DIR
from tests.numerics import central_difference

N = len(wl.COORDINATE_NAMES)
K_EQ_N_PER_M = 2.0e7  # hydraulic spring of the lift cylinders (order of Eq. 28)
VALUES = tomllib.loads((MACHINES_DIR / "values" / "compact_wheel_loader.toml").read_text())


def _params(**changes: float) -> np.ndarray:
    raw = np.array([changes.get(name, VALUES[name]["value"]) for name in wl.PARAMETER_NAMES])
    completed, _ = wl.function("complete_parameters")(raw)
    return np.asarray(completed).ravel()


def _lift_force(params: np.ndarray, p: ca.SX) -> ca.SX:
    f_act0 = float(wl.function("complete_parameters")(params)[1])
    x0 = float(wl.function("cylinder_kinematics")(np.zeros(N), np.zeros(N), params)[0])
    x = wl.function("cylinder_kinematics")(p, ca.DM.zeros(N), params)[0]
    return f_act0 - K_EQ_N_PER_M * (x - x0), f_act0, x0


def _rate(params: np.ndarray, road: np.ndarray | None = None) -> ca.Function:
    state = ca.SX.sym("state", 2 * N + 2)
    p, pd, anchor = state[:N], state[N : 2 * N], state[2 * N :]
    force, _, _ = _lift_force(params, p)
    pdd, anchor_rate = wl.function("forward_dynamics")(
        p,
        pd,
        anchor,
        force,
        ca.DM.zeros(4) if road is None else road,
        ca.DM.zeros(4),
        ca.DM.zeros(3),
        params,
    )
    return ca.Function("rate", [state], [ca.vertcat(pd, pdd, anchor_rate)])


def _integrate(params: np.ndarray, start: np.ndarray, road: np.ndarray | None = None) -> np.ndarray:
    rate = _rate(params, road)
    solution = solve_ivp(
        lambda _, y: np.asarray(rate(y)).ravel(),
        (0.0, 2.0),
        start,
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        t_eval=np.linspace(0.0, 2.0, 201),
    )
    assert solution.success, solution.message
    return solution.y.T


START = 0.2 * np.array(
    [0.002, -0.004, 0.004, -0.006, 0.01, 0.03, 0.02, -0.05, 0.08, -0.1, 0.0, 0.0]
)


def test_undamped_motion_conserves_energy() -> None:
    undamped = {f"c_{a}{x}": 0.0 for a in "AB" for x in "xy"} | {"c_tilt": 0.0}
    params = _params(**undamped)
    trajectory = _integrate(params, START)
    assert np.all(trajectory[:, 2 * N :] == 0.0)  # the tyres stuck: no anchor moved
    energy_fn = wl.function("mechanical_energy")
    _, f_act0, x0 = _lift_force(params, ca.DM.zeros(N))
    cylinder = wl.function("cylinder_kinematics")

    def energy(row: np.ndarray) -> float:
        p, pd, anchor = row[:N], row[N : 2 * N], row[2 * N :]
        out = energy_fn(p, pd, anchor, np.zeros(4), np.zeros(4), params)
        t, v_g, v_tyre, v_int = (float(out[i]) for i in (0, 1, 2, 5))
        extension = float(cylinder(p, pd, params)[0]) - x0
        lift = K_EQ_N_PER_M * extension**2 / 2 - f_act0 * extension
        return t + v_g + v_tyre + v_int + lift

    values = np.array([energy(row) for row in trajectory])
    assert np.ptp(values) < 1e-9 * max(abs(values).max(), 1.0) + 1e-9
    assert values[0] > 1.0  # the start moves: a real test, not 0 == 0


def test_free_flight_conserves_momentum() -> None:
    """Without gravity and off the ground the three bodies only push on each other (lift and tilt
    cylinders): linear momentum and angular momentum about the origin stay constant."""
    free = {f"{k}_{a}{x}": 0.0 for k in "kc" for a in "AB" for x in "xy"} | {"g": 0.0}
    params = _params(**(free | {"k_Ay": 1e5, "k_By": 1e5}))
    # the road 1 m below both axles: the tyres are in the air (no force, not even the contact
    # law's smoothed ε/4 at zero load)
    trajectory = _integrate(params, START, np.array([0.0, -1.0, 0.0, -1.0]))
    masses = [VALUES[f"m_{i}"]["value"] for i in (1, 2, 3)]
    inertias = [VALUES[f"J_{i}"]["value"] for i in (1, 2, 3)]
    positions, velocities = wl.function("point_positions"), wl.function("point_velocities")
    names = list(positions.name_out())
    cogs = [names.index(f"r_{k}") for k in "HGQ"]

    def momentum(row: np.ndarray) -> np.ndarray:
        p, pd = row[:N], row[N : 2 * N]
        r = [np.asarray(positions(p, params)[i]).ravel() for i in cogs]
        v = [np.asarray(velocities(p, pd, params)[i]).ravel() for i in cogs]
        linear = sum(m * vi for m, vi in zip(masses, v, strict=True))
        spin = sum(j * w for j, w in zip(inertias, pd[2:5], strict=True))
        orbital = sum(
            m * (ri[0] * vi[1] - ri[1] * vi[0]) for m, ri, vi in zip(masses, r, v, strict=True)
        )
        return np.array([*linear, spin + orbital])

    values = np.array([momentum(row) for row in trajectory])
    drift = np.abs(values - values[0]).max(axis=0)
    assert np.all(drift < 1e-10 * np.abs(values).max()), drift


def _hand_positions(p: np.ndarray) -> dict[str, np.ndarray]:
    """r_H + R(θ1) D + R(θ2)(K − D) + R(θ3)(Q − K), written out from the description."""

    def rot(a: float) -> np.ndarray:
        return np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])

    pt = {k: np.array([VALUES[f"{k}_x"]["value"], VALUES[f"{k}_y"]["value"]]) for k in "DGKQ"}
    r_h = p[:2]
    r_d = r_h + rot(p[2]) @ pt["D"]
    r_k = r_d + rot(p[3]) @ (pt["K"] - pt["D"])
    return {
        "H": r_h,
        "G": r_d + rot(p[3]) @ (pt["G"] - pt["D"]),
        "Q": r_k + rot(p[4]) @ (pt["Q"] - pt["K"]),
    }


def test_mass_matrix_matches_an_independent_hand_derivation() -> None:
    p = np.array([0.1, -0.05, 0.2, -0.4, 0.7])
    params = _params()
    masses = {k: VALUES[f"m_{i}"]["value"] for k, i in zip("HGQ", (1, 2, 3), strict=True)}
    expected = np.diag([0.0, 0.0, *(VALUES[f"J_{i}"]["value"] for i in (1, 2, 3))])
    for k, m in masses.items():
        jac = central_difference(lambda q, k=k: _hand_positions(q)[k], p, np.full(N, 1e-6))
        expected += m * jac.T @ jac
    actual = np.asarray(wl.function("mass_matrix")(p, params))
    np.testing.assert_allclose(actual, expected, rtol=1e-8, atol=1e-8 * np.abs(expected).max())


def test_linearisation_matches_finite_differences() -> None:
    params = _params()
    rate = _rate(params)
    x0 = START[: 2 * N] * 0.5
    linear = wl.function("linearisation")
    # linearise the closed lift circuit: F_act = F_act0 − k_eq (x − x0) about the state x0
    p, pd = x0[:N], x0[N:]
    force, _, _ = _lift_force(params, ca.DM(p))
    a_mat, b_mat = (
        np.asarray(m)
        for m in linear(p, pd, float(force), np.zeros(4), np.zeros(4), np.zeros(3), params)[:2]
    )
    q_act = np.asarray(wl.function("actuator_map")(p, params)).ravel()
    order = wl.STATE_NAMES
    index = [order.index(n) for n in (*wl.COORDINATE_NAMES, *wl.RATE_NAMES)]
    reference = central_difference(
        lambda x: np.asarray(rate(np.r_[x, 0.0, 0.0])).ravel()[: 2 * N], x0, np.full(2 * N, 1e-6)
    )
    closed = a_mat.copy()
    closed[:, [order.index(n) for n in wl.COORDINATE_NAMES]] -= (
        K_EQ_N_PER_M * b_mat @ q_act[None, :]
    )
    actual = closed[np.ix_(index, index)]
    scale = max(np.abs(reference).max(), 1.0)
    np.testing.assert_allclose(actual, reference, rtol=1e-6, atol=1e-6 * scale)


def undamped_modes() -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies [Hz] and mode shapes at the static equilibrium (Eq. 27-29): M and the
    stiffness K = ∂r/∂p at rest plus the lift cylinders' hydraulic spring k_eq Q_act Q_actᵀ."""
    params = _params()
    zeros = np.zeros(N)
    f_act0 = float(wl.function("complete_parameters")(params)[1])
    out = wl.function("residual_jacobians")(
        zeros, zeros, zeros, f_act0, np.zeros(4), np.zeros(4), np.zeros(3), params
    )
    q_act = np.asarray(wl.function("actuator_map")(zeros, params)).ravel()
    stiffness = np.asarray(out[1]) + K_EQ_N_PER_M * np.outer(q_act, q_act)
    mass = np.asarray(wl.function("mass_matrix")(zeros, params))
    eigenvalues, shapes = eigh(stiffness[1:, 1:], mass[1:, 1:])  # x_H: rigid-body surge ~ tyres
    return np.sqrt(np.abs(eigenvalues)) / (2 * np.pi), shapes


def test_modes_are_positive_and_in_the_ride_band() -> None:
    frequencies, _ = undamped_modes()
    assert np.all(frequencies > 0.5) and frequencies.min() < 5.0, frequencies


if __name__ == "__main__":
    np.set_printoptions(precision=3, suppress=True)
    frequencies, shapes = undamped_modes()
    for f, shape in zip(frequencies, shapes.T, strict=True):
        print(f"{f:7.2f} Hz  shape (y_H, θ1, θ2, θ3) = {shape / np.abs(shape).max()}")
    pytest.main([__file__, "-q"])
