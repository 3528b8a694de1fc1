"""The plant's power balance (loader_model/plant/energy.py) at random states, and its pieces.

dE/dt by forward AD through the plant's xdot (plus the road displacement's own rate) must equal
the input powers minus the losses at any state, input and parameter set, to round-off: a check
of the stored energy being a true state function of the plant that integrates, independent of
any integrator. States are drawn wide: tyres off the ground, cylinders in their end stops, relief
and check valves open, the accumulator empty, cavitating chambers. Measured over 300 seeded states
of ``_case``: worst |dE/dt − P_net| 2.0e-13 of the largest power; with the textbook p²V/(2K) and
p Q in place of Ψ and π Q, 1.1e-2 (50 states): the test tells the two apart.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.plant import components as hyd
from loader_model.plant.energy import (
    ENERGY_NAMES,
    INPUT_POWER_NAMES,
    LOSS_NAMES,
    energy_function,
    energy_rate_function,
)
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import STATE_NAMES
from loader_model.plant.plant_parameters import (
    PLANT_PARAMETER_NAMES,
    PlantOptions,
    plant_parameter_vector,
)

OPTIONS = (
    PlantOptions(),
    PlantOptions(accumulator=True),
    PlantOptions.closed(),
    PlantOptions.for_controller("baseline"),
    PlantOptions.for_controller("passive"),
)
#: Spread of the random states around the static equilibrium (state order of STATE_NAMES).
SPREAD = np.array(
    [0.02, 0.03, 0.03, 0.3, 0.5, 0.5, 0.5, 1.0, 0.005, 0.005, 8e6, 2e6, 3e-5, 2e-3, 4e-4]
    + [0.01, 0.2] * 4  # the occupant (outside the energy balance: it must not disturb it)
)


def _case(seed: int, load: str, option: int, isothermal: bool) -> tuple[np.ndarray, ...]:
    params = plant_parameter_vector(None, load, OPTIONS[option])
    if isothermal:
        params[PLANT_PARAMETER_NAMES.index("n_poly")] = 1.0
    x0, u0 = static_state(params)
    rng = np.random.default_rng(seed)
    x = x0 + SPREAD * rng.uniform(-1.0, 1.0, x0.size)
    x[STATE_NAMES.index("p_A")] = rng.uniform(-0.5e5, 2.6e7)  # to beyond the relief setting
    # the oil in the accumulator stays below its volume V_0 (the gas pressure diverges there)
    x[STATE_NAMES.index("V_acc")] = (
        rng.uniform(0.0, 0.95) * params[PLANT_PARAMETER_NAMES.index("V_0")]
    )
    w = np.concatenate([rng.normal(0, 0.02, 4), rng.normal(0, 0.5, 4), rng.normal(0, 500.0, 3)])
    u = np.array([u0 * rng.uniform(-3.0, 3.0)])
    return x, u, w, rng.normal(0, 0.5, 4), params


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    load=st.sampled_from(("empty", "full")),
    option=st.integers(0, len(OPTIONS) - 1),
    isothermal=st.booleans(),
)
def test_stored_energy_rate_equals_inputs_minus_losses(
    seed: int, load: str, option: int, isothermal: bool
) -> None:
    x, u, w, road_velocity, params = _case(seed, load, option, isothermal)
    rate, net = (float(v) for v in energy_rate_function()(x, u, w, road_velocity, params))
    _, _, inputs, losses, _ = energy_function()(x, u, w, road_velocity, params)
    scale = np.abs(np.concatenate([np.asarray(inputs), np.asarray(losses)])).max()
    assert scale > 1.0  # watts: the state really moves energy
    assert rate == pytest.approx(net, rel=0, abs=1e-10 * scale)


def test_equilibrium_stores_and_balances() -> None:
    """At rest the pump's power goes into leakage and nothing else moves (accumulator on)."""
    params = plant_parameter_vector(None, "full", PlantOptions(accumulator=True))
    x0, u0 = static_state(params)
    energy, parts, inputs, losses, _ = energy_function()(x0, u0, np.zeros(11), np.zeros(4), params)
    parts, inputs, losses = (np.asarray(v).ravel() for v in (parts, inputs, losses))
    assert len(parts) == len(ENERGY_NAMES) and float(energy) == pytest.approx(parts.sum())
    pump, leakage = inputs[INPUT_POWER_NAMES.index("pump")], losses[LOSS_NAMES.index("leakage")]
    assert pump > 100.0 and pump == pytest.approx(leakage, rel=1e-9)
    assert parts[ENERGY_NAMES.index("kinetic")] == 0.0
    assert parts[ENERGY_NAMES.index("oil_A")] > 0.0 and parts[ENERGY_NAMES.index("gas")] > 0.0


@pytest.mark.parametrize("exponent", [1.0, 1.0 + 1e-7, 1.4])
def test_gas_energy_is_the_integral_of_the_gas_pressure(exponent: float) -> None:
    volume = ca.SX.sym("V")
    energy = hyd.accumulator_gas_energy(5e6, 1e-3, exponent, volume)
    pressure = hyd.accumulator_gas_pressure(5e6, 1e-3, exponent, volume)
    check = ca.Function("check", [volume], [ca.gradient(energy, volume), pressure, energy])
    for oil in (-2e-5, 1e-9, 3e-4, 6e-4):
        slope, gauge, _ = (float(v) for v in check(oil))
        assert slope == pytest.approx(gauge, rel=1e-9)
    # closed form of the isothermal gas: p0 V0 ln(V0 / (V0 − V)) − p_atm V
    absolute = 5e6 + hyd.ATMOSPHERIC_PRESSURE_PA
    isothermal = absolute * 1e-3 * np.log(1e-3 / 0.7e-3) - hyd.ATMOSPHERIC_PRESSURE_PA * 3e-4
    assert float(check(3e-4)[2]) == pytest.approx(isothermal, rel=1e-6 if exponent < 1.1 else 1)


def test_compression_energy_tends_to_the_linear_law() -> None:
    """Ψ = V (π(p) − p) → p² V / (2 K) for p ≪ K; 100 bar in 1 l at K = 1.64 GPa: 30.5 J."""
    psi = float(hyd.compression_energy(1.64e9, 1e-3, 1e7))
    assert psi == pytest.approx(1e14 * 1e-3 / (2 * 1.64e9), rel=4e-3)
    assert float(hyd.flow_power_pressure(1.64e9, 1e7)) == pytest.approx(
        1e7 * (1 + 1e7 / 3.28e9), rel=1e-5
    )
