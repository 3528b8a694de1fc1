"""A, B, E, C, D of the generated linearisation against central finite differences of the
generated nonlinear forward dynamics (an independent route: no symbolic Jacobians involved)."""

from __future__ import annotations

import numpy as np
import pytest

import loader_model_generated as generated
from loader_model.vehicle.dynamics import OUTPUT_NAMES, STATE_NAMES, LoaderDynamics
from tests.numerics import central_difference

ACCELERATIONS = generated.function("point_accelerations")
SPECIFIC_FORCES = generated.function("specific_forces")


def _state_derivative(model: LoaderDynamics, x: np.ndarray, u: float, w: np.ndarray) -> np.ndarray:
    p, pd = x[0::2], x[1::2]
    pdd = model.forward_dynamics(p, pd, u, w[0:4], w[4:8], w[8:11])
    out = np.empty(8)
    out[0::2], out[1::2] = pd, pdd
    return out


def _outputs(model: LoaderDynamics, x: np.ndarray, u: float, w: np.ndarray) -> np.ndarray:
    p, pd = x[0::2], x[1::2]
    pdd = model.forward_dynamics(p, pd, u, w[0:4], w[4:8], w[8:11])
    a_h, a_n, a_s = (np.asarray(a).ravel() for a in ACCELERATIONS(p, pd, pdd, model.parameters))
    f_h, f_n, f_s = (np.asarray(f).ravel() for f in SPECIFIC_FORCES(p, pd, pdd, model.parameters))
    return np.array([*pd[:3], p[3] - p[2], *a_h, a_n[1], *a_s, pdd[2], *f_h, f_n[1], *f_s])


@pytest.fixture
def operating_point() -> tuple[np.ndarray, float, np.ndarray]:
    """A moving, deflected state (both tyres in contact) with cylinder force and inputs."""
    x = np.array([0.004, 0.05, -0.006, -0.03, 0.012, 0.2, -0.02, 0.35])
    w = np.array([0.001, 0.003, -0.002, 0.002, 0.01, -0.02, 0.03, 0.01, 150.0, -80.0, 40.0])
    return x, 0.0, w


def _assert_close(actual: np.ndarray, reference: np.ndarray) -> None:
    # central differences with relative steps of 1e-6 are accurate to ~1e-9 of the largest entry;
    # the bar is a relative error of 1e-6
    scale = max(np.abs(reference).max(), 1.0)
    np.testing.assert_allclose(actual, reference, rtol=1e-6, atol=1e-6 * scale)


def test_linearisation_matches_finite_differences(
    paper_layout: dict[str, float], operating_point: tuple[np.ndarray, float, np.ndarray]
) -> None:
    model = LoaderDynamics(paper_layout)
    x, _, w = operating_point
    u = model.static_cylinder_force_N * 1.05
    p, pd = x[0::2], x[1::2]
    linear = model.linearise(p, pd, u, w[0:4], w[4:8], w[8:11])
    steps_x = 1e-6 * np.maximum(np.abs(x), 1.0)
    a_fd = central_difference(lambda z: _state_derivative(model, z, u, w), x, steps_x)
    b_fd = central_difference(
        lambda z: _state_derivative(model, x, z[0], w), np.array([u]), np.array([1e-3 * abs(u)])
    )
    e_fd = central_difference(
        lambda z: _state_derivative(model, x, u, z), w, 1e-6 * np.maximum(np.abs(w), 1.0)
    )
    c_fd = central_difference(lambda z: _outputs(model, z, u, w), x, steps_x)
    du_fd = central_difference(
        lambda z: _outputs(model, x, z[0], w), np.array([u]), np.array([1e-3 * abs(u)])
    )
    dw_fd = central_difference(
        lambda z: _outputs(model, x, u, z), w, 1e-6 * np.maximum(np.abs(w), 1.0)
    )
    for actual, reference in (
        (linear.A, a_fd),
        (linear.B, b_fd),
        (linear.E, e_fd),
        (linear.C, c_fd),
        (linear.D_u, du_fd),
        (linear.D_w, dw_fd),
    ):
        _assert_close(actual, reference)


def test_state_space_has_named_signals(paper_layout: dict[str, float]) -> None:
    system = LoaderDynamics(paper_layout).linearise().state_space()
    assert system.state_labels == list(STATE_NAMES)
    assert system.output_labels == list(OUTPUT_NAMES)
    assert system.input_labels[0] == "F_act" and "M_d" in system.input_labels
    assert system.nstates == 8 and system.ninputs == 12


def test_static_equilibrium_is_an_equilibrium(paper_layout: dict[str, float]) -> None:
    model = LoaderDynamics(paper_layout)
    np.testing.assert_allclose(model.forward_dynamics(np.zeros(4), np.zeros(4)), 0.0, atol=1e-9)
    g = paper_layout["g"]
    total_weight = g * (paper_layout["m_1"] + paper_layout["m_2"])
    np.testing.assert_allclose(
        model.parameter("F_Ay0") + model.parameter("F_By0"), total_weight, rtol=1e-12
    )


def test_tyre_loses_contact_instead_of_pulling(paper_layout: dict[str, float]) -> None:
    """The road drops 0.2 m under A, far beyond the tyre's static deflection: the front tyre
    carries nothing, so the accelerations equal those of the same loader without a front tyre."""
    model = LoaderDynamics(paper_layout)
    assert model.parameter("F_Ay0") / paper_layout["k_Ay"] < 0.05
    road_down = (0.01, -0.2, 0.0, 0.0)
    # a front tyre far from the ground: no stiffness, a negative preload (below the transition)
    no_front_tyre = dict(paper_layout, k_Ax=0.0, k_Ay=0.0, c_Ax=0.0, c_Ay=0.0, F_Ay0=-1e3)
    no_front_tyre["F_By0"] = model.parameter("F_By0")
    # Lifted with a relaxed horizontal spring (anchor where the contact point now is), the front
    # tyre carries nothing; with a stretched one, its spring relaxes at 1/tau_slip instead.
    relaxed = (-road_down[0], 0.0)
    lifted = model.forward_dynamics(np.zeros(4), np.zeros(4), road_m=road_down, anchor_m=relaxed)
    contact = model.tyre_contact(np.zeros(4), anchor_m=relaxed, road_m=road_down)
    np.testing.assert_allclose(contact["F_tyre"][:2], [0.0, 0.0], rtol=0, atol=1e-12)
    stretched = model.tyre_contact(np.zeros(4), road_m=road_down)
    stretch = -road_down[0]
    tau = paper_layout["tau_slip"]
    np.testing.assert_allclose(stretched["anchor_rate"][0], stretch / tau, rtol=1e-12)
    reference = LoaderDynamics(
        no_front_tyre, equilibrium=False, check_ranges=False
    ).forward_dynamics(np.zeros(4), np.zeros(4), force_N=model.static_cylinder_force_N)
    np.testing.assert_allclose(lifted, reference, rtol=1e-12, atol=1e-12)
    assert lifted[1] < -1.0  # and the unsupported loader falls
