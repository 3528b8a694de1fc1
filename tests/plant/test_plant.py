"""The plant Function: parameter order, static equilibrium, AD linearisation against finite
differences, oil mass conservation, Table 1 from the plant."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

import loader_model_generated as generated
from loader_model.plant.equilibrium import static_state
from loader_model.plant.linear import linearise_plant
from loader_model.plant.plant import EXOGENOUS_NAMES, OUTPUT_NAMES, STATE_NAMES, plant_function
from loader_model.plant.plant_parameters import (
    HYDRAULIC_PARAMETERS,
    OCCUPANT_PARAMETERS,
    PLANT_PARAMETER_NAMES,
    PLANT_PARAMETER_UNITS,
    PlantOptions,
    plant_parameter_vector,
)
from tests.numerics import central_difference

OPTIONS = {
    "drive": PlantOptions(),
    "accumulator": PlantOptions(accumulator=True),
    "closed": PlantOptions.closed(),
    "baseline": PlantOptions.for_controller("baseline"),
    "passive": PlantOptions.for_controller("passive"),
}


def test_parameter_vector_matches_the_function_inputs() -> None:
    plant = plant_function()
    assert plant.name_in() == ["x", "u", "w", "params"]
    assert plant.name_out() == ["xdot", "y"]
    assert plant.size1_in(3) == len(PLANT_PARAMETER_NAMES)
    assert plant.size1_in(0) == len(STATE_NAMES) and plant.size1_in(2) == len(EXOGENOUS_NAMES)
    assert plant.size1_out(1) == len(OUTPUT_NAMES)
    assert PLANT_PARAMETER_NAMES[: len(generated.PARAMETER_NAMES)] == generated.PARAMETER_NAMES
    assert len(set(PLANT_PARAMETER_NAMES)) == len(PLANT_PARAMETER_NAMES)
    assert set(PLANT_PARAMETER_UNITS) == set(PLANT_PARAMETER_NAMES)
    vector = plant_parameter_vector(None, "empty")
    assert vector.shape == (len(PLANT_PARAMETER_NAMES),) and np.all(np.isfinite(vector))
    named = dict(zip(PLANT_PARAMETER_NAMES, vector, strict=True))
    assert named["K_oil"] == 1.64e9 and named["f_C"] == 1.07e-4  # Table 5, Table 4
    assert named["omega_p"] == pytest.approx(2 * np.pi * 22.3, rel=1e-15)  # Table 2
    added = len(HYDRAULIC_PARAMETERS) + len(OCCUPANT_PARAMETERS)
    assert added == len(PLANT_PARAMETER_NAMES) - len(generated.PARAMETER_NAMES)


@pytest.mark.parametrize("load", ["empty", "full"])
@pytest.mark.parametrize("option", list(OPTIONS))
def test_static_state_is_an_equilibrium(load: str, option: str) -> None:
    params = plant_parameter_vector(None, load, OPTIONS[option])
    state, command = static_state(params)
    rates, outputs = plant_function()(state, command, np.zeros(len(EXOGENOUS_NAMES)), params)
    rates = np.asarray(rates).ravel()
    named = dict(zip(OUTPUT_NAMES, np.asarray(outputs).ravel(), strict=True))
    np.testing.assert_allclose(rates[:10], 0.0, atol=1e-12)  # p̈, ξ̇
    # pressure rates: round-off of K_oil/V (1e12 Pa/m³) times flows of 1e-4 m³/s; measured at
    # most 3.0e-6 Pa/s (accumulator on: the orifice's laminar conductance at a round-off Δp)
    # behind closed load-holding valves the piston seals leak from A to B (quasi-static state):
    # ṗ_A = −K Q_seal / V_A, ṗ_B = +K Q_seal / V_B with Q_seal = n k_seal (p_A − p_B)
    theta = dict(zip(PLANT_PARAMETER_NAMES, params, strict=True))
    seal = (1 - theta["holding_open"]) * theta["leakage_on"] * theta["n_cyl"] * theta["k_seal"]
    seal *= named["p_A"] - named["p_B"]
    area = np.pi / 4 * theta["d_piston"] ** 2
    annulus = area - np.pi / 4 * theta["d_rod"] ** 2
    v_a = theta["n_cyl"] * (area * named["x_piston"] + theta["V_dead_A"])
    v_b = theta["n_cyl"] * (annulus * (theta["stroke"] - named["x_piston"]) + theta["V_dead_B"])
    expected = theta["K_oil"] * seal * np.array([-1 / v_a, 1 / v_b])
    np.testing.assert_allclose(rates[10:12], expected, rtol=1e-9, atol=1e-5)
    np.testing.assert_allclose(rates[12:], 0.0, atol=1e-9)
    # accelerometers read gravity only, the seat pad too; the rod side sits at charge pressure
    assert named["f_Hy"] == pytest.approx(9.81, rel=1e-12)
    assert named["f_Py"] == pytest.approx(9.81, rel=1e-12) and abs(named["f_Px"]) < 1e-12
    assert named["p_B"] == pytest.approx(2.0e6, rel=1e-15)
    # measured static piston pressures (gauge): 89.3 bar (340 kg), 129.7 bar (770 kg)
    expected_bar = {"empty": 89.28, "full": 129.74}[load]
    assert named["p_A"] / 1e5 == pytest.approx(expected_bar, abs=0.01)


@pytest.mark.parametrize("option", ["drive", "accumulator", "passive"])
def test_ad_linearisation_matches_finite_differences(option: str) -> None:
    """At a moving, off-equilibrium point with every part of the drive active."""
    params = plant_parameter_vector(None, "full", OPTIONS[option])
    state, command = static_state(params)
    rng = np.random.default_rng(7)
    scale = np.array(
        [1e-3] * 4 + [0.05] * 4 + [1e-3] * 2 + [3e5, 1e5, 2e-6, 1e-4, 2e-5] + [1e-3, 0.02] * 4
    )
    x = state + scale * rng.standard_normal(len(STATE_NAMES))
    u = command + 3e-6
    w = np.array([1e-3, 2e-3, -1e-3, 1e-3, 0.01, 0.05, -0.02, 0.03, 100.0, -50.0, 20.0])
    linear = linearise_plant(params, x, u, w)
    plant = plant_function()

    def rates(xx, uu, ww):
        return np.asarray(plant(xx, uu, ww, params)[0]).ravel()

    def outputs(xx, uu, ww):
        return np.asarray(plant(xx, uu, ww, params)[1]).ravel()

    steps_x = 1e-6 * np.maximum(np.abs(x), scale)
    steps_w = 1e-6 * np.maximum(np.abs(w), 1e-3)
    references = {
        "A": central_difference(lambda z: rates(z, u, w), x, steps_x),
        "B": central_difference(lambda z: rates(x, z[0], w), np.array([u]), np.array([1e-9])),
        "E": central_difference(lambda z: rates(x, u, z), w, steps_w),
        "C": central_difference(lambda z: outputs(z, u, w), x, steps_x),
        "D_u": central_difference(lambda z: outputs(x, z[0], w), np.array([u]), np.array([1e-9])),
        "D_w": central_difference(lambda z: outputs(x, u, z), w, steps_w),
    }
    for name, reference in references.items():
        actual = getattr(linear, name)
        # central differences are accurate to ~1e-8 of each row's largest entry
        row_scale = np.maximum(np.abs(reference).max(axis=1, keepdims=True), 1e-12)
        np.testing.assert_allclose(
            actual / row_scale, reference / row_scale, rtol=0, atol=1e-6, err_msg=name
        )


def _oil_mass(states: np.ndarray, params: np.ndarray) -> np.ndarray:
    """Σ V_i e^(p_i/K) + V_acc: oil mass over the reference density (Eq. 36, 37 with a constant
    bulk modulus; the accumulator's oil at the reference density)."""
    named = dict(zip(PLANT_PARAMETER_NAMES, params, strict=True))
    n = named["n_cyl"]
    piston = np.pi / 4 * named["d_piston"] ** 2
    annulus = piston - np.pi / 4 * named["d_rod"] ** 2
    plant = plant_function()
    masses = []
    for row in states:
        outputs = np.asarray(plant(row, 0.0, np.zeros(11), params)[1]).ravel()
        position = outputs[OUTPUT_NAMES.index("x_piston")]
        v_a = n * (piston * position + named["V_dead_A"])
        v_b = n * (annulus * (named["stroke"] - position) + named["V_dead_B"])
        k_oil = named["K_oil"]
        masses.append(v_a * np.exp(row[10] / k_oil) + v_b * np.exp(row[11] / k_oil) + row[14])
    return np.array(masses)


@pytest.mark.parametrize("accumulator", [False, True])
def test_oil_mass_is_conserved_without_leakage_and_pump_flow(accumulator: bool) -> None:
    """5 s over a board with the chambers closed (and the accumulator connected): the oil mass
    of chambers (plus accumulator) stays constant to the solver tolerance."""
    options = PlantOptions(
        pump=False, valves=False, leakage=False, friction=True, accumulator=accumulator
    )
    params = plant_parameter_vector(None, "empty", options)
    state, _ = static_state(params)
    time, x = ca.SX.sym("t"), ca.SX.sym("x", len(STATE_NAMES))
    bump = ca.if_else(
        ca.logic_and(time > 0.2, time < 0.4), 0.02 * ca.sin(np.pi * (time - 0.2) / 0.2) ** 2, 0
    )
    road = ca.vertcat(0, bump, 0, 0)
    w = ca.vertcat(road, ca.jtimes(road, time, ca.SX(1.0)), ca.SX.zeros(3))
    rates = plant_function()(x, 0.0, w, params)[0]
    grid = np.linspace(0.0, 5.0, 501)
    options_cvodes = {"reltol": 1e-10, "abstol": 1e-12, "max_step_size": 0.01}
    integrator = ca.integrator(
        "oil", "cvodes", {"x": x, "t": time, "ode": rates}, 0.0, grid, options_cvodes
    )
    states = np.asarray(integrator(x0=state)["xf"]).T
    assert np.ptp(states[:, 10]) > 1e5  # the piston pressure really swings (Pa)
    if accumulator:
        assert np.ptp(states[:, 14]) > 1e-6  # oil moves through the orifice (m³)
    mass = _oil_mass(states, params)
    drift = np.abs(mass - mass[0]).max() / mass[0]
    assert drift < 1e-11, drift  # measured 4.6e-13 (chambers), 1.5e-13 (with accumulator)


@pytest.mark.parametrize(
    ("updates", "match"),
    [
        ({"hydraulics.bulk_modulus": 0.0}, r"hydraulics.bulk_modulus = 0.0 Pa is out of range"),
        ({"cylinders.dead_volume_a": -1e-4}, r"cylinders.dead_volume_a = -0.0001 m\^3 is out of"),
        ({"pump.displacement_rate_limit": -1.24e-3}, r"pump.displacement_rate_limit = -0.00124"),
        (
            {"accumulator.precharge_pressure": 3e7},
            r"accumulator.precharge_pressure = 30000000.0 Pa",
        ),
        (
            {"hydraulics.relief_pressure": 5e6},
            r"accumulator.precharge_pressure = 5000000.0 Pa must be below hydraulics.relief_pr",
        ),
        ({"hydraulics.oil_density": 0.0}, r"hydraulics.oil_density = 0.0 kg/m\^3 is out of range"),
    ],
)
def test_bad_hydraulic_parameters_are_refused_by_name(updates, match) -> None:
    from loader_model.parameters.sets import default_loader, replace

    with pytest.raises(ValueError, match=match):
        replace(default_loader(), updates)
