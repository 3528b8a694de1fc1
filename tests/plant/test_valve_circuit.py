"""The valve-controlled lift circuit against closed forms (Merritt, Hydraulic Control Systems).

Steady flows of the valve (:mod:`loader_model.plant.valve_circuit`, the function the plant
calls) against the orifice equation Q = C_d w o √(2 Δp / ρ) over a grid of spool positions and
pressure drops: compensated (Q = K_q o while the supply holds the compensator's drop, the orifice
law with the whole drop when it does not), uncompensated, and the meter-out edge; each with the
spool's leakage G_s (p − p_T). Outside the smoothing bands the laws are exact, so the tolerance
is round-off: measured at most 3.0e-16 relative (2.2e-16 with the parameters as inputs), held
at 1e-12.

The valve-cylinder's hydraulic natural frequency (Merritt ch. 5): with the rod side sealed by the
spool and the compensated meter-in edge's K_c = 0, the boom on its cylinders is a mass on the oil
spring of both chambers, k_h = n β A_p² (1/V_A + α²/V_B) (the single-rod form of errata 6 of the
paper's Eq. 28), so ω_h = (dx_cyl/dφ) √(k_h / J_D). The compact wheel loader's mechanics with the
valve circuit (no derivation: the plant takes the circuit as an argument), its chassis held by
tyres 1e5 times stiffer and its bucket locked to the boom, linearised by CasADi's AD at its
static equilibrium: the hydraulic mode within 0.1 % of ω_h = 112.04 rad/s (measured 112.03 rad/s,
0.009 %: gravity's and the cylinder force's geometric stiffness, the chassis' residual compliance;
a property of the model, not of the CPU).
"""

from __future__ import annotations

import functools
import math
import tomllib
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from loader_model.parameters.valve import ValveParameters
from loader_model.plant import valve_circuit as valve
from loader_model.plant.equilibrium import equilibrium_function
from loader_model.plant.layout import plant_layout
from loader_model.plant.machine_parameters import (
    machine_plant_parameter_vector,
    valve_plant_entries,
)
from loader_model.plant.plant import build_plant
from loader_model.plant.plant_parameters import PlantOptions

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "valve_wheel_loader"
RTOL = 1e-12  # exact laws outside the bands: round-off (measured <= 3.0e-16)


def _example_valve() -> ValveParameters:
    raw = tomllib.loads((EXAMPLE / "valve_wheel_loader_values.toml").read_text("utf-8"))
    return ValveParameters(**{name: item["value"] for name, item in raw["valve"].items()})


def _theta(**changes: float) -> dict[str, float]:
    theta = valve_plant_entries(_example_valve(), "load_sensing")
    theta |= {"rho_oil": 870.0, "G_check": 1e-9, "p_relief": 2.5e7, "G_relief": 1e-9}
    theta |= {"n_cyl": 2.0, "k_seal": 1e-16, "valves_on": 1.0, "pump_on": 1.0}
    theta |= {"leakage_on": 1.0, "holding_open": 1.0, "Q_supply_max": 1.0}  # no flow limit
    return theta | changes


@functools.cache
def _flow_function() -> tuple[list[str], list[str], ca.Function]:
    """The valve's flows as one Function of (p_A, p_B, x_s) and the parameters (built once)."""
    keys = sorted(_theta())
    symbols, values = ca.SX.sym("s", 3), ca.SX.sym("theta", len(keys))
    theta = {name: values[k] for k, name in enumerate(keys)}
    flows = valve.valve_circuit_flows(theta, symbols[0], symbols[1], symbols[2])
    names = sorted(flows)
    outputs = ca.vertcat(*(flows[n] for n in names))
    return keys, names, ca.Function("flows", [symbols, values], [outputs])


def _flows(theta: dict[str, float], p_a: float, p_b: float, spool: float) -> dict[str, float]:
    keys, names, function = _flow_function()
    result = function([p_a, p_b, spool], [theta[k] for k in keys])
    return dict(zip(names, np.asarray(result, dtype=float).ravel(), strict=True))


def _orifice(theta: dict[str, float], spool: float, drop: float) -> float:
    """Merritt's orifice equation with the edge's opening (the C¹ ramp's b/2 beyond the lap)."""
    opening = abs(spool) - theta["x_s_lap"] - valve.OPENING_BAND_M / 2
    return theta["C_d_s"] * theta["w_s"] * opening * math.sqrt(2 * drop / theta["rho_oil"])


SPOOL_FRACTIONS = (0.05, 0.2, 0.5, 0.8, 0.98)


@pytest.mark.parametrize("fraction", SPOOL_FRACTIONS)
@pytest.mark.parametrize("p_a_bar", [5.0, 30.0, 100.0, 200.0])
def test_compensated_flow_is_the_flow_gain_times_the_opening(
    fraction: float, p_a_bar: float
) -> None:
    """Load sensing: p_s = p_A + Δp_LS, so the compensator holds Δp_c: Q = K_q o, any load."""
    theta = _theta()
    spool, p_a = fraction * theta["x_s_max"], p_a_bar * 1e5
    flows = _flows(theta, p_a, theta["p_tank"], spool)
    opening = spool - valve.OPENING_BAND_M / 2
    k_q = theta["C_d_s"] * theta["w_s"] * math.sqrt(2 * theta["dp_comp"] / theta["rho_oil"])
    assert float(valve.flow_gain(theta)) == pytest.approx(k_q, rel=RTOL)
    assert flows["supply_pressure"] == pytest.approx(p_a + theta["dp_LS"], rel=RTOL)
    leak = theta["G_spool"] * (p_a - theta["p_tank"])
    assert flows["valve_a"] == pytest.approx(k_q * opening - leak, rel=RTOL)
    assert flows["valve_a"] == pytest.approx(_orifice(theta, spool, theta["dp_comp"]) - leak)
    assert flows["supply_flow"] == pytest.approx(k_q * opening, rel=RTOL)
    # the rod side at tank pressure: no drop across B -> T, no leak
    assert flows["valve_b"] == pytest.approx(0.0, abs=1e-18)


@pytest.mark.parametrize("fraction", SPOOL_FRACTIONS)
@pytest.mark.parametrize("drop_bar", [2.0, 5.0, 9.0])
def test_compensated_edge_below_its_setting_follows_the_orifice_law(
    fraction: float, drop_bar: float
) -> None:
    """A constant-pressure supply only ``drop`` above p_A (< Δp_c = 10 bar): the compensator is
    wide open, the edge takes the whole drop."""
    theta = _theta(load_sensing=0.0)
    spool, p_a = fraction * theta["x_s_max"], theta["p_supply_max"] - drop_bar * 1e5
    flows = _flows(theta, p_a, theta["p_tank"], spool)
    leak = theta["G_spool"] * (p_a - theta["p_tank"])
    assert flows["supply_flow"] == pytest.approx(_orifice(theta, spool, drop_bar * 1e5), rel=RTOL)
    assert flows["valve_a"] == pytest.approx(flows["supply_flow"] - leak, rel=RTOL)


@pytest.mark.parametrize("fraction", SPOOL_FRACTIONS)
@pytest.mark.parametrize("drop_bar", [2.0, 20.0, 80.0, 200.0])
def test_uncompensated_and_meter_out_edges_follow_the_orifice_law(
    fraction: float, drop_bar: float
) -> None:
    """Without compensator: P -> A (raising) and P -> B (lowering) with the supply's drop; the
    meter-out edges A -> T and B -> T with the port's drop to the tank line."""
    theta = _theta(load_sensing=0.0, compensated=0.0)
    spool, drop, p_t = fraction * theta["x_s_max"], drop_bar * 1e5, theta["p_tank"]
    p_port = theta["p_supply_max"] - drop
    raising = _flows(theta, p_port, p_t + drop, spool)  # B drains to tank across its edge
    leak_b = theta["G_spool"] * drop
    assert raising["supply_flow"] == pytest.approx(_orifice(theta, spool, drop), rel=RTOL)
    assert raising["valve_b"] == pytest.approx(-_orifice(theta, spool, drop) - leak_b, rel=RTOL)
    lowering = _flows(theta, p_t + drop, p_port, -spool)  # A drains, P feeds B
    assert lowering["supply_flow"] == pytest.approx(_orifice(theta, spool, drop), rel=RTOL)
    assert lowering["valve_a"] == pytest.approx(-_orifice(theta, spool, drop) - leak_b, rel=RTOL)


def test_closed_spool_the_flow_limit_and_the_load_check() -> None:
    theta = _theta()
    centred = _flows(theta, 1e7, theta["p_tank"], 0.0)
    assert centred["supply_flow"] == 0.0  # critically lapped: every edge closed
    assert centred["valve_a"] == pytest.approx(-theta["G_spool"] * (1e7 - theta["p_tank"]))
    limited = _flows(theta | {"Q_supply_max": 1e-3}, 5e6, theta["p_tank"], theta["x_s_max"])
    assert limited["supply_flow"] == pytest.approx(1e-3, rel=RTOL)  # 79 l/min asked, 60 given
    # a load above the supply's maximum: the load check holds, no flow back into P
    held = _flows(theta | {"load_sensing": 0.0}, 2.4e7, theta["p_tank"], theta["x_s_max"] / 2)
    assert held["supply_flow"] == 0.0


def _stiff_valve_loader() -> tuple[dict[str, float], np.ndarray, list[str]]:
    """The compact wheel loader (full bucket) with the example's valve circuit, its chassis
    held by tyres 1e5 times stiffer, the bucket locked to the boom, friction and occupant off."""
    layout = plant_layout("compact_wheel_loader", "valve")
    options = PlantOptions(friction=False, occupant=False)
    pump = machine_plant_parameter_vector(
        plant_layout("compact_wheel_loader"), None, "full", options
    )
    names = plant_layout("compact_wheel_loader").parameter_names
    entries = dict(zip(names, pump.tolist(), strict=True))
    entries |= valve_plant_entries(_example_valve(), "load_sensing")
    for name in ("k_Ax", "k_Ay", "k_Bx", "k_By", "k_tilt"):
        entries[name] *= 1e5
    vector = np.array([entries[n] for n in layout.parameter_names])
    return entries, vector, list(layout.state_names)


def test_hydraulic_natural_frequency_of_the_valve_cylinder() -> None:
    entries, params, states = _stiff_valve_loader()
    valve = plant_layout("compact_wheel_loader", "valve")
    x0, u0, _ = equilibrium_function(valve)(params)
    plant = build_plant(ca.SX, valve)
    x = ca.SX.sym("x", plant.size1_in(0))
    xdot = plant(x, u0, np.zeros(plant.size1_in(2)), params)[0]
    rate = np.asarray(ca.Function("f", [x], [xdot])(x0), dtype=float).ravel()
    assert np.max(np.abs(rate[: states.index("p_A")])) < 1e-9  # at rest
    a = np.asarray(ca.Function("A", [x], [ca.jacobian(xdot, x)])(x0), dtype=float)
    # the hydraulic spring of both sealed chambers along the cylinder, totals over n
    v = entries
    n, k_oil = v["n_cyl"], v["K_oil"]
    piston = math.pi / 4 * v["d_piston"] ** 2
    alpha = 1 - (v["d_rod"] / v["d_piston"]) ** 2
    kinematics = plant_layout("compact_wheel_loader").machine.function("cylinder_kinematics")
    completed = plant_layout("compact_wheel_loader").machine.function("complete_parameters")(
        params[: len(plant_layout("compact_wheel_loader").machine.parameter_names)]
    )[0]
    coordinates = states[: states.index("x_H") + 5]
    zeros = np.zeros(len(coordinates))
    position = float(kinematics(zeros, zeros, completed)[0]) - v["L_retracted"]
    v_a = piston * position + v["V_dead_A"]
    v_b = alpha * piston * (v["stroke"] - position) + v["V_dead_B"]
    k_h = n * k_oil * piston**2 * (1 / v_a + alpha**2 / v_b)
    # the cylinder's lever on the boom: dx_cyl/dphi from the kinematics' rate at a unit phi rate
    rates = zeros.copy()
    rates[coordinates.index("theta_2")] = rates[coordinates.index("theta_3")] = 1.0
    lever = float(kinematics(zeros, rates, completed)[1])
    # boom and locked bucket about the boom pivot D (parallel axes)
    d = np.array([v["D_x"], v["D_y"]])
    j_d = v["J_2"] + v["m_2"] * np.sum((np.array([v["G_x"], v["G_y"]]) - d) ** 2)
    j_d += v["J_3"] + v["m_3"] * np.sum((np.array([v["Q_x"], v["Q_y"]]) - d) ** 2)
    omega_h = abs(lever) * math.sqrt(k_h / j_d)
    eigenvalues = np.linalg.eigvals(a)
    hydraulic = eigenvalues[np.argmin(np.abs(np.abs(eigenvalues) - omega_h))]
    assert abs(hydraulic) == pytest.approx(omega_h, rel=1e-3)
    assert hydraulic.real < 0  # damped (spool leakage, tyres)
