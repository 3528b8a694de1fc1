r"""The lift circuit's states: load-holding valves between the pump's circuit and the cylinders.

A pump-controlled (displacement-controlled, DC) boom has the pump's two ports piped to the
cylinders' two sides; load-holding valves on the piston side keep the boom up while the pump is
idle (Heybroek, *Saving Energy in Construction Machinery using Displacement Control Hydraulics*,
Linköping Studies in Science and Technology, Thesis No. 1372, 2008; the Purdue DC prototypes,
e.g. Hippalgaonkar & Ivantysynova, SICFP 2013). Commercial ride control connects its
accumulator between those valves and the cylinder (guide page "Hydraulics"), so it acts while the
valves are closed. The plant's switch ``holding_open`` h (1 open, 0 closed) sets which state the
circuit is in; per side of the piston (totals over the n cylinders):

.. math::

    Q_{A,net} &= h\,(Q_p - Q_L) + Q_{check} - Q_{relief} - Q_{acc} - (1 - h)\,Q_{seal}
                 - n A_p \dot x_{cyl} \\
    Q_{B,net} &= -h\,Q_p + Q_{charge} + h\,Q_L + (1 - h)\,Q_{seal}
                 + n \alpha A_p \dot x_{cyl}

Which valve acts where:

- *pump flow* Q_p and *Table 5's regression flow* Q_L = k_Lp (p_A − p_B) + k_Lv ẋ (Eq. 47, 48's
  sign): on the pump side of the load-holding valves, so only while they are open;
- *anti-cavitation check* Q_check from the charge line: the charge check valves of the closed
  pump circuit keep the pump's piston-side line at charge pressure at least, and a load-holding
  valve is a pilot-operated check that blocks the flow out of the piston side but passes flow
  into it; so the make-up reaches the cylinder in both states (without it a sealed piston side
  would go to negative absolute pressure, a tension oil cannot carry, when the boom bounces);
- *relief* Q_relief: a port (shock) relief on the cylinder side, always (it protects the sealed
  cylinder too);
- *charge line* Q_charge: the rod side stays tied to the charge line in both states (the rod
  side is the low side while the boom carries its weight);
- *piston-seal leakage* Q_seal = n k_seal (p_A − p_B): inside each cylinder, acting only while
  the valves are closed: while open it is part of what Table 5's regression measured (and five
  orders of magnitude smaller than it), so it is not counted twice.

Why Table 5's k_Lp is not a cylinder leak (errata 11): at the empty bucket's
p_A − p_B = 69 bar, k_Lp = 2.87e-11 m³/(s·Pa) is 11.9 l/min, so a boom on a leaking cylinder
would sink about 3 cm/s. Q_A in Eq. 48 was estimated from the pump's displacement, so the slope
lumps the pump's volumetric losses (about 11 % of its 110 l/min here; estimate) with regression
artefacts (with C, the net flow is negative below 111 bar). It is the pump-side flow needed to
hold a pressure, so the holding command of :mod:`loader_model.plant.equilibrium` follows from
it while the valves are open, and V_p0 = 0 while they are closed. Modelled as a cylinder leak
it damped the baseline as a series damper on the boom support (about 34 rad/s on the 4.7 Hz
boom mode).

The seal leakage k_seal (parameter file ``[leakage] k_seal``) is an estimate at the acceptance
limit of a 63 mm bore in an excavator service manual (1.6 ml per 10 min): 1.1e-16 m³/(s·Pa) per
cylinder, a drift of 0.014 mm/min at 69 bar (a compact excavator's drift test allows 6 mm in
3 min for a new boom cylinder, valves and seals together: 2 mm/min; Caterpillar 308C testing
and adjusting manual). With the valves closed and the accumulator shut, the boom drifts
quasi-statically at ẋ_cyl = −Q_seal / (n A_p): p_A stays at the pressure that holds the boom
(nearly: it eases by a few Pa/s as the boom sinks, and the oil's compliance takes 0.2-0.3 % of
the leak, ``tests/plant/test_circuit.py``).
"""

from __future__ import annotations

from typing import Any

from loader_model.plant import components as hyd

__all__ = ["circuit_flows"]

Expr = Any


def circuit_flows(
    theta: dict[str, Expr], p_a: Expr, p_b: Expr, velocity: Expr, displacement: Expr
) -> dict[str, Expr]:
    """Flows of the lift circuit in its valve state (module docstring), totals over cylinders.

    Parameters
    ----------
    theta
        Plant parameters by name (:data:`~loader_model.plant.plant_parameters.
        PLANT_PARAMETER_NAMES`).
    p_a, p_b
        Chamber pressures (gauge), Pa.
    velocity
        Cylinder extension rate ẋ_cyl, m/s.
    displacement
        Saturated pump displacement V_p, m³/rev.

    Returns
    -------
    dict
        ``pump_flow`` (into the piston side), ``charge``, ``check``, ``relief``, ``leakage``
        (from A to B: Table 5's flow while open, the seal leakage while closed).
    """
    open_ = theta["holding_open"]
    closed = 1 - open_
    valves = theta["valves_on"]
    pump_flow = open_ * theta["pump_on"] * theta["n_pump"] * displacement
    charge = valves * theta["G_charge"] * (theta["p_charge"] - p_b)
    check = valves * theta["G_check"] * hyd.ramp(theta["p_charge"] - p_a, 1e4)
    relief = valves * theta["G_relief"] * hyd.ramp(p_a - theta["p_relief"], 1e5)
    regression = hyd.leakage_flow(theta["k_Lp"], theta["k_Lv"], p_a, p_b, velocity)
    seal = theta["n_cyl"] * theta["k_seal"] * (p_a - p_b)
    leakage = theta["leakage_on"] * (open_ * regression + closed * seal)
    return {
        "pump_flow": pump_flow,
        "charge": charge,
        "check": check,
        "relief": relief,
        "leakage": leakage,
    }
