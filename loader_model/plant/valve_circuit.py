r"""A valve-controlled open lift circuit: a proportional directional valve fed by a supply.

The second kind of lift circuit (a description's ``[circuit] kind = "valve"``; the first is the
paper's closed-circuit displacement-controlled pump of :mod:`loader_model.plant.circuit`). Most
wheel loaders, tractors and telehandlers raise their boom this way: a 4/3 proportional
directional valve with an individual pressure compensator, fed by a load-sensing pump, its
return to the tank line. Totals over the n cylinders of the lift group, one valve for the group.

**Spool** (Merritt, *Hydraulic Control Systems*, 1967, ch. 3). Position x_s in m, positive
P → A and B → T (raising the boom), negative P → B and A → T; saturated at the spool stroke
±x_s,max and driven by its command through the same rate-limited second-order loop as the
pump's displacement (:func:`~loader_model.plant.components.pump_displacement_acceleration` with
ω_s, ζ_s, ẋ_s,max). Each metering edge opens by o = x_s − x_0 beyond the overlap x_0 (x_0 = 0:
critically lapped) with the area gradient w (Merritt's w: area per unit opening), A = w o.

**Metering edges** (Merritt ch. 3, the orifice equation):

.. math::

    Q = C_d\, w\, o\, \sqrt{2 \Delta p / \rho}

A meter-in edge (P → A, P → B) sits behind an individual pressure compensator that holds the
drop across it at its setting Δp_c while the supply is high enough, so the valve's flow gain is
K_q = C_d w √(2 Δp_c / ρ) and Q = K_q o whatever the load (flow-pressure coefficient K_c = 0);
when p_s − p_A < Δp_c the compensator is fully open and the edge follows the orifice law with
Δp = p_s − p_A; a load check valve blocks flow back to P. Without compensator
(``compensated`` = 0) the meter-in edge is a plain orifice with Merritt's flow-pressure
coefficient K_c = −∂Q/∂p_A > 0.
The meter-out edges (A → T, B → T) are plain orifices to the tank line at p_T (pre-compensated
valves, e.g. the sectional mobile valves of the load-sensing literature, compensate the inlet
only). Every work port leaks G_s (p − p_T) to the tank line across the spool's clearance
(Merritt ch. 3's null leakage, taken laminar; its P → port part is cut off by the compensator,
closed at a centred spool).

**Supply.** A load-sensing pump (Axin, Eriksson, Palmberg, *Flow versus pressure control of
pumps in mobile hydraulic systems*, Proc. IMechE Part I 228(4), 2014) keeps its outlet at the
highest load pressure plus its margin Δp_LS, up to its maximum pressure p_max:
p_s = min(max(p_A, p_B) + Δp_LS, p_max); a constant-pressure source holds p_s = p_max.
Either delivers at most Q_max: a meter-in flow is saturated at it (with one valve section, the
compensator cannot hold its drop once the pump is at its flow limit, so the section gets what
the pump gives).

**Around the valve** as in the pump circuit: the load-holding valve on the piston side (closed,
h = 0: the valve's flow into and out of A is blocked and the cylinder sealed, its piston seals
leaking Q_seal), the relief valve on the piston side, anti-cavitation checks from the tank line
into both sides, and the passive accumulator between the load-holding valve and the cylinder.

Non-smooth laws are C¹ and exact outside stated bands, like :mod:`~loader_model.plant.components`:
the square root below a drop of :data:`ROOT_BAND_PA`, the min / max of pressures within
:data:`PRESSURE_BAND_PA`. An edge opens as the C¹ ramp of :mod:`~loader_model.plant.components`
over its first :data:`OPENING_BAND_M`: closed (exactly) for x_s ≤ x_0, o = x_s − x_0 − b/2
beyond x_0 + b, so the smoothing adds b/2 = 5 µm to the overlap (0.1 % of a 5 mm stroke).
"""

from __future__ import annotations

from typing import Any

import casadi as ca

from loader_model.plant import components as hyd

__all__ = [
    "OPENING_BAND_M",
    "PRESSURE_BAND_PA",
    "ROOT_BAND_PA",
    "VALVE_PARAMETERS",
    "edge_opening",
    "flow_gain",
    "meter_in_flow",
    "orifice_root",
    "smooth_max",
    "smooth_min",
    "supply_pressure",
    "valve_circuit_flows",
    "valve_drive",
]

Expr = Any

#: Below this pressure drop [Pa] the square root of the orifice law is a C¹ odd cubic.
ROOT_BAND_PA = 1e4
#: Over this opening [m] an edge opens quadratically (C¹ ramp), exact beyond it.
OPENING_BAND_M = 1e-5
#: Width [Pa] over which the supply's min and max blend (exact outside it).
PRESSURE_BAND_PA = 1e5
#: The spool's and its rate's C¹ saturations are exact below 99 % of their limit (as the pump's).
SATURATION_BAND = 0.01

#: (name, unit, description) of the valve circuit's own entries of the plant parameter vector.
VALVE_PARAMETERS: tuple[tuple[str, str, str], ...] = (
    ("x_s_max", "m", "spool stroke: the saturation of the spool and of its command"),
    ("w_s", "m", "area gradient of each metering edge (Merritt's w)"),
    ("x_s_lap", "m", "spool overlap of each metering edge (0: critically lapped)"),
    ("C_d_s", "-", "discharge coefficient of the metering edges"),
    ("dp_comp", "Pa", "setting of the individual pressure compensator (drop held across P-A/P-B)"),
    ("compensated", "-", "1: meter-in edges pressure compensated; 0: plain orifices"),
    ("omega_s", "rad/s", "natural frequency of the spool position loop"),
    ("zeta_s", "-", "damping ratio of the spool position loop"),
    ("xd_s_max", "m/s", "spool rate limit"),
    ("G_spool", "m^3/(s*Pa)", "leakage of each work port to the tank line across the spool"),
    ("p_tank", "Pa", "tank line pressure, gauge"),
    ("p_supply_max", "Pa", "maximum pressure of the supply (the constant-pressure setting)"),
    ("dp_LS", "Pa", "load-sensing margin: supply above the highest load pressure"),
    ("Q_supply_max", "m^3/s", "flow limit of the supply"),
    ("load_sensing", "-", "1: load-sensing pump; 0: constant-pressure source"),
)


def smooth_min(a: Expr, b: Expr, width: Expr) -> Expr:
    """C¹ min(a, b): exact for |a − b| ≥ width / 2."""
    return a - hyd.ramp(a - b + width / 2, width)


def smooth_max(a: Expr, b: Expr, width: Expr) -> Expr:
    """C¹ max(a, b): exact for |a − b| ≥ width / 2."""
    return a + hyd.ramp(b - a + width / 2, width)


def orifice_root(pressure_drop_pa: Expr, band_pa: Expr = ROOT_BAND_PA) -> Expr:
    r"""sign(Δp) √|Δp|, C¹: exact for |Δp| ≥ δ, the odd cubic with the same value and slope at
    ±δ inside (finite slope at zero, so the plant's Jacobian exists at a closed edge).

    .. math:: r(\Delta p) = \frac{5 \Delta p}{4 \sqrt\delta} - \frac{\Delta p^3}{4 \delta^{5/2}}
              \quad (|\Delta p| < \delta)
    """
    inner = 5 * pressure_drop_pa / (4 * ca.sqrt(band_pa)) - pressure_drop_pa**3 / (4 * band_pa**2.5)
    outer = ca.sign(pressure_drop_pa) * ca.sqrt(ca.fabs(pressure_drop_pa))
    return ca.if_else(ca.fabs(pressure_drop_pa) >= band_pa, outer, inner)


def edge_opening(spool_m: Expr, overlap_m: Expr) -> Expr:
    """Opening [m] of the edge that opens for positive ``spool_m`` beyond the overlap (C¹)."""
    return hyd.ramp(spool_m - overlap_m, OPENING_BAND_M)


def flow_gain(theta: dict[str, Expr]) -> Expr:
    r"""Compensated flow gain K_q = C_d w √(2 Δp_c / ρ) in m²/s (Merritt ch. 3)."""
    return theta["C_d_s"] * theta["w_s"] * ca.sqrt(2 * theta["dp_comp"] / theta["rho_oil"])


def meter_in_flow(theta: dict[str, Expr], opening_m: Expr, supply_pa: Expr, port_pa: Expr) -> Expr:
    """Flow [m³/s] from P into a work port across an opened meter-in edge (module notes): the
    drop held at Δp_c by the compensator while the supply allows, a load check against back
    flow, saturated at the supply's flow limit."""
    available = supply_pa - port_pa
    compensated = smooth_min(available, theta["dp_comp"], PRESSURE_BAND_PA)
    drop = theta["compensated"] * compensated + (1 - theta["compensated"]) * available
    drop = smooth_max(drop, 0, PRESSURE_BAND_PA)  # the load check valve
    area = theta["C_d_s"] * theta["w_s"] * opening_m
    demand = area * ca.sqrt(2 / theta["rho_oil"]) * orifice_root(drop)
    limit = theta["Q_supply_max"]
    return hyd.saturate(demand, limit, 0.01 * limit)


def supply_pressure(theta: dict[str, Expr], p_a: Expr, p_b: Expr) -> Expr:
    """Supply pressure p_s [Pa]: load sensing min(max(p_A, p_B) + Δp_LS, p_max), or p_max."""
    load = smooth_max(p_a, p_b, PRESSURE_BAND_PA)
    sensed = smooth_min(load + theta["dp_LS"], theta["p_supply_max"], PRESSURE_BAND_PA)
    return theta["load_sensing"] * sensed + (1 - theta["load_sensing"]) * theta["p_supply_max"]


def _meter_out_flow(theta: dict[str, Expr], opening_m: Expr, port_pa: Expr) -> Expr:
    area = theta["C_d_s"] * theta["w_s"] * opening_m
    return area * ca.sqrt(2 / theta["rho_oil"]) * orifice_root(port_pa - theta["p_tank"])


def valve_circuit_flows(
    theta: dict[str, Expr], p_a: Expr, p_b: Expr, spool_m: Expr
) -> dict[str, Expr]:
    """Flows of the valve circuit (module notes), totals over the cylinders, in m³/s.

    Parameters
    ----------
    theta
        Plant parameters by name (the valve layout's, :data:`VALVE_PARAMETERS` among them).
    p_a, p_b
        Chamber pressures (gauge), Pa.
    spool_m
        Saturated spool position x_s, m.

    Returns
    -------
    dict
        ``valve_a`` (from the valve towards the piston side, before the load-holding valve),
        ``valve_b`` (into the rod side), ``supply_flow`` (out of the supply; ``supply_a``,
        ``supply_b`` its parts through P -> A and P -> B), ``supply_pressure``,
        ``check`` (tank into A), ``check_b`` (tank into B), ``relief`` (A to tank), ``leakage``
        (piston seals from A to B, behind closed load-holding valves only).
    """
    valves = theta["valves_on"]
    supply = valves * theta["pump_on"]
    lap = theta["x_s_lap"]
    raise_edge, lower_edge = edge_opening(spool_m, lap), edge_opening(-spool_m, lap)
    p_s = supply_pressure(theta, p_a, p_b)
    into_a = supply * meter_in_flow(theta, raise_edge, p_s, p_a)
    into_b = supply * meter_in_flow(theta, lower_edge, p_s, p_b)
    spool_leak = theta["leakage_on"] * theta["G_spool"]
    out_a = valves * (
        _meter_out_flow(theta, lower_edge, p_a) + spool_leak * (p_a - theta["p_tank"])
    )
    out_b = valves * (
        _meter_out_flow(theta, raise_edge, p_b) + spool_leak * (p_b - theta["p_tank"])
    )
    check = valves * theta["G_check"] * hyd.ramp(theta["p_tank"] - p_a, 1e4)
    check_b = valves * theta["G_check"] * hyd.ramp(theta["p_tank"] - p_b, 1e4)
    relief = valves * theta["G_relief"] * hyd.ramp(p_a - theta["p_relief"], 1e5)
    seal = theta["n_cyl"] * theta["k_seal"] * (p_a - p_b)
    return {
        "valve_a": into_a - out_a,
        "valve_b": into_b - out_b,
        "supply_flow": into_a + into_b,
        "supply_a": into_a,
        "supply_b": into_b,
        "supply_pressure": p_s,
        "check": check,
        "check_b": check_b,
        "relief": relief,
        "leakage": theta["leakage_on"] * (1 - theta["holding_open"]) * seal,
    }


def _accumulator(theta: dict[str, Any], p_a: Any, v_acc: Any) -> tuple[Any, Any, Any]:
    """Gas pressure, orifice flow (at chamber A's density) and oil volume rate of the
    accumulator, as the pump circuit's (:mod:`loader_model.plant.plant`: the oil mass is
    conserved between chamber and accumulator)."""
    p_acc = hyd.accumulator_gas_pressure(
        theta["p_0"], theta["n_acc"] * theta["V_0"], theta["n_poly"], v_acc
    )
    q_acc = (
        theta["accumulator_on"]
        * theta["n_acc"]
        * hyd.orifice_flow(
            theta["d_orifice"], theta["C_d"], theta["rho_oil"], p_a - p_acc, theta["dp_laminar"]
        )
    )
    return p_acc, q_acc, ca.exp(p_a / theta["K_oil"]) * q_acc


def valve_drive(
    states: Any, u: Any, theta: dict[str, Any], common: dict[str, Any], piston: Any, annulus: Any
) -> dict[str, Any]:
    """:func:`~loader_model.plant.plant.hydraulic_drive` of a valve circuit (module notes):
    the spool's loop in place of the pump's, the valve's flows through the load-holding valve
    into A and directly into B. ``piston``, ``annulus``: total areas over the cylinders."""
    p_a, p_b, x_s, xd_s, v_acc = (states[k] for k in range(5))
    x_max, xd_max = theta["x_s_max"], theta["xd_s_max"]
    spool = hyd.saturate(x_s, x_max, SATURATION_BAND * x_max)
    flows = valve_circuit_flows(theta, p_a, p_b, spool)
    p_acc, q_acc, accumulator_rate = _accumulator(theta, p_a, v_acc)
    velocity, leakage = common["velocity"], flows["leakage"]
    into_a = theta["holding_open"] * flows["valve_a"] + flows["check"] - flows["relief"]
    dp_a = hyd.chamber_pressure_rate(
        theta["K_oil"], common["V_A"], into_a - q_acc - piston * velocity - leakage
    )
    into_b = flows["valve_b"] + flows["check_b"] + annulus * velocity + leakage
    dp_b = hyd.chamber_pressure_rate(theta["K_oil"], common["V_B"], into_b)
    command = hyd.saturate(u, x_max, SATURATION_BAND * x_max)
    rate = hyd.saturate(xd_s, xd_max, SATURATION_BAND * xd_max)
    dxd_s = hyd.pump_displacement_acceleration(
        x_s, xd_s, command, theta["omega_s"], theta["zeta_s"]
    )
    return common | {
        # a closed load-holding valve blocks the line P -> A feeds: no flow out of the supply
        "pump_flow": theta["holding_open"] * flows["supply_a"] + flows["supply_b"],
        "supply_pressure": flows["supply_pressure"],
        "valve_a": flows["valve_a"],
        "valve_b": flows["valve_b"],
        "check": flows["check"],
        "check_b": flows["check_b"],
        "relief": flows["relief"],
        "leakage": leakage,
        "q_acc": q_acc,
        "accumulator_rate": accumulator_rate,
        "p_acc": p_acc,
        "rates": ca.vertcat(dp_a, dp_b, rate, dxd_s, accumulator_rate),
    }
