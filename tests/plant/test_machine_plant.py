"""The plant of a described machine other than the skid-steer: the compact wheel loader (issue 23).

Its static equilibrium is a fixed point (open load-holding valves: |ẋ| below 1e-9 in every state;
closed: only the piston seals' leakage moves the pressures, as for the skid-steer), its
linearisation agrees with central finite differences, and its power balance holds to round-off
with the locked tilt cylinder's spring and damper booked. The skid-steer's layout is the paper's.
"""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.plant.energy import energy_names, energy_rate_function
from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import plant_layout
from loader_model.plant.linear import linearise_plant, undamped_matrices_from_plant
from loader_model.plant.machine_parameters import machine_plant_parameter_vector
from loader_model.plant.plant import (
    EXOGENOUS_NAMES,
    OUTPUT_NAMES,
    STATE_NAMES,
    plant_function,
)
from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES, PlantOptions
from loader_model.plant.scenario import resolve_plant

MACHINE = "compact_wheel_loader"


def _params(controller: str = "skyhook", load: str | None = None, **changes: bool) -> np.ndarray:
    options = PlantOptions.for_controller(controller)
    if changes:
        from dataclasses import replace

        options = replace(options, **changes)
    return machine_plant_parameter_vector(plant_layout(MACHINE), None, load, options)


def test_skid_steer_layout_is_the_papers() -> None:
    layout = plant_layout()
    assert layout.state_names == STATE_NAMES
    assert layout.output_names == OUTPUT_NAMES
    assert layout.exogenous_names == EXOGENOUS_NAMES
    assert layout.parameter_names == PLANT_PARAMETER_NAMES


def test_wheel_loader_layout() -> None:
    layout = plant_layout(MACHINE)
    assert layout.state_names[:5] == ("x_H", "y_H", "theta_1", "theta_2", "theta_3")
    assert layout.index("p_A") == 12
    assert "psi" in layout.output_names and "F_By" in layout.output_names
    function = plant_function(MACHINE)
    assert function.size1_in(0) == len(layout.state_names)
    assert function.size1_out(1) == len(layout.output_names)
    assert function.size1_in(3) == len(layout.parameter_names)
    assert plant_function(MACHINE) is function


@pytest.mark.parametrize("load", [None, "empty"])
def test_open_valves_equilibrium_is_a_fixed_point(load: str | None) -> None:
    params = _params("skyhook", load)
    x0, u0 = static_state(params, MACHINE)
    xdot, _ = plant_function(MACHINE)(x0, u0, np.zeros(11), params)
    assert np.max(np.abs(np.asarray(xdot).ravel())) < 1e-9


def test_closed_valves_equilibrium_drifts_by_the_seals_only() -> None:
    layout = plant_layout(MACHINE)
    x0, u0 = static_state(_params("baseline"), MACHINE)
    xdot = np.asarray(plant_function(MACHINE)(x0, u0, np.zeros(11), _params("baseline"))[0])
    xdot = xdot.ravel()
    pressures = [layout.index("p_A"), layout.index("p_B")]
    others = np.delete(xdot, pressures)
    assert np.max(np.abs(others)) < 1e-9
    assert 10.0 < abs(xdot[pressures[0]]) < 1e3  # Pa/s: the seals' leakage through the piston
    sealed = _params("baseline", leakage=False)
    x0, u0 = static_state(sealed, MACHINE)
    xdot = np.asarray(plant_function(MACHINE)(x0, u0, np.zeros(11), sealed)[0]).ravel()
    assert np.max(np.abs(xdot)) < 1e-9


def test_static_outputs() -> None:
    scenario = resolve_plant(None, "full", PlantOptions(), machine=MACHINE)
    assert scenario.layout == plant_layout(MACHINE)
    assert scenario.output("p_A") == pytest.approx(41.34e5, rel=1e-3)
    assert scenario.output("F_Ay") + scenario.output("F_By") == pytest.approx(
        (4200 + 450 + 950) * 9.80665, rel=1e-9
    )
    assert scenario.output("f_Sy") == pytest.approx(9.80665, rel=1e-6)
    empty = scenario.with_options(PlantOptions.for_controller("passive"))
    assert empty.layout is scenario.layout and empty.parameter("accumulator_on") == 1.0


def test_linearisation_matches_finite_differences() -> None:
    params = _params("skyhook")
    linear = linearise_plant(params, machine=MACHINE)
    function = plant_function(MACHINE)
    x0, u0 = linear.operating_state, linear.operating_input
    layout = plant_layout(MACHINE)
    scale = np.ones(x0.size)
    scale[[layout.index(n) for n in ("p_A", "p_B")]] = 1e4
    scale[[layout.index(n) for n in ("V_p", "Vd_p", "V_acc")]] = 1e-6
    step = 1e-6 * scale
    columns = []
    for k in range(x0.size):
        dx = np.zeros(x0.size)
        dx[k] = step[k]
        plus = np.asarray(function(x0 + dx, u0, np.zeros(11), params)[0]).ravel()
        minus = np.asarray(function(x0 - dx, u0, np.zeros(11), params)[0]).ravel()
        columns.append((plus - minus) / (2 * step[k]))
    numeric = np.column_stack(columns)
    error = np.abs(numeric - linear.A) * scale[None, :]
    assert np.max(error) < 1e-5 * np.max(np.abs(linear.A) * scale[None, :])
    system = linear.state_space()
    assert "theta_3" in system.state_labels and "xi_A" not in system.state_labels


def test_undamped_matrices() -> None:
    mass, stiffness, k_eq = undamped_matrices_from_plant(
        machine_plant_parameter_vector(plant_layout(MACHINE), None, None, PlantOptions.closed()),
        machine=MACHINE,
    )
    assert mass.shape == (5, 5) and stiffness.shape == (5, 5)
    assert np.all(np.linalg.eigvalsh(mass) > 0)
    assert k_eq > 1e6


def test_power_balance_at_random_states() -> None:
    names, losses = energy_names(plant_layout(MACHINE))
    assert names[-1] == "internal" and losses[-1] == "internal"
    params = _params("skyhook", occupant=False)
    x0, u0 = static_state(params, MACHINE)
    rng = np.random.default_rng(3)
    rate = energy_rate_function(plant_layout(MACHINE))
    for _ in range(20):
        x = (
            x0
            + rng.normal(0.0, 1.0, x0.size)
            * np.r_[[0.01] * 5, [0.2] * 5, [0.002] * 2, 2e5, 1e5, 1e-6, 1e-5, 0.0, [0.0] * 8]
        )
        w = rng.normal(0.0, 0.01, 11)
        road_velocity = rng.normal(0.0, 0.1, 4)
        de_dt, p_net = (float(v) for v in rate(x, u0, w, road_velocity, params))
        assert de_dt == pytest.approx(p_net, abs=1e-9 * max(1.0, abs(p_net)) + 1e-6)
