"""Units and descriptions of the FMU's variables (:mod:`loader_model.fmu.variables`).

The names are the skid-steer's; another machine's further names get theirs from their form.
"""

from __future__ import annotations

from loader_model.plant.plant import EXOGENOUS_NAMES, STATE_NAMES
from loader_model.simulation.result import COLUMN_UNITS

__all__: list[str] = []

_EXOGENOUS_UNITS = dict.fromkeys(EXOGENOUS_NAMES[0:4], "m") | dict.fromkeys(
    EXOGENOUS_NAMES[4:8], "m/s"
)
_EXOGENOUS_UNITS |= {"F_dx": "N", "F_dy": "N", "M_d": "N*m"}
_AXLE = {"A": "front axle A", "B": "rear axle B"}
#: Units of the states: the simulation's column table, the one place that gives them.
_STATE_UNITS = {name: COLUMN_UNITS[name] for name in STATE_NAMES}
_STATE_DESCRIPTIONS = {
    "x_H": "chassis centre of gravity H, forward, from static equilibrium",
    "y_H": "chassis centre of gravity H, up, from static equilibrium",
    "theta_1": "chassis pitch angle (nose up positive)",
    "theta_2": "boom angle (absolute)",
    "xi_A": "horizontal tyre anchor of the front axle (stick-slip contact)",
    "xi_B": "horizontal tyre anchor of the rear axle (stick-slip contact)",
    "p_A": "piston-side pressure, gauge (Eq. 36)",
    "p_B": "rod-side pressure, gauge (Eq. 37)",
    "V_p": "pump displacement (Fig. 9)",
    "Vd_p": "rate of the pump displacement (Fig. 9)",
    "V_acc": "oil volume in the accumulator(s)",
    "x_s": "spool position of the proportional valve (Merritt, ch. 3)",
    "xd_s": "spool velocity of the proportional valve",
    "u_Px": "seat pad relative to S, forward, from the static deflection",
    "u_Ox": "occupant's moving mass relative to S, forward, from the static deflection",
    "u_Py": "seat pad relative to S, up, from the static deflection",
    "u_Oy": "occupant's moving mass relative to S, up, from the static deflection",
}
#: Smallest nominal magnitude of each state (absolute tolerance = relative tolerance × nominal).
_NOMINAL_FLOOR = {"m": 1e-3, "rad": 1e-3, "m/s": 1e-2, "rad/s": 1e-2, "Pa": 1e5}
_OUTPUTS = {
    "xd_H": ("m/s", "forward velocity of H (Eq. 40)"),
    "yd_H": ("m/s", "vertical velocity of H (Eq. 40)"),
    "thetad_1": ("rad/s", "chassis pitch rate (Eq. 40)"),
    "phi": ("rad", "boom angle relative to the chassis, theta_2 - theta_1 (Eq. 40)"),
    "f_Hx": ("m/s^2", "specific force at H, forward (accelerometer, gravity included)"),
    "f_Hy": ("m/s^2", "specific force at H, up (accelerometer, gravity included)"),
    "f_Ny": ("m/s^2", "specific force at the forward sensor point N, up"),
    "f_Sx": ("m/s^2", "specific force of the chassis at the seat base S, forward"),
    "f_Sy": ("m/s^2", "specific force of the chassis at the seat base S, up"),
    "thetadd_1": ("rad/s^2", "chassis pitch acceleration"),
    "p_A": ("Pa", "piston-side pressure, gauge"),
    "p_B": ("Pa", "rod-side pressure, gauge"),
    "F_act": ("N", "cylinder force, all cylinders (Eq. 31)"),
    "x_piston": ("m", "piston position from the retracted end"),
    "V_p": ("m^3/rev", "pump displacement"),
    "Q_pump": ("m^3/s", "pump flow"),
    "x_s": ("m", "spool position of the proportional valve"),
    "Q_supply": ("m^3/s", "supply flow of the valve circuit (load-sensing pump or source)"),
    "F_Ay": ("N", "vertical tyre force at the front axle"),
    "F_By": ("N", "vertical tyre force at the rear axle"),
    "p_acc": ("Pa", "accumulator gas pressure, gauge"),
    "f_Px": ("m/s^2", "seat pad under the occupant, forward (gravity included, section 5.3)"),
    "f_Py": ("m/s^2", "seat pad under the occupant, up (gravity included, section 5.3)"),
}
