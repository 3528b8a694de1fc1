r"""The plant: generated multibody model + lift cylinders + pump + valves + accumulator, one Function.

.. math:: \dot x = f(x, u, w, \theta), \qquad y = h(x, u, w, \theta)

State x (:data:`STATE_NAMES`): the coordinates p and rates ṗ (Eq. 26), the tyre anchors ξ
(``derive/contact.py``), the chamber pressures p_A, p_B (gauge, Pa; Eq. 36, 37), the pump
displacement V_p and its rate (Fig. 9), the oil volume in the accumulator, then the seated
occupant's states on the seat cushion at S (:mod:`loader_model.plant.occupant`, appended so the
earlier indices stay). Input u: the pump
displacement command V_p,ref [m³/rev]. Exogenous w: road displacement and rate under each axle,
disturbance forces at H (Eq. 5-7). Parameters θ: :data:`~loader_model.plant.plant_parameters.
PLANT_PARAMETER_NAMES` (mechanical, then hydraulic, then switches); the static tyre loads are
completed inside the graph (generated ``complete_parameters``), so a varied θ stays consistent.

The drive (Fig. 8, section 2.4): ``n_cyl`` single-rod cylinders in parallel, all quantities below
are totals over them. Through open load-holding valves (h = 1) the pump moves oil from the
rod-side line to the piston-side line; closed (h = 0), the cylinders and the accumulator are
sealed from the pump's circuit (:mod:`loader_model.plant.circuit`):

.. math::

    \dot p_A &= \frac{K_{oil}}{V_A}\left(h (Q_p - Q_L) + Q_{check} - Q_{relief} - Q_{seal}
               - Q_{acc} - A_p \dot x_{cyl}\right) \quad \text{(Eq. 36)} \\
    \dot p_B &= \frac{K_{oil}}{V_B}\left(-h Q_p + Q_{charge} + h Q_L + Q_{seal}
               + \alpha A_p \dot x_{cyl}\right) \quad \text{(Eq. 37)} \\
    F_{act} &= A_p (p_A - \alpha p_B) - F_f + F_{end} \quad \text{(Eq. 31)}

with Q_p = n V_p (V_p saturated at ±V_p,max), the rod side tied to the charge line by the
low-side valve Q_charge = G_charge (p_c − p_B) (the rod side is the low side while the boom
carries its weight), an anti-cavitation check valve from the charge line into the piston side
(through the load-holding valve's check), a port relief valve on the piston side, Table 5's
pump-side regression flow Q_L (Eq. 47 with Eq. 48's sign; errata 11), the piston
seals' leakage Q_seal = n k_seal (p_A − p_B) behind closed valves, seal friction F_f (Eq. 46,
errata 10 reading), end stops, and the accumulator through its orifice (between the valves and
the cylinder). The pump's
displacement loop is the second-order system of Fig. 9 with its command saturated at ±V_p,max
and its rate limited to ±V̇_p,max (Table 2, errata 8), each by the C¹ saturation of
:mod:`loader_model.plant.components` (exact below 99 % of the limit).

A machine whose description has ``[circuit] kind = "valve"`` has a proportional directional
valve in place of the pump (:mod:`loader_model.plant.valve_circuit`): the states V_p, V̇_p become
the spool x_s, ẋ_s (the same loop, saturation and rate limit, with ω_s, ζ_s, x_s,max, ẋ_s,max),
the input its command x_s,ref [m]; the valve's flow reaches A through the load-holding valve
and B directly, the rod side drains to the tank line instead of the charge line, and Table 5's
pump-side flow is not part of it.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import casadi as ca

from loader_model.plant import components as hyd
from loader_model.plant.circuit import circuit_flows
from loader_model.plant.layout import (
    SKID_STEER,
    MachineSource,
    PlantLayout,
    plant_layout,
    resolve_layout,
)
from loader_model.plant.occupant import occupant_dynamics
from loader_model.plant.valve_circuit import valve_drive

__all__ = [
    "EXOGENOUS_NAMES",
    "INPUT_NAMES",
    "OUTPUT_NAMES",
    "SKID_STEER",
    "STATE_NAMES",
    "build_plant",
    "hydraulic_drive",
    "named_parameters",
    "plant_function",
    "plant_layout",
]

#: The skid-steer's plant (any machine: :func:`plant_layout`).
STATE_NAMES: tuple[str, ...] = SKID_STEER.state_names
INPUT_NAMES: tuple[str, ...] = SKID_STEER.input_names
EXOGENOUS_NAMES: tuple[str, ...] = SKID_STEER.exogenous_names
OUTPUT_NAMES: tuple[str, ...] = SKID_STEER.output_names

_SATURATION_BAND = 0.01  # C¹ saturations are exact below 99 % of their limit


def named_parameters(params: Any, layout: PlantLayout | None = None) -> dict[str, Any]:
    """The entries of a plant parameter vector by name (the layout's, default the skid-steer's
    :data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`)."""
    names = (layout or SKID_STEER).parameter_names
    return {name: params[i] for i, name in enumerate(names)}


def hydraulic_drive(
    x: Any, u: Any, theta: dict[str, Any], completed: Any, layout: PlantLayout | None = None
) -> dict[str, Any]:
    """Hydraulic quantities of the state, totals over the cylinders (module docstring).

    Returns the cylinder force and position, the pressure rates and every flow and force they
    are made of (so that :mod:`loader_model.plant.energy` books the same terms): ``velocity``
    ẋ_cyl, chamber volumes ``V_A``, ``V_B``, flows ``pump_flow``, ``charge``, ``check``,
    ``relief``, ``leakage``, ``q_acc`` (into the orifice, at chamber A's density),
    ``accumulator_rate`` (its oil volume rate), forces ``friction`` and ``end_stop``.
    ``layout`` (default the skid-steer's) gives the machine, its circuit and its state indices;
    a valve circuit's drive has ``pump_flow`` the supply's flow and adds ``supply_pressure``,
    ``valve_a``, ``valve_b`` and ``check_b`` (:mod:`loader_model.plant.valve_circuit`).
    """
    layout = layout or SKID_STEER
    n_p, h = layout.n_coordinates, layout.index("p_A")
    p, pd = x[0:n_p], x[n_p : 2 * n_p]
    p_a, p_b, v_p, vd_p, v_acc = x[h], x[h + 1], x[h + 2], x[h + 3], x[h + 4]
    kinematics = layout.machine.function("cylinder_kinematics")(p, pd, completed)
    n = theta["n_cyl"]
    piston = ca.pi / 4 * theta["d_piston"] ** 2
    annulus = piston - ca.pi / 4 * theta["d_rod"] ** 2
    position = kinematics[0] - theta["L_retracted"]
    velocity = kinematics[1]
    v_a, v_b = hyd.chamber_volumes(
        position, piston, annulus, theta["stroke"], theta["V_dead_A"], theta["V_dead_B"]
    )
    friction = theta["friction_on"] * hyd.seal_friction(
        theta["f_s"], theta["tau_s"], theta["gamma_f"], theta["f_C"], theta["f_v"], p_a, velocity
    )
    end_stop = n * hyd.end_stop_force(
        position, velocity, theta["stroke"], theta["k_end"], theta["c_end"]
    )
    force = n * (piston * p_a - annulus * p_b) - friction + end_stop
    if layout.circuit == "valve":
        common = {"force": force, "position": position, "velocity": velocity}
        common |= {"V_A": n * v_a, "V_B": n * v_b, "friction": friction, "end_stop": end_stop}
        return valve_drive(x[h : h + 5], u, theta, common, n * piston, n * annulus)
    v_max, vd_max = theta["V_p_max"], theta["Vd_p_max"]
    displacement = hyd.saturate(v_p, v_max, _SATURATION_BAND * v_max)
    flows = circuit_flows(theta, p_a, p_b, velocity, displacement)
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
    k_oil = theta["K_oil"]
    pump_flow, leakage = flows["pump_flow"], flows["leakage"]
    # summed in the order of before the circuit states, so that open valves give the same
    # floating-point rates (a lift-off trial can turn on a rounding difference)
    dp_a = hyd.chamber_pressure_rate(
        k_oil,
        n * v_a,
        pump_flow + flows["check"] - flows["relief"] - q_acc - n * piston * velocity - leakage,
    )
    dp_b = hyd.chamber_pressure_rate(
        k_oil, n * v_b, -pump_flow + flows["charge"] + n * annulus * velocity + leakage
    )
    command = hyd.saturate(u, v_max, _SATURATION_BAND * v_max)
    rate = hyd.saturate(vd_p, vd_max, _SATURATION_BAND * vd_max)
    dvd_p = hyd.pump_displacement_acceleration(
        v_p, vd_p, command, theta["omega_p"], theta["zeta_p"]
    )
    # the accumulator's oil is taken as incompressible at the reference density; the orifice's
    # mass flow is ρ(p_A) q_acc with ρ(p) = ρ0 e^(p/K_oil), the density law of Eq. 36, so oil
    # mass is conserved exactly between the chamber and the accumulator
    accumulator_rate = ca.exp(p_a / k_oil) * q_acc
    return {
        "force": force,
        "position": position,
        "velocity": velocity,
        "V_A": n * v_a,
        "V_B": n * v_b,
        "pump_flow": flows["pump_flow"],
        "charge": flows["charge"],
        "check": flows["check"],
        "relief": flows["relief"],
        "leakage": flows["leakage"],
        "q_acc": q_acc,
        "accumulator_rate": accumulator_rate,
        "friction": friction,
        "end_stop": end_stop,
        "p_acc": p_acc,
        "rates": ca.vertcat(dp_a, dp_b, rate, dvd_p, accumulator_rate),
    }


def build_plant(symbol: type = ca.SX, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """Build the plant Function ``plant(x, u, w, params) -> (xdot, y)`` (module docstring).

    Parameters
    ----------
    symbol : casadi.SX or casadi.MX
        Symbol type of the graph (SX: fast to evaluate and to JIT-compile; MX: compact).
    layout : PlantLayout
        The machine and its lift circuit (default the skid-steer's; any machine:
        :func:`plant_layout`, another circuit: :func:`~loader_model.plant.layout.machine_layout`).
    """
    info = layout.machine
    n_p, n_a, n_w = layout.n_coordinates, layout.n_anchors, len(info.road_names)
    x = symbol.sym("x", len(layout.state_names))
    u = symbol.sym("u", len(layout.input_names))
    w = symbol.sym("w", len(layout.exogenous_names))
    params = symbol.sym("params", len(layout.parameter_names))
    theta = named_parameters(params, layout)
    completed, _ = info.function("complete_parameters")(params[: layout.n_mechanical])
    drive = hydraulic_drive(x, u, theta, completed, layout)
    p, pd, anchor = x[0:n_p], x[n_p : 2 * n_p], x[2 * n_p : 2 * n_p + n_a]
    road, road_rate = w[0:n_w], w[n_w : 2 * n_w]
    disturbance = w[2 * n_w : 2 * n_w + len(info.disturbance_names)]
    pdd, anchor_rate = info.function("forward_dynamics")(
        p, pd, anchor, drive["force"], road, road_rate, disturbance, completed
    )
    forces = info.function("specific_forces")(p, pd, pdd, completed)
    occupant_rate, pad = occupant_dynamics(
        x[layout.n_hydraulic_end :], forces[layout.seat_sensor], theta
    )
    xdot = ca.vertcat(pd, pdd, anchor_rate, drive["rates"], occupant_rate)
    tyres = info.function("tyre_contact")(p, pd, anchor, road, road_rate, completed)[0]
    h = layout.index("p_A")
    index = info.coordinate_names.index
    joints = [p[index(body)] - p[index(parent)] for body, parent in info.joint_coordinates]
    y = ca.vertcat(
        pd[0],
        pd[1],
        pd[2],
        *joints,
        *(forces[k][axis] for _, k, axis in layout.sensor_outputs),
        pdd[2],
        x[h],
        x[h + 1],
        drive["force"],
        drive["position"],
        x[h + 2],
        drive["pump_flow"],
        *(tyres[2 * k + 1] for k in range(len(info.axles))),
        drive["p_acc"],
        pad,
    )
    return ca.Function(
        "plant", [x, u, w, params], [xdot, y], ["x", "u", "w", "params"], ["xdot", "y"]
    )


@cache
def _plant_function(layout: PlantLayout) -> ca.Function:
    return build_plant(ca.SX, layout)


def plant_function(machine: MachineSource = SKID_STEER) -> ca.Function:
    """The SX plant Function of ``machine`` (its :class:`PlantLayout`, or a name or description
    file resolved once here), built once per process and machine."""
    return _plant_function(resolve_layout(machine))
