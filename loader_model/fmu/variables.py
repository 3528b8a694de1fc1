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

Another described machine has the same blocks with the names of its plant layout
(:func:`~loader_model.plant.layout.plant_layout`); its completed parameters are its
``static_names`` (tyre loads and locked-cylinder preloads). Units and descriptions of names the
skid-steer lacks follow from their form (``theta_3``: rad, ``f_Bx``: a specific force, ...).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import loader_model_generated as generated
from loader_model.fmu.variable_tables import (
    _AXLE,
    _EXOGENOUS_UNITS,
    _NOMINAL_FLOOR,
    _OUTPUTS,
    _STATE_DESCRIPTIONS,
    _STATE_UNITS,
)
from loader_model.plant.layout import CIRCUITS, SKID_STEER, PlantLayout
from loader_model.plant.plant import EXOGENOUS_NAMES, INPUT_NAMES, OUTPUT_NAMES, STATE_NAMES
from loader_model.plant.plant_parameters import (
    HYDRAULIC_PARAMETERS,
    OCCUPANT_PARAMETERS,
    PLANT_PARAMETER_NAMES,
    PLANT_PARAMETER_UNITS,
)
from loader_model.plant.valve_circuit import VALVE_PARAMETERS
from loader_model.simulation.result import column_unit

__all__ = [
    "ACTUATOR_COMMANDS",
    "COMPLETED_PARAMETERS",
    "FMU_PARAMETER_NAMES",
    "FmuVariable",
    "fmu_parameter_names",
    "fmu_parameter_values",
    "fmu_variables",
    "state_nominals",
]

#: Per lift circuit, the plant's command input: name, unit, description.
ACTUATOR_COMMANDS: dict[str, tuple[str, str, str]] = {
    "pump": (INPUT_NAMES[0], "m^3/rev", "pump displacement command V_p,ref"),
    "valve": ("x_s_ref", "m", "spool position command x_s,ref of the proportional valve"),
}
#: Parameters the plant completes inside its graph (static tyre loads): not exported.
COMPLETED_PARAMETERS: tuple[str, ...] = ("F_Ay0", "F_By0")
#: The FMU's parameters, in value-reference order.
FMU_PARAMETER_NAMES: tuple[str, ...] = tuple(
    name for name in PLANT_PARAMETER_NAMES if name not in COMPLETED_PARAMETERS
)


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


def _parameter_description(name: str, layout: PlantLayout | None = None) -> str:
    hydraulic = {
        item[0]: item[2] for item in HYDRAULIC_PARAMETERS + OCCUPANT_PARAMETERS + VALVE_PARAMETERS
    }
    if layout is not None and name in layout.machine.parameter_descriptions:
        return layout.machine.parameter_descriptions[name] or name
    return generated.PARAMETER_DESCRIPTIONS.get(name) or hydraulic[name]


def _parameter_unit(name: str, layout: PlantLayout | None) -> str:
    if layout is not None and name in layout.machine.parameter_units:
        return layout.machine.parameter_units[name]
    if name in PLANT_PARAMETER_UNITS:
        return PLANT_PARAMETER_UNITS[name]
    return {item[0]: item[1] for item in VALVE_PARAMETERS}[name]  # a valve circuit's own


def _layout(layout: PlantLayout) -> PlantLayout | None:
    """None for the skid-steer (the module constants), else the machine's plant layout."""
    return None if layout.machine.is_default else layout


def fmu_parameter_names(layout: PlantLayout = SKID_STEER) -> tuple[str, ...]:
    """The FMU's parameters of the machine ``layout`` in value-reference order (its completed
    ones left out).

    For the skid-steer: :data:`FMU_PARAMETER_NAMES`.
    """
    own = _layout(layout)
    if own is None:
        return FMU_PARAMETER_NAMES
    completed = set(own.machine.static_names)
    return tuple(name for name in own.parameter_names if name not in completed)


def _state_unit(name: str) -> str:
    if name in _STATE_UNITS:
        return _STATE_UNITS[name]
    if name.startswith("thetad_"):
        return "rad/s"
    if name.startswith("theta_"):
        return "rad"
    return "m/s" if name.endswith("d") or "d_" in name else "m"


def _output(name: str, layout: PlantLayout | None) -> tuple[str, str]:
    if name in _OUTPUTS or layout is None:
        return _OUTPUTS[name]
    if name in layout.machine.joint_angles:
        return "rad", f"joint angle {name} of a pinned body relative to its parent"
    if name in (item[0] for item in layout.sensor_outputs):
        axis = "forward" if name[-1] == "x" else "up"
        return "m/s^2", f"specific force at point {name[2:-1]}, {axis} (gravity included)"
    if name.startswith("F_") and name.endswith("y"):
        return "N", f"vertical tyre force at axle {name[2:-1]}"
    return "", name


def _exogenous_description(name: str) -> str:
    if name.startswith("w"):
        axle, direction = name[-2], "vertical" if name[-1] == "y" else "horizontal"
        what = "rate of the road" if name.startswith("wd_") else "road"
        return f"{what} under the {_AXLE.get(axle, f'axle {axle}')}, {direction}"
    return {
        "F_dx": "disturbance force at H, forward (Eq. 5)",
        "F_dy": "disturbance force at H, up (Eq. 6)",
        "M_d": "disturbance moment about H (Eq. 7)",
    }[name]


def fmu_parameter_values(params: np.ndarray, layout: PlantLayout = SKID_STEER) -> np.ndarray:
    """The FMU's parameter values (order :func:`fmu_parameter_names`) from a plant vector."""
    own = _layout(layout)
    names = PLANT_PARAMETER_NAMES if own is None else own.parameter_names
    index = [names.index(name) for name in fmu_parameter_names(layout)]
    return np.asarray(params, dtype=float)[index]


def state_nominals(
    x0: np.ndarray, params: np.ndarray, layout: PlantLayout = SKID_STEER
) -> np.ndarray:
    """Nominal magnitude of each state: its static value, at least a floor of its unit."""
    own = _layout(layout)
    names = PLANT_PARAMETER_NAMES if own is None else own.parameter_names
    states = STATE_NAMES if own is None else own.state_names
    values = dict(zip(names, np.asarray(params, dtype=float), strict=True))
    floors = _NOMINAL_FLOOR | {"m^3": max(values["n_acc"] * values["V_0"], 1e-4)}
    # the actuator's position and rate (V_p, Vd_p or x_s, xd_s): at least their limits
    actuator, rate = CIRCUITS[layout.circuit][:2]
    limits = {actuator: values[layout.command_limit], rate: values[layout.rate_limit]}
    return np.array(
        [
            max(abs(float(v)), limits[name] if name in limits else floors[_state_unit(name)])
            for name, v in zip(states, x0, strict=True)
        ]
    )


def fmu_variables(
    params: np.ndarray, x0: np.ndarray, u0: float, layout: PlantLayout = SKID_STEER
) -> list[FmuVariable]:
    """Every Real variable in value-reference order (module docstring), with start values.

    Parameters
    ----------
    params : numpy.ndarray
        Plant parameter vector (order ``PLANT_PARAMETER_NAMES``): the parameters' start values.
    x0, u0
        Static state and pump command of ``params``: the states' and V_p_ref's start values.
    layout : PlantLayout
        The machine (default the skid-steer); ``params`` and ``x0`` are in its layout's orders.
    """
    own = _layout(layout)
    exogenous = EXOGENOUS_NAMES if own is None else own.exogenous_names
    states = STATE_NAMES if own is None else own.state_names
    outputs = OUTPUT_NAMES if own is None else own.output_names
    out: list[FmuVariable] = []
    fixed = ("parameter", "fixed", "exact")
    values = fmu_parameter_values(params, layout)
    for name, value in zip(fmu_parameter_names(layout), values, strict=True):
        unit = _unit(_parameter_unit(name, own))
        description = _parameter_description(name, own)
        out.append(FmuVariable(name, len(out), *fixed, unit, description, value))
    command, unit, description = ACTUATOR_COMMANDS[layout.circuit]
    out.append(
        FmuVariable(
            command,
            len(out),
            "input",
            "continuous",
            "",
            unit,
            f"{description} (start: the static command that holds the boom)",
            u0,
        )
    )
    for name in exogenous:
        out.append(
            FmuVariable(
                name,
                len(out),
                "input",
                "continuous",
                "",
                _EXOGENOUS_UNITS.get(name) or column_unit(name),
                _exogenous_description(name),
                0.0,
            )
        )
    nominals = state_nominals(x0, params, layout)
    for i, name in enumerate(states):
        description = _STATE_DESCRIPTIONS.get(name) or (
            f"rate of {name.replace('d', '', 1)}" if "d_" in name else f"coordinate {name}"
        )
        out.append(
            FmuVariable(
                f"x.{name}",
                len(out),
                "local",
                "continuous",
                "approx",
                _state_unit(name),
                f"state: {description} (start: static equilibrium)",
                float(x0[i]),
                nominal=float(nominals[i]),
            )
        )
    for name in states:
        unit = _state_unit(name)
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
    for name in outputs:
        unit, description = _output(name, own)
        out.append(
            FmuVariable(name, len(out), "output", "continuous", "calculated", unit, description)
        )
    return out
