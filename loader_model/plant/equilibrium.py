r"""Static equilibrium of the plant, computed inside the CasADi graph from the parameters.

At rest (p = 0, ṗ = 0, no road input) the generated ``complete_parameters`` gives the tyre loads
and the cylinder force F_act0 that hold the loader (masses, geometry, gravity). The hydraulics
follow in closed form (totals over the n cylinders; friction and end stops vanish at rest):

.. math::

    p_{B0} = p_c, \qquad p_{A0} = \frac{F_{act0} + n \alpha A_p p_c}{n A_p}, \qquad
    V_{p0} = \frac{Q_{L0}}{n_{pump}} = \frac{k_{Lp} (p_{A0} - p_{B0})}{n_{pump}}

(through open load-holding valves the pump holds the boom against Table 5's pump-side flow,
so the rod side needs no charge flow; with the pump switched off, the valves shut or the
load-holding valves closed, V_p0 = 0: :mod:`loader_model.plant.circuit`). A valve circuit
(:mod:`loader_model.plant.valve_circuit`) has its rod side at the tank pressure, p_B0 = p_T,
and holds the boom with the spool opened just enough that the meter-in edge feeds the spool's
leakage G_s (p_A0 − p_T) to tank: o = G_s (p_A0 − p_T) / (C_d w √(2/ρ) r(Δp)), with Δp the
compensated drop and r the orifice root, and x_s0 = x_0 + the inverse of the edge's C¹ ramp
(x_s0 = 0 with the load-holding valve closed). The accumulator
holds the oil volume at which its gas pressure equals p_A0 (inverse of the polytropic law), so
no oil flows through its orifice. The occupant's states are zero (measured from the static
deflection, :mod:`loader_model.plant.occupant`).

Behind closed load-holding valves the state is static up to the piston seals' leakage: the boom
drifts at ẋ_cyl = −Q_seal / (n A_p), about 0.014 mm/min with the default seals, so x0 is the
quasi-static state (ṗ_A(x0) = −K_oil Q_seal / V_A; exact with the leakage switched off).
"""

from __future__ import annotations

from functools import cache
from typing import Any

import casadi as ca
import numpy as np

from loader_model.plant import valve_circuit as valve
from loader_model.plant.components import ATMOSPHERIC_PRESSURE_PA
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.occupant import OCCUPANT_STATE_NAMES
from loader_model.vehicle.cylinder import static_piston_pressure

__all__ = ["equilibrium_function", "static_state"]


def _valve_hold(theta: dict[str, Any], p_a: Any, holding: Any) -> Any:
    """The spool position that feeds A the spool's leakage to tank at p_A0 (valve circuit)."""
    leak = holding * theta["G_spool"] * (p_a - theta["p_tank"])
    supply = valve.supply_pressure(theta, p_a, theta["p_tank"])
    available = supply - p_a
    compensated = valve.smooth_min(available, theta["dp_comp"], valve.PRESSURE_BAND_PA)
    drop = theta["compensated"] * compensated + (1 - theta["compensated"]) * available
    drop = valve.smooth_max(drop, 0, valve.PRESSURE_BAND_PA)
    per_opening = theta["C_d_s"] * theta["w_s"] * ca.sqrt(2 / theta["rho_oil"])
    opening = leak / (per_opening * valve.orifice_root(drop))
    band = valve.OPENING_BAND_M  # the inverse of the edge's C¹ ramp
    travel = ca.if_else(opening <= band / 2, ca.sqrt(2 * band * opening), opening + band / 2)
    return ca.if_else(leak > 0, theta["x_s_lap"] + travel, 0)


def _build(symbol: type, layout: PlantLayout) -> ca.Function:
    params = symbol.sym("params", len(layout.parameter_names))
    theta = {name: params[i] for i, name in enumerate(layout.parameter_names)}
    _, force = layout.machine.function("complete_parameters")(params[: layout.n_mechanical])
    holding = theta["pump_on"] * theta["valves_on"] * theta["leakage_on"] * theta["holding_open"]
    if layout.circuit == "valve":
        p_b = theta["p_tank"]
        p_a = static_piston_pressure(force, theta["n_cyl"], theta["d_piston"], theta["d_rod"], p_b)
        v_p = _valve_hold(theta, p_a, holding)
    else:
        p_b = theta["p_charge"]
        p_a = static_piston_pressure(force, theta["n_cyl"], theta["d_piston"], theta["d_rod"], p_b)
        v_p = holding * theta["k_Lp"] * (p_a - p_b) / theta["n_pump"]
    gas = theta["n_acc"] * theta["V_0"]
    absolute_0 = theta["p_0"] + ATMOSPHERIC_PRESSURE_PA
    absolute_a = p_a + ATMOSPHERIC_PRESSURE_PA
    filled = gas * (1 - (absolute_0 / ca.fmax(absolute_a, absolute_0)) ** (1 / theta["n_poly"]))
    empty = (p_a - theta["p_0"]) / (theta["n_poly"] * absolute_0 / gas)
    v_acc = ca.if_else(p_a >= theta["p_0"], filled, empty)
    zeros = symbol.zeros(layout.index("p_A"))
    state = ca.vertcat(zeros, p_a, p_b, v_p, 0, v_acc, symbol.zeros(len(OCCUPANT_STATE_NAMES)))
    return ca.Function(
        "plant_equilibrium",
        [params],
        [state, v_p, force],
        ["params"],
        ["x0", "u0", "F_act0"],
    )


@cache
def equilibrium_function(layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``plant_equilibrium(params) -> (x0, u0, F_act0)``: static state, the actuator command
    that holds it, and the cylinder force (SX, built once per machine and circuit)."""
    return _build(ca.SX, layout)


def static_state(
    params: np.ndarray, machine: MachineSource = SKID_STEER
) -> tuple[np.ndarray, float]:
    """Numeric static state (order of the machine's plant states, default the skid-steer's
    :data:`~loader_model.plant.plant.STATE_NAMES`) and command; ``machine`` its
    :class:`~loader_model.plant.layout.PlantLayout`, or a name or description file resolved
    once here."""
    layout = resolve_layout(machine)
    x0, u0, _ = equilibrium_function(layout)(np.asarray(params, dtype=float))
    state = np.asarray(x0, dtype=float).ravel()
    assert state.shape == (len(layout.state_names),)
    return state, float(u0)
