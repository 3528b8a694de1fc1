"""H2 gain design: CasADi cost against python-control/scipy, AD gradient against finite
differences, IPOPT result against the output-feedback LQR optimum, margins, limits, failures."""

from __future__ import annotations

import casadi as ca
import control
import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

from loader_model.control import (
    DesignPlant,
    H2DesignError,
    design_h2_gain,
    h2_cost_function,
    h2_costs,
    output_feedback_lqr,
)
from tests.control_plant import MEASURED, PERFORMANCE, TABLE3_GAIN, loader_design_plant

Y, Z = list(MEASURED), list(PERFORMANCE)
EFFORT = np.eye(1)


@pytest.fixture(scope="module")
def systems() -> dict[str, control.StateSpace]:
    return {load: loader_design_plant(load) for load in ("empty", "full")}


@pytest.fixture(scope="module")
def plants(systems: dict[str, control.StateSpace]) -> list[DesignPlant]:
    # z = (y, seat accelerations): the H2 problem whose single-plant optimum is the
    # output-feedback LQR with Q = C_zᵀ C_z, R = 1, X0 = B_w B_wᵀ (J_H2 = 2 J_LQR).
    return [
        DesignPlant.from_statespace(
            systems[load],
            control=["u"],
            noise=["nu_Fy", "nu_M"],
            measured=Y,
            performance=Y + Z,
            name=load,
        )
        for load in ("empty", "full")
    ]


@pytest.fixture(scope="module")
def lqr_gain(systems: dict[str, control.StateSpace]) -> np.ndarray:
    sys = systems["empty"]
    c_z = np.asarray(sys.C)
    b_w = np.asarray(sys.B)[:, 1:]
    result = output_feedback_lqr(sys, c_z.T @ c_z, EFFORT, b_w @ b_w.T, inputs=["u"], outputs=Y)
    assert result.converged
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


def test_single_plant_optimum_equals_output_feedback_lqr(plants, lqr_gain) -> None:
    result = design_h2_gain(plants[:1], TABLE3_GAIN, effort_weight=EFFORT)
    lqr_cost = design_h2_gain(
        plants[:1],
        lqr_gain,
        effort_weight=EFFORT,
        ipopt_options={"max_iter": 0},
        raise_on_failure=False,
    ).initial_cost
    assert result.success and result.cost < result.initial_cost
    np.testing.assert_allclose(result.cost, lqr_cost, rtol=1e-10)
    assert np.linalg.norm(result.gain - lqr_gain) <= 1e-7 * np.linalg.norm(lqr_gain)


@pytest.mark.parametrize("margin", [0.01, 0.1])
def test_two_loads_beat_the_start_and_the_lqr_gain(plants, lqr_gain, margin) -> None:
    result = design_h2_gain(plants, TABLE3_GAIN, effort_weight=EFFORT, margin=margin)
    lqr = design_h2_gain(
        plants,
        lqr_gain,
        effort_weight=EFFORT,
        ipopt_options={"max_iter": 0},
        raise_on_failure=False,
    )
    assert result.success and result.solver_status == "Solve_Succeeded"
    assert result.cost < result.initial_cost
    lqr_margin = min(-np.max(p.real) for p in lqr.poles)
    if lqr_margin > margin:  # the LQR gain is admissible: the optimum must be at least as good
        assert result.cost < lqr.initial_cost
    for poles in result.poles:
        assert np.max(poles.real) < -margin * (1 - 1e-6)
    assert result.margin >= margin * (1 - 1e-6)


def test_destabilising_start_ends_stable(plants) -> None:
    start = -TABLE3_GAIN
    assert any(np.max(np.linalg.eigvals(p.A - p.B_u @ start @ p.C_y).real) > 0 for p in plants)
    result = design_h2_gain(plants, start, effort_weight=EFFORT, margin=0.1)
    assert result.success and np.isinf(result.initial_cost)
    assert all(np.max(p.real) < -0.1 * (1 - 1e-6) for p in result.poles)


def test_unreachable_margin_is_reported(plants) -> None:
    with pytest.raises(H2DesignError, match="margin not reached") as info:
        design_h2_gain(plants, TABLE3_GAIN, margin=50.0)
    assert not info.value.result.success


def test_input_rms_limit_and_mask(plants) -> None:
    free = design_h2_gain(plants, TABLE3_GAIN, effort_weight=EFFORT)
    limit = 0.8 * min(float(u[0]) for u in free.input_rms)
    limited = design_h2_gain(plants, TABLE3_GAIN, effort_weight=EFFORT, input_rms_limits=[limit])
    assert all(u[0] <= limit * (1 + 1e-6) for u in limited.input_rms)
    assert limited.cost > free.cost
    mask = np.array([[True, True, True, False]])
    masked = design_h2_gain(plants, TABLE3_GAIN, effort_weight=EFFORT, mask=mask)
    assert masked.gain[0, 3] == TABLE3_GAIN[0, 3] and masked.cost >= free.cost


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"gain0": np.zeros((2, 4))}, r"gain0 must have shape \(1, 4\)"),
        ({"mask": np.ones((4, 1), dtype=bool)}, r"mask must have the gain's shape \(1, 4\)"),
        ({"margin": -1.0}, "margin must be finite and >= 0"),
        ({"input_rms_limits": [1.0, 2.0]}, "input_rms_limits must be 1 positive finite numbers"),
        ({"effort_weight": -np.eye(1)}, "effort_weight must be positive semidefinite"),
    ],
)
def test_bad_arguments(plants, kwargs, message) -> None:
    arguments = {"gain0": TABLE3_GAIN} | kwargs
    with pytest.raises(ValueError, match=message):
        design_h2_gain(plants, **arguments)


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
        np.diff(result.cost_history) <= 1e-14 * result.cost
    )
    assert result.output_names == tuple(Y) and result.input_names == ("u",)
