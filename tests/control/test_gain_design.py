"""Gain design on the 13-state test plant: CasADi cost against python-control/scipy, AD gradient
against finite differences, the certified BFGS and IPOPT designs (``optimise_gain``) against the
output-feedback LQR optimum and the retired Gramian design's optima, margins, limits, failures."""

from __future__ import annotations

from dataclasses import replace

import casadi as ca
import control
import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

from loader_model.control import (
    DesignPlant,
    h2_cost_function,
    h2_costs,
    output_feedback_lqr,
)
from loader_model.control.comfort_design import optimise_gain
from tests.control_plant import (
    MEASURED,
    PERFORMANCE,
    TABLE3_GAIN,
    loader_design_plant,
    loader_h2_plants,
)

Y, Z = list(MEASURED), list(PERFORMANCE)
EFFORT = np.eye(1)


@pytest.fixture(scope="module")
def systems() -> dict[str, control.StateSpace]:
    return {load: loader_design_plant(load) for load in ("empty", "full")}


@pytest.fixture(scope="module")
def plants(systems: dict[str, control.StateSpace]) -> list[DesignPlant]:
    return loader_h2_plants(systems)


@pytest.fixture(scope="module")
def lqr_gain(systems: dict[str, control.StateSpace]) -> np.ndarray:
    sys = systems["empty"]
    c_z = np.asarray(sys.C)
    b_w = np.asarray(sys.B)[:, 1:]
    result = output_feedback_lqr(sys, c_z.T @ c_z, EFFORT, b_w @ b_w.T, inputs=["u"], outputs=Y)
    # Reached 2.2e-13 (Haswell) and 4.4e-13 (SkylakeX kernel of OpenBLAS): margin 20.
    assert result.converged and result.residuals[2] <= 1e-11
    return result.gain


def _reference_cost(sys: control.StateSpace, gain: np.ndarray) -> float:
    """H2² from (nu_Fy, nu_M) to (y, z, u) of the python-control interconnection, by scipy."""
    controller = control.ss([], [], [], -gain, inputs=Y, outputs=["u"], name="K")
    loop = control.interconnect([sys, controller], inputs=["nu_Fy", "nu_M"], outputs=[*Y, *Z, "u"])
    a, b, c = (np.asarray(m) for m in (loop.A, loop.B, loop.C))
    assert np.max(np.linalg.eigvals(a).real) < 0
    gramian = solve_continuous_lyapunov(a, -b @ b.T)
    return float(np.trace(c @ gramian @ c.T))


@pytest.mark.parametrize("gain", [TABLE3_GAIN, np.array([[-3.0, 0.1, 7.0, -0.5]])])
def test_cost_function_matches_python_control_and_scipy(plants, systems, gain) -> None:
    cost = h2_cost_function(plants, EFFORT)
    assert cost.name_in() == ["K"] and cost.name_out() == ["J", "J_plants"]
    per_plant = np.asarray(cost(K=gain)["J_plants"]).ravel()
    for value, load in zip(per_plant, ("empty", "full"), strict=True):
        np.testing.assert_allclose(value, _reference_cost(systems[load], gain), rtol=1e-9)


def test_cost_gradient_matches_central_differences(plants) -> None:
    cost = h2_cost_function(plants, EFFORT)
    k = ca.MX.sym("K", 1, 4)
    gradient = ca.Function("g", [k], [ca.gradient(cost(k)[0], k)])
    gain = TABLE3_GAIN.astype(float)
    analytic = np.asarray(gradient(gain)).ravel()
    numeric = np.zeros(4)
    for i in range(4):  # central differences of the scipy cost (more accurate than 1e-10)
        h = 1e-4 * max(1.0, abs(gain[0, i]))
        step = np.zeros((1, 4))
        step[0, i] = h
        up, down = (sum(h2_costs(plants, gain + s, EFFORT)["costs"]) for s in (step, -step))
        numeric[i] = (up - down) / (2 * h)
    assert np.linalg.norm(analytic - numeric) <= 1e-6 * np.linalg.norm(analytic)


#: Optima of the two-load problem found by the retired Gramian IPOPT design (an independent
#: formulation: Gramian and stability certificate as unknowns) over 15 warm starts.
GRAMIAN_OPTIMUM = {0.01: 0.4237270747766, 0.1: 0.42407}


def _margin(plants: list[DesignPlant], gain: np.ndarray) -> float:
    return min(-np.max(np.linalg.eigvals(p.A - p.B_u @ gain @ p.C_y).real) for p in plants)


@pytest.mark.parametrize("solver", ["bfgs", "ipopt"])
def test_single_plant_optimum_equals_output_feedback_lqr(plants, lqr_gain, solver) -> None:
    # J_H2 = 2 J_LQR: same optimum, found by the adjoint gradient instead of Eq. 42's iteration.
    result = optimise_gain(plants[:1], TABLE3_GAIN, effort=EFFORT, margin=0.0, solver=solver)
    lqr_cost = sum(h2_costs(plants[:1], lqr_gain, EFFORT)["costs"])
    assert result["converged"]
    # Measured on Haswell / SkylakeX: cost within 1.2e-12 / 3.8e-12, gain within 3.9e-6 (BFGS)
    # and 1.7e-5 (IPOPT) of the LQR's: J is flat to second order, so the gain is resolved
    # to about the square root of the gradient tolerance.
    np.testing.assert_allclose(result["cost"], lqr_cost, rtol=1e-10)
    assert np.linalg.norm(result["gain"] - lqr_gain) <= 2e-4 * np.linalg.norm(lqr_gain)


@pytest.mark.parametrize("solver", ["bfgs", "ipopt"])
def test_two_loads_reach_the_gramian_optimum_with_an_inactive_margin(plants, solver) -> None:
    result = optimise_gain(plants, TABLE3_GAIN, effort=EFFORT, margin=0.01, solver=solver)
    assert result["converged"] and result["cost"] < sum(
        h2_costs(plants, TABLE3_GAIN, EFFORT)["costs"]
    )
    # Measured 1.1e-11 (BFGS) and 1e-12 (IPOPT) from the Gramian optimum on both kernels.
    np.testing.assert_allclose(result["cost"], GRAMIAN_OPTIMUM[0.01], rtol=1e-9)
    assert _margin(plants, result["gain"]) > 0.01


def test_active_margin_is_met_at_every_iterate_and_near_the_gramian_optimum(
    plants, lqr_gain
) -> None:
    result = optimise_gain(plants, TABLE3_GAIN, effort=EFFORT, margin=0.1, solver="ipopt")
    assert min(result["iterate_margins"]) > 0.1 and _margin(plants, result["gain"]) > 0.1
    bfgs = optimise_gain(plants, TABLE3_GAIN, effort=EFFORT, margin=0.1)
    assert _margin(plants, bfgs["gain"]) > 0.1
    # An interior method approaches an active margin slowly: BFGS stops 8e-5 above the Gramian
    # optimum ("no decrease along the search direction"), IPOPT after 200 iterations 3e-5 to
    # 1.7e-4 above it (Haswell, SkylakeX). Both beat the LQR gain, which misses the margin.
    assert _margin(plants, lqr_gain) < 0.1
    for found in (result, bfgs):
        assert found["cost"] <= GRAMIAN_OPTIMUM[0.1] * (1 + 5e-4)
        assert found["cost"] >= GRAMIAN_OPTIMUM[0.01]


def test_destabilising_start_ends_stable(plants) -> None:
    start = -TABLE3_GAIN
    assert _margin(plants, start) < 0
    result = optimise_gain(plants, start, effort=EFFORT, margin=0.01)
    assert _margin(plants, result["start"]) >= 1.5 * 0.01 + 0.01
    assert result["converged"] and _margin(plants, result["gain"]) > 0.01
    np.testing.assert_allclose(result["cost"], GRAMIAN_OPTIMUM[0.01], rtol=1e-9)


def test_unreachable_margin_is_reported(plants) -> None:
    with pytest.raises(ValueError, match=r"no start gain meets the margin 50\.0 rad/s"):
        optimise_gain(plants, TABLE3_GAIN, margin=50.0)


def test_input_rms_limit_and_mask(plants) -> None:
    free = optimise_gain(plants, TABLE3_GAIN, effort=EFFORT, margin=0.01)
    u_rms = [float(u[0]) for u in h2_costs(plants, free["gain"], EFFORT)["u_rms"]]
    limit = 0.8 * min(u_rms)
    # e = u: C_e = 0, D_eu = 1, so C_e^cl = −K C_y and var(e) is var(u).
    bounded = [
        replace(p, C_e=np.zeros((1, p.A.shape[0])), D_eu=np.eye(1), e_rms_limits=(limit,))
        for p in plants
    ]
    start = TABLE3_GAIN * 0.1  # inside the limit: the barrier needs a strictly feasible start
    assert all(u[0] < limit for u in h2_costs(bounded, start, EFFORT)["u_rms"])
    limited = optimise_gain(bounded, start, effort=EFFORT, margin=0.01)
    assert all(u[0] <= limit for u in h2_costs(bounded, limited["gain"], EFFORT)["u_rms"])
    assert limited["cost"] > free["cost"]
    mask = np.array([[True, True, True, False]])
    masked = optimise_gain(plants, TABLE3_GAIN, effort=EFFORT, margin=0.01, mask=mask)
    assert masked["gain"][0, 3] == TABLE3_GAIN[0, 3] and masked["cost"] >= free["cost"]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"gain0": np.zeros((2, 4))}, r"gain0 must have shape \(1, 4\)"),
        ({"mask": np.ones((4, 1), dtype=bool)}, r"mask must have the gain's shape \(1, 4\)"),
        ({"margin": -1.0}, "margin must be finite and >= 0"),
        ({"effort": -np.eye(1)}, "effort must be positive semidefinite"),
        ({"solver": "newton"}, "solver 'newton': allowed: 'bfgs' or 'ipopt'"),
    ],
)
def test_bad_arguments(plants, kwargs, message) -> None:
    arguments = {"gain0": TABLE3_GAIN} | kwargs
    with pytest.raises(ValueError, match=message):
        optimise_gain(plants, **arguments)


def test_design_plant_rejects_noise_feedthrough(systems) -> None:
    sys = systems["empty"]
    d = np.asarray(sys.D).copy()
    d[5, 1] = 1.0
    bad = control.ss(sys.A, sys.B, sys.C, d, inputs=sys.input_labels, outputs=sys.output_labels)
    with pytest.raises(ValueError, match="D from noise to performance outputs must be 0"):
        DesignPlant.from_statespace(
            bad, control=["u"], noise=["nu_Fy", "nu_M"], measured=Y, performance=Z
        )


def test_output_feedback_lqr_on_the_loader_plant(systems) -> None:
    sys = systems["full"]
    c_z, b_w = np.asarray(sys.C), np.asarray(sys.B)[:, 1:]
    result = output_feedback_lqr(sys, c_z.T @ c_z, EFFORT, b_w @ b_w.T, inputs=["u"], outputs=Y)
    assert result.converged and max(result.residuals) <= 1e-11
    assert np.max(result.poles.real) < 0 and np.all(
        np.diff(result.cost_history) <= 1e-11 * result.cost
    )
    assert result.output_names == tuple(Y) and result.input_names == ("u",)
