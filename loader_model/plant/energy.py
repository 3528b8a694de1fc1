r"""Power flows of the plant: stored energy, inputs and losses as one CasADi Function.

Built from the same pieces as the plant (:func:`~loader_model.plant.plant.hydraulic_drive`, the
generated ``mechanical_energy``, the components of :mod:`~loader_model.plant.components`), so the
balance

.. math:: \frac{dE}{dt} = \frac{\partial E}{\partial x} f(x, u, w)
          + \frac{\partial E}{\partial w_{road}} \dot w_{road,true}
          = P_{road} + P_{pump} + P_{charge} + P_{dist} - \sum D

holds at every state, to round-off (``tests/plant/test_plant_energy.py``). Stored energy E:

- kinetic ½ ṗᵀ M ṗ (Eq. 25), gravity, tyre springs with the contact law's clamp (Eq. 1-4,
  derive/energy.py), end stops (:func:`~loader_model.plant.components.end_stop_energy`);
- oil compression Ψ = V (π(p) − p) in chambers A and B (Eq. 36, 37 with their density law,
  :func:`~loader_model.plant.components.compression_energy`);
- accumulator gas, polytropic (:func:`~loader_model.plant.components.accumulator_gas_energy`).

A volume flow Q leaving or entering a chamber at pressure p carries π(p) Q, π(p) = K(e^(p/K) − 1),
so (all flows totals over the cylinders):

- pump (Fig. 9): P_pump = Q_p (π(p_A) − π(p_B)); charge line: P_charge = π(p_c)(Q_charge + Q_check);
- road: F_tyre · ẇ + F_elastic · (ẇ_true − ẇ) (derive/energy.py; ẇ_x = 0 by design while w_x
  moves, :mod:`~loader_model.simulation.travel`); disturbance (Eq. 5-7): F_dx ẋ_H + F_dy ẏ_H + M_d θ̇1;
- losses: tyres (dampers, sliding), seal friction F_f ẋ (Eq. 46, errata 10), end stops' damping,
  leakage Q_L (π_A − π_B) (Eq. 47, 48), orifice π_A q_acc − p_acc V̇_acc, low-side and check valves
  (π_c − π) Q, relief π_A Q_relief (to the tank at 0 gauge).

The seated occupant (:mod:`loader_model.plant.occupant`) is outside the balance: its relative
motion is driven by the chassis's acceleration at S (a base excitation, not a closed
conservative system) and its reaction on the chassis is neglected (a 55 kg seated mass on a
3.5 t machine), so E, the inputs and the losses are those of the loader without the occupant,
and the occupant's states enter none of them.

Two losses are not sign-definite, because the plant's laws are not: leakage's k_Lv ẋ term (Eq. 48)
moves oil against the pressure without a force on the piston, and the orifice feeds an
accumulator whose oil is incompressible at ρ0 while the chamber's is not, so for
0 < p_A − p_acc ≲ p_A² / (2 K) the flow runs "downhill" in pressure but "uphill" in π.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import casadi as ca

from loader_model.plant import components as hyd
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.plant import hydraulic_drive, named_parameters, plant_function

__all__ = [
    "ENERGY_NAMES",
    "INPUT_POWER_NAMES",
    "LOSS_NAMES",
    "build_energy",
    "energy_function",
    "energy_names",
    "energy_rate_function",
]

#: Stored energies [J], in the order of the output ``E_parts``.
ENERGY_NAMES = ("kinetic", "gravity", "tyres", "end_stops", "oil_A", "oil_B", "gas")
#: Input powers [W], output ``P_in``.
INPUT_POWER_NAMES = ("road", "pump", "charge_line", "disturbance")
#: Dissipated powers [W], output ``P_loss``.
LOSS_NAMES = (
    "tyres",
    "seal_friction",
    "end_stops",
    "leakage",
    "orifice",
    "low_side_valve",
    "check_valve",
    "relief_valve",
)


def _has_internal(layout: PlantLayout) -> bool:
    return bool(layout.machine.locked_cylinders)


def energy_names(layout: PlantLayout = SKID_STEER) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The stored-energy and loss names of the machine ``layout``: :data:`ENERGY_NAMES`,
    :data:`LOSS_NAMES`, each with ``"internal"`` appended for a machine with locked cylinders
    (their springs' energy and their dampers' loss, the generated ``V_internal``,
    ``D_internal``)."""
    if _has_internal(layout):
        return (*ENERGY_NAMES, "internal"), (*LOSS_NAMES, "internal")
    return ENERGY_NAMES, LOSS_NAMES


def _hydraulics(
    x: Any, drive: dict[str, Any], theta: dict[str, Any], h: int = 10
) -> tuple[list, list, list]:
    """Stored energies, input powers (pump, charge line) and losses of the hydraulic drive
    (``h``: the index of p_A in the state)."""
    p_a, p_b, v_acc = x[h], x[h + 1], x[h + 4]
    k_oil, n = theta["K_oil"], theta["n_cyl"]
    pi_a, pi_b = hyd.flow_power_pressure(k_oil, p_a), hyd.flow_power_pressure(k_oil, p_b)
    pi_c = hyd.flow_power_pressure(k_oil, theta["p_charge"])
    position, velocity = drive["position"], drive["velocity"]
    stop_energy = n * hyd.end_stop_energy(position, theta["stroke"], theta["k_end"])
    stop_spring = n * hyd.end_stop_spring_force(position, theta["stroke"], theta["k_end"])
    stored = [
        stop_energy,
        hyd.compression_energy(k_oil, drive["V_A"], p_a),
        hyd.compression_energy(k_oil, drive["V_B"], p_b),
        hyd.accumulator_gas_energy(
            theta["p_0"], theta["n_acc"] * theta["V_0"], theta["n_poly"], v_acc
        ),
    ]
    charge, check = drive["charge"], drive["check"]
    inputs = [drive["pump_flow"] * (pi_a - pi_b), pi_c * (charge + check)]
    losses = [
        drive["friction"] * velocity,
        (stop_spring - drive["end_stop"]) * velocity,
        drive["leakage"] * (pi_a - pi_b),
        pi_a * drive["q_acc"] - drive["p_acc"] * drive["accumulator_rate"],
        (pi_c - pi_b) * charge,
        (pi_c - pi_a) * check,
        pi_a * drive["relief"],
    ]
    return stored, inputs, losses


def build_energy(symbol: type = ca.SX, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``plant_energy(x, u, w, road_velocity, params) -> (E, E_parts, P_in, P_loss, F_elastic)``.

    ``road_velocity`` is the time derivative of the road displacement w[0:4] (what the road
    really does); w[4:8] is the rate the tyre law's dampers see. ``F_elastic`` (4,): the tyres'
    elastic forces, whose product with ``road_velocity`` is the part of P_road that depends on it.
    For another machine (``layout``) the sizes are its own, and its locked cylinders add an entry to
    ``E_parts`` and ``P_loss`` (:func:`energy_names`).

    Raises
    ------
    ValueError
        For a machine with a valve circuit (its supply, meter-out and spool-leakage terms are
        not booked here).
    """
    info = layout.machine
    if layout.circuit != "pump":
        raise ValueError(
            f"machine {info.name!r} has the circuit kind {layout.circuit!r}; the energy balance "
            "books the pump circuit's terms only (allowed: kind 'pump')"
        )
    n_p, n_a, n_w = layout.n_coordinates, layout.n_anchors, len(info.road_names)
    x = symbol.sym("x", len(layout.state_names))
    u = symbol.sym("u", len(layout.input_names))
    w = symbol.sym("w", len(layout.exogenous_names))
    road_velocity = symbol.sym("road_velocity", n_w)
    params = symbol.sym("params", len(layout.parameter_names))
    theta = named_parameters(params, layout)
    completed, _ = info.function("complete_parameters")(params[: layout.n_mechanical])
    drive = hydraulic_drive(x, u, theta, completed, layout)
    p, pd, anchor = x[0:n_p], x[n_p : 2 * n_p], x[2 * n_p : 2 * n_p + n_a]
    road, road_rate, disturbance = w[0:n_w], w[n_w : 2 * n_w], w[2 * n_w : 2 * n_w + 3]
    kinetic, gravity, tyres, elastic, tyre_loss, *internal = info.function("mechanical_energy")(
        p, pd, anchor, road, road_rate, completed
    )
    forces = info.function("tyre_contact")(p, pd, anchor, road, road_rate, completed)[0]
    road_power = ca.dot(forces, road_rate) + ca.dot(elastic, road_velocity - road_rate)
    stored, hydraulic_in, hydraulic_loss = _hydraulics(x, drive, theta, layout.index("p_A"))
    internal_stored, internal_loss = internal[:1], internal[1:2]
    parts = ca.vertcat(kinetic, gravity, tyres, *stored, *internal_stored)
    inputs = ca.vertcat(road_power, *hydraulic_in, ca.dot(disturbance, pd[0:3]))
    losses = ca.vertcat(tyre_loss, *hydraulic_loss, *internal_loss)
    return ca.Function(
        "plant_energy",
        [x, u, w, road_velocity, params],
        [ca.sum1(parts), parts, inputs, losses, elastic],
        ["x", "u", "w", "road_velocity", "params"],
        ["E", "E_parts", "P_in", "P_loss", "F_elastic"],
    )


def energy_function(machine: MachineSource = SKID_STEER) -> ca.Function:
    """The SX :func:`build_energy` Function of ``machine`` (its
    :class:`~loader_model.plant.layout.PlantLayout`, or a name or description file resolved
    once here), built once per process and machine."""
    return _energy_function(resolve_layout(machine))


@cache
def _energy_function(layout: PlantLayout) -> ca.Function:
    return build_energy(ca.SX, layout)


def energy_rate_function(layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``energy_rate(x, u, w, road_velocity, params) -> (dE_dt, P_net)`` of the machine
    ``layout`` (:func:`_energy_rate_function`)."""
    return _energy_rate_function(layout)


@cache
def _energy_rate_function(layout: PlantLayout) -> ca.Function:
    """``energy_rate(x, u, w, road_velocity, params) -> (dE_dt, P_net)``: both sides of the balance.

    dE/dt = ∂E/∂x · f(x, u, w) + ∂E/∂w_road · road_velocity by forward AD through the plant's
    ``xdot``; P_net = ΣP_in − ΣP_loss. Equal to round-off at any state (module docstring).
    """
    n_w = len(layout.machine.road_names)
    x = ca.SX.sym("x", len(layout.state_names))
    u = ca.SX.sym("u", len(layout.input_names))
    w = ca.SX.sym("w", len(layout.exogenous_names))
    road_velocity = ca.SX.sym("road_velocity", n_w)
    params = ca.SX.sym("params", len(layout.parameter_names))
    energy, _, inputs, losses, _ = energy_function(layout)(x, u, w, road_velocity, params)
    xdot = plant_function(layout)(x, u, w, params)[0]
    direction = ca.vertcat(xdot, road_velocity)
    rate = ca.jtimes(energy, ca.vertcat(x, w[0:n_w]), direction)
    return ca.Function(
        "energy_rate",
        [x, u, w, road_velocity, params],
        [rate, ca.sum1(inputs) - ca.sum1(losses)],
        ["x", "u", "w", "road_velocity", "params"],
        ["dE_dt", "P_net"],
    )
