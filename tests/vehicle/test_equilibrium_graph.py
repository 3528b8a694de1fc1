"""The static equilibrium inside the CasADi graph (generated ``complete_parameters``) and the
accelerometer outputs (generated ``specific_forces``)."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

import loader_model_generated as generated
from loader_model.vehicle.dynamics import LoaderDynamics

NAMES = list(generated.PARAMETER_NAMES)
G = 9.81


def _at_rest_accelerations(params: ca.MX) -> ca.MX:
    completed, force = generated.function("complete_parameters")(params)
    z4, z3 = ca.MX.zeros(4), ca.MX.zeros(3)
    pdd, anchor_rate = generated.function("forward_dynamics")(
        z4, z4, ca.MX.zeros(2), force, z4, z4, z3, completed
    )
    return ca.vertcat(pdd, anchor_rate)


@pytest.mark.parametrize("load", ["empty", "full"])
def test_raised_boom_mass_stays_at_rest_inside_the_graph(load: str) -> None:
    """m_2 raised 10 % as a symbol of the graph: the completed parameters keep p̈ = 0.

    Before the equilibrium was in the graph the same change gave p̈ = (0.088, −0.074, −0.021,
    −0.311) (issue 7).
    """
    base = LoaderDynamics.from_parameters(None, load).parameters
    scale = ca.MX.sym("scale")
    index = NAMES.index("m_2")
    params = ca.vertcat(ca.MX(base[:index]), scale * base[index], ca.MX(base[index + 1 :]))
    rest = ca.Function("rest", [scale], [_at_rest_accelerations(params)])
    np.testing.assert_allclose(np.asarray(rest(1.1)).ravel(), 0.0, rtol=0, atol=1e-12)


def test_derivative_of_static_loads_matches_finite_differences() -> None:
    base = LoaderDynamics.from_parameters(None, "full").parameters
    params = ca.MX.sym("params", len(NAMES))
    completed, force = generated.function("complete_parameters")(params)
    loads = ca.vertcat(completed[NAMES.index("F_Ay0")], completed[NAMES.index("F_By0")], force)
    jacobian = ca.Function("dloads", [params], [ca.jacobian(loads, params)])
    evaluate = ca.Function("loads", [params], [loads])
    analytic = np.asarray(jacobian(base))
    for name in ("m_1", "m_2", "G_x", "D_y", "E_x", "g"):
        k = NAMES.index(name)
        step = 1e-6 * max(abs(base[k]), 1.0)
        plus, minus = base.copy(), base.copy()
        plus[k] += step
        minus[k] -= step
        central = (np.asarray(evaluate(plus)) - np.asarray(evaluate(minus))).ravel() / (2 * step)
        np.testing.assert_allclose(analytic[:, k], central, rtol=1e-7, atol=1e-6, err_msg=name)


@pytest.mark.parametrize("pitch_rad", [-0.3, -0.01, 0.0, 0.01, 0.2])
def test_resting_pitched_loader_reads_gravity(pitch_rad: float) -> None:
    """At rest with the chassis pitched by θ1, every accelerometer reads (g sin θ1, g cos θ1).

    The specific force at rest is +g ŷ (the ground pushes up); the chassis x axis is
    (cos θ1, sin θ1), so a nose-up loader (θ1 > 0) reads +g sin θ1 along it. Issue 7 wrote
    −g sin θ1; that holds for x pointing backwards or for clockwise pitch, not for this frame.
    """
    model = LoaderDynamics.from_parameters(None, "empty")
    p = np.array([0.0, 0.0, pitch_rad, pitch_rad - 0.1])
    readings = model.specific_forces(p, np.zeros(4), np.zeros(4))
    expected = G * np.array([np.sin(pitch_rad), np.cos(pitch_rad)])
    for point in "HNS":
        np.testing.assert_allclose(readings[point], expected, rtol=0, atol=1e-12, err_msg=point)


def test_specific_force_adds_rotation_terms_off_the_centre() -> None:
    """At N (ahead of H) a pitch acceleration θ̈ adds N_x θ̈ to the vertical reading and a pitch
    rate adds the centripetal −N_x θ̇² along x (closed form, θ1 = 0)."""
    model = LoaderDynamics.from_parameters(None, "empty")
    n_x, n_y = model.parameter("N_x"), model.parameter("N_y")
    rate, acceleration = 0.5, 3.0
    pd = np.array([0.0, 0.0, rate, 0.0])
    pdd = np.array([0.0, 0.0, acceleration, 0.0])
    reading = model.specific_forces(np.zeros(4), pd, pdd)["N"]
    expected = [-n_x * rate**2 - n_y * acceleration, G + n_x * acceleration - n_y * rate**2]
    np.testing.assert_allclose(reading, expected, rtol=1e-13, atol=1e-13)
