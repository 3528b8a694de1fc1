"""The FMU's variables: names, value references, causality, units, descriptions and start values.

Real value references are laid out in one block, in this order, and the C wrapper stores every
Real in one array indexed by its value reference:

- parameters (causality parameter, fixed): the plant parameters, in the order of
  :data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`, without the static tyre
  loads F_Ay0, F_By0, which the plant completes from the others;
- inputs (input): V_p_ref, then the road and disturbances
  (:data:`~loader_model.plant.plant.EXOGENOUS_NAMES`);
- states (local): ``x.<name>`` (:data:`~loader_model.plant.plant.STATE_NAMES`);
- derivatives (local): ``der(x.<name>)``;
- outputs (output): :data:`~loader_model.plant.plant.OUTPUT_NAMES`.

The one Boolean (value reference 0) is ``start_at_equilibrium``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import loader_model_generated as generated
from loader_model.plant.plant import EXOGENOUS_NAMES, INPUT_NAMES, OUTPUT_NAMES, STATE_NAMES
from loader_model.plant.plant_parameters import (
    HYDRAULIC_PARAMETERS,
    OCCUPANT_PARAMETERS,
    PLANT_PARAMETER_NAMES,
    PLANT_PARAMETER_UNITS,
)

__all__ = [
    "COMPLETED_PARAMETERS",
    "FMU_PARAMETER_NAMES",
    "FmuVariable",
    "fmu_parameter_values",
    "fmu_variables",
    "state_nominals",
]

#: Parameters the plant completes inside its graph (static tyre loads): not exported.
COMPLETED_PARAMETERS: tuple[str, ...] = ("F_Ay0", "F_By0")
#: The FMU's parameters, in value-reference order.
FMU_PARAMETER_NAMES: tuple[str, ...] = tuple(
    name for name in PLANT_PARAMETER_NAMES if name not in COMPLETED_PARAMETERS
)

_EXOGENOUS_UNITS = dict.fromkeys(EXOGENOUS_NAMES[0:4], "m") | dict.fromkeys(
    EXOGENOUS_NAMES[4:8], "m/s"
)
_EXOGENOUS_UNITS |= {"F_dx": "N", "F_dy": "N", "M_d": "N*m"}
_AXLE = {"A": "front axle A", "B": "rear axle B"}
_STATE_UNITS = {
    "x_H": "m",
    "y_H": "m",
    "theta_1": "rad",
    "theta_2": "rad",
    "xd_H": "m/s",
    "yd_H": "m/s",
    "thetad_1": "rad/s",
    "thetad_2": "rad/s",
    "xi_A": "m",
    "xi_B": "m",
    "p_A": "Pa",
    "p_B": "Pa",
    "V_p": "m^3/rev",
    "Vd_p": "m^3/(rev*s)",
    "V_acc": "m^3",
    **{name: "m" for name in ("u_Px", "u_Ox", "u_Py", "u_Oy")},
    **{name: "m/s" for name in ("ud_Px", "ud_Ox", "ud_Py", "ud_Oy")},
}
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
    "F_Ay": ("N", "vertical tyre force at the front axle"),
    "F_By": ("N", "vertical tyre force at the rear axle"),
    "p_acc": ("Pa", "accumulator gas pressure, gauge"),
    "f_Px": ("m/s^2", "seat pad under the occupant, forward (gravity included, section 5.3)"),
    "f_Py": ("m/s^2", "seat pad under the occupant, up (gravity included, section 5.3)"),
}


@dataclass(frozen=True)
class FmuVariable:
    """One Real variable of the FMU (FMI 2.0 ``ScalarVariable``).

    Attributes
    ----------
    name, causality, variability, initial : str
        FMI 2.0 attributes (``initial`` empty: none written).
    value_reference : int
        Index into the wrapper's Real array.
    unit, description : str
        Unit (empty: dimensionless) and one line.
    start : float or None
        Start value, written when not None.
    derivative_of : str or None
        For a derivative: the name of its state.
    nominal : float or None
        Nominal magnitude of a state.
    """

    name: str
    value_reference: int
    causality: str
    variability: str
    initial: str
    unit: str
    description: str
    start: float | None = None
    derivative_of: str | None = None
    nominal: float | None = None


def _unit(unit: str) -> str:
    return "" if unit == "-" else unit


def _parameter_description(name: str) -> str:
    hydraulic = {item[0]: item[2] for item in HYDRAULIC_PARAMETERS + OCCUPANT_PARAMETERS}
    return generated.PARAMETER_DESCRIPTIONS.get(name) or hydraulic[name]


def _exogenous_description(name: str) -> str:
    if name.startswith("w"):
        axle, direction = name[-2], "vertical" if name[-1] == "y" else "horizontal"
        what = "rate of the road" if name.startswith("wd_") else "road"
        return f"{what} under the {_AXLE[axle]}, {direction}"
    return {
        "F_dx": "disturbance force at H, forward (Eq. 5)",
        "F_dy": "disturbance force at H, up (Eq. 6)",
        "M_d": "disturbance moment about H (Eq. 7)",
    }[name]


def fmu_parameter_values(params: np.ndarray) -> np.ndarray:
    """The FMU's parameter values (order :data:`FMU_PARAMETER_NAMES`) from a plant vector."""
    index = [PLANT_PARAMETER_NAMES.index(name) for name in FMU_PARAMETER_NAMES]
    return np.asarray(params, dtype=float)[index]


def state_nominals(x0: np.ndarray, params: np.ndarray) -> np.ndarray:
    """Nominal magnitude of each state: its static value, at least a floor of its unit."""
    values = dict(zip(PLANT_PARAMETER_NAMES, np.asarray(params, dtype=float), strict=True))
    floors = _NOMINAL_FLOOR | {
        "m^3/rev": values["V_p_max"],
        "m^3/(rev*s)": values["Vd_p_max"],
        "m^3": max(values["n_acc"] * values["V_0"], 1e-4),
    }
    return np.array(
        [
            max(abs(float(v)), floors[_STATE_UNITS[name]])
            for name, v in zip(STATE_NAMES, x0, strict=True)
        ]
    )


def fmu_variables(params: np.ndarray, x0: np.ndarray, u0: float) -> list[FmuVariable]:
    """Every Real variable in value-reference order (module docstring), with start values.

    Parameters
    ----------
    params : numpy.ndarray
        Plant parameter vector (order ``PLANT_PARAMETER_NAMES``): the parameters' start values.
    x0, u0
        Static state and pump command of ``params``: the states' and V_p_ref's start values.
    """
    out: list[FmuVariable] = []
    fixed = ("parameter", "fixed", "exact")
    for name, value in zip(FMU_PARAMETER_NAMES, fmu_parameter_values(params), strict=True):
        unit = _unit(PLANT_PARAMETER_UNITS[name])
        out.append(FmuVariable(name, len(out), *fixed, unit, _parameter_description(name), value))
    out.append(
        FmuVariable(
            INPUT_NAMES[0],
            len(out),
            "input",
            "continuous",
            "",
            "m^3/rev",
            "pump displacement command V_p,ref (start: the static command that holds the boom)",
            u0,
        )
    )
    for name in EXOGENOUS_NAMES:
        out.append(
            FmuVariable(
                name,
                len(out),
                "input",
                "continuous",
                "",
                _EXOGENOUS_UNITS[name],
                _exogenous_description(name),
                0.0,
            )
        )
    nominals = state_nominals(x0, params)
    for i, name in enumerate(STATE_NAMES):
        description = _STATE_DESCRIPTIONS.get(name) or f"rate of {name.replace('d', '', 1)}"
        out.append(
            FmuVariable(
                f"x.{name}",
                len(out),
                "local",
                "continuous",
                "approx",
                _STATE_UNITS[name],
                f"state: {description} (start: static equilibrium)",
                float(x0[i]),
                nominal=float(nominals[i]),
            )
        )
    for name in STATE_NAMES:
        unit = _STATE_UNITS[name]
        out.append(
            FmuVariable(
                f"der(x.{name})",
                len(out),
                "local",
                "continuous",
                "calculated",
                f"{unit}/s" if "/" not in unit else f"({unit})/s",
                f"time derivative of x.{name}",
                derivative_of=f"x.{name}",
            )
        )
    for name in OUTPUT_NAMES:
        unit, description = _OUTPUTS[name]
        out.append(
            FmuVariable(name, len(out), "output", "continuous", "calculated", unit, description)
        )
    return out
