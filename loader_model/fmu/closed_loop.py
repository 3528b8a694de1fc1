r"""The closed loop in the FMU: plant + one discrete 1 kHz controller, sampled by time events.

The controllers of :mod:`loader_model.control.controllers` are discrete (sample time T_s = 1 ms).
The FMU keeps them discrete instead of replacing them by a continuous equivalent: FMI 2.0 Model
Exchange has time events for exactly this. At every sample t_k = t_0 + k T_s the FMU asks for an
event (``nextEventTime``), reads the plant outputs y(t_k) (the plant has no direct feedthrough
from the command), and updates

.. math:: (z_{k+1}, u_k) = \mathrm{controller}(z_k, y_{sensor}(t_k), \theta_c)

holding u_k as the pump command until t_{k+1} (zero-order hold, as the 1 kHz target does). The
controller states start at their fixed point at the initial plant outputs (the filters are linear
in z: z_0 = (I − A)⁻¹ z_next(0, y_0)), so a loader at rest stays at rest. The command V_p_ref is
an output of the closed-loop FMU; the road and disturbances stay inputs.

Controller parameters: the settings of :data:`~loader_model.control.settings.SETTINGS_NAMES`
as ``controller.<name>``, except four facts of the plant that the graph takes from the plant's
own parameters (V_p_max, or a valve circuit's spool stroke x_s_max; g, N_x) and from its static
equilibrium (u_hold), so that changing a plant parameter in the importing tool keeps the
controller consistent. A valve circuit's command is the spool position x_s_ref.

Any described machine: the controllers read their sensors by name
(:data:`~loader_model.control.sensors.SENSOR_NAMES`: f_Hx, f_Hy, f_Ny, φ, p_A), which every
machine's plant layout has among its outputs, and the settings' plant facts by parameter name;
the graph takes the machine's outputs, states and FMU parameters from
:func:`~loader_model.plant.layout.plant_layout` and
:func:`~loader_model.fmu.variables.fmu_parameter_names`. A machine whose plant lacks a sensor
or one of those parameters is refused naming it.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from loader_model.control.controllers import controller_function, controller_state_names
from loader_model.control.sensors import SENSOR_NAMES
from loader_model.control.settings import SETTINGS_NAMES
from loader_model.fmu.variables import ACTUATOR_COMMANDS, FmuVariable, fmu_parameter_names
from loader_model.plant.layout import SKID_STEER, PlantLayout

__all__ = [
    "CONTROLLER_PARAMETERS",
    "closed_loop_functions",
    "closed_loop_variables",
    "controller_parameter_values",
]

#: Settings the graph takes from the plant: setting name -> plant parameter (u_hold: equilibrium;
#: V_p_max: the actuator's command limit, a valve's spool stroke x_s_max).
_FROM_PLANT = {"V_p_max": "V_p_max", "g": "g", "N_x": "N_x", "u_hold": None}


def _from_plant(layout: PlantLayout) -> dict[str, str | None]:
    """:data:`_FROM_PLANT` for the machine's circuit: the command limit is its own parameter."""
    return _FROM_PLANT | {"V_p_max": layout.command_limit}


#: (name, unit, description) of the controller's FMU parameters, in value-reference order.
CONTROLLER_PARAMETERS: tuple[tuple[str, str, str], ...] = (
    ("k_x", "", "K_fb on the normalised forward velocity of H (Table 3)"),
    ("k_y", "", "K_fb on the normalised vertical velocity of H (Table 3)"),
    ("k_theta", "", "K_fb on the normalised pitch rate (Table 3)"),
    ("k_phi", "", "K_fb on the normalised boom angle (Table 3)"),
    ("tau", "rad/s", "corner of the semi-integrator 1/(s + tau) (section 3.3)"),
    ("k_p", "", "pressure-loop gain on normalised signals (section 3.2)"),
    ("omega_hp", "rad/s", "corner of the high-pass on p_A"),
    ("T_s", "s", "sample time of the controller (1 kHz)"),
    ("a_norm", "m/s^2", "normalisation of linear acceleration (2 g)"),
    ("alpha_norm", "rad/s^2", "normalisation of angular acceleration"),
    ("phi_norm", "rad", "normalisation of the boom angle"),
    ("u_limit", "m^3/rev", "saturation of the command (the pump's; a valve's in m of spool)"),
    ("p_norm", "Pa", "normalisation of p_A for the load case"),
    ("phi_0", "rad", "boom angle of the operating point (plant output phi)"),
)
_EXPOSED = tuple(name for name, _, _ in CONTROLLER_PARAMETERS)
assert set(_EXPOSED) | set(_FROM_PLANT) == set(SETTINGS_NAMES)


def controller_parameter_values(settings: np.ndarray) -> np.ndarray:
    """The controller's FMU parameter values from a full settings vector (SETTINGS_NAMES order)."""
    settings = np.asarray(settings, dtype=float)
    return np.array([settings[SETTINGS_NAMES.index(name)] for name in _EXPOSED])


def _named_indices(
    names: tuple[str, ...], wanted: tuple[str, ...], what: str, layout: PlantLayout
) -> list[int]:
    """Indices of ``wanted`` in ``names``; ValueError naming the missing ones."""
    missing = [name for name in wanted if name not in names]
    if missing:
        raise ValueError(
            f"machine {layout.name!r}: its plant has no {what} {missing} that the controller "
            f"reads; a closed-loop FMU needs {list(wanted)}"
        )
    return [names.index(name) for name in wanted]


def closed_loop_functions(
    controller: str, ode: ca.Function, start: ca.Function, layout: PlantLayout = SKID_STEER
) -> tuple[ca.Function, ca.Function]:
    """``fmu_sample(x, in, p, z) -> (z_next, u)`` and ``fmu_ctrl_init(x, in, p) -> z0``.

    ``p`` is (FMU plant parameters, controller parameters); ``in`` is (held command, w).
    ``ode`` and ``start`` are the plant FMU's Functions (:func:`~loader_model.fmu.build.
    fmu_functions`) of the machine ``layout`` (default the skid-steer), whose outputs, states and FMU
    parameters are then named by its plant layout.

    Raises
    ------
    ValueError
        For an unknown controller, or a machine whose plant lacks a sensor output or a plant
        fact of the settings (named).
    """
    law = controller_function(controller)
    n_z = len(controller_state_names(controller))
    parameter_names = fmu_parameter_names(layout)
    n_p = len(parameter_names)
    from_plant = _from_plant(layout)
    facts_from = tuple(v for v in from_plant.values() if v)
    fact_index = dict(
        zip(
            facts_from,
            _named_indices(parameter_names, facts_from, "parameters", layout),
            strict=True,
        )
    )
    sensor_index = _named_indices(layout.output_names, SENSOR_NAMES, "outputs", layout)
    (hold_index,) = _named_indices(layout.state_names, (layout.actuator_state,), "state", layout)
    x = ca.SX.sym("x", ode.size1_in(0))
    inputs = ca.SX.sym("in", ode.size1_in(1))
    p = ca.SX.sym("p", n_p + len(_EXPOSED))
    z = ca.SX.sym("z", n_z)
    plant_p, exposed = p[:n_p], dict(zip(_EXPOSED, ca.vertsplit(p[n_p:]), strict=True))
    _, y = ode(x, inputs, plant_p)
    x0 = start(plant_p)
    # the holding command of the static equilibrium is the actuator's static state (V_p, x_s)
    facts = {
        "u_hold": x0[hold_index],
        **{k: plant_p[fact_index[v]] for k, v in from_plant.items() if v},
    }
    settings = ca.vertcat(*[exposed.get(name, facts.get(name)) for name in SETTINGS_NAMES])
    sensors = ca.vertcat(*[y[i] for i in sensor_index])
    z_next, u = law(z, sensors, settings)
    sample = ca.Function(
        "fmu_sample", [x, inputs, p, z], [z_next, u], ["x", "in", "p", "z"], ["z_next", "u"]
    )
    free = ca.substitute(z_next, z, ca.SX.zeros(n_z))
    a = ca.jacobian(z_next, z)
    z0 = ca.solve(ca.SX.eye(n_z) - a, free) if n_z else ca.SX(0, 1)
    init = ca.Function("fmu_ctrl_init", [x, inputs, p], [z0], ["x", "in", "p"], ["z0"])
    return sample, init


def closed_loop_variables(
    plant_variables: list[FmuVariable],
    controller: str,
    settings: np.ndarray,
    layout: PlantLayout = SKID_STEER,
) -> list[FmuVariable]:
    """The closed-loop FMU's Real variables, renumbered 0, 1, ... (wrapper layout).

    Order: plant parameters (those of the machine ``layout``, default the skid-steer), ``controller.
    <setting>``, ``V_p_ref`` (now a discrete output: the held command), the exogenous inputs,
    states, derivatives, plant outputs, ``controller.<z>``.
    """
    from dataclasses import replace

    n_p = len(fmu_parameter_names(layout))
    command_name, command_unit, command_description = ACTUATOR_COMMANDS[layout.circuit]
    if plant_variables[n_p].name != command_name:
        raise ValueError(
            f"plant_variables of machine {layout.name!r}: variable {n_p} is "
            f"{plant_variables[n_p].name!r}, expected the command {command_name!r}"
        )
    parameters = [
        (name, command_unit if name == "u_limit" else unit, description)
        for name, unit, description in CONTROLLER_PARAMETERS
    ]
    settings_vars = [
        FmuVariable(
            f"controller.{name}", 0, "parameter", "fixed", "exact", unit, description, value
        )
        for (name, unit, description), value in zip(
            parameters, controller_parameter_values(settings), strict=True
        )
    ]
    command = replace(
        plant_variables[n_p],
        causality="output",
        variability="discrete",
        initial="calculated",
        start=None,
        description=f"{command_description} of the {controller} controller, held over T_s",
    )
    states = [
        FmuVariable(
            f"controller.{name}",
            0,
            "local",
            "discrete",
            "calculated",
            "",
            f"state of the {controller} controller's filters (start: its fixed point)",
        )
        for name in controller_state_names(controller)
    ]
    ordered = [
        *plant_variables[:n_p],
        *settings_vars,
        command,
        *plant_variables[n_p + 1 :],
        *states,
    ]
    return [replace(v, value_reference=i) for i, v in enumerate(ordered)]
