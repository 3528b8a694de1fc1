"""The ride controllers of :mod:`loader_model.control` on the simulator's interface.

The controllers read the five sensor signals (:data:`loader_model.control.sensors.SENSOR_NAMES`),
the simulator hands them the plant's whole output vector; :func:`plant_controller` composes the
selection with the controller's own CasADi Function (one implementation, no copy), and
:func:`controller_setup` gives its settings vector for a plant and its initial state: the
controller's fixed point at the plant's static readings, so the high-pass on p_A and the
semi-integrators start settled instead of seeing the static pressure as a step.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from loader_model.plant.layout import PlantLayout
from loader_model.plant.plant import OUTPUT_NAMES

if TYPE_CHECKING:
    from loader_model.plant.scenario import PlantScenario

__all__ = ["RIDE_CONTROLLERS", "controller_setup", "plant_controller", "plant_controller_setup"]

#: Command-line names of the ride controllers and the controller Function each one uses.
RIDE_CONTROLLERS = {
    "baseline": "baseline",
    "passive": "passive",
    "virtual-accumulator": "virtual_accumulator",
    "skyhook": "skyhook",
}


def plant_controller(name: str, layout: PlantLayout | None = None) -> ca.Function:
    """``controller(z, y, settings) -> (z_next, u)`` of ride controller ``name`` on the plant's
    output vector ``y`` (order :data:`~loader_model.plant.plant.OUTPUT_NAMES`, or that of
    the plant of the machine ``layout``: the sensors by name)."""
    from loader_model.control.controllers import controller_function
    from loader_model.control.sensors import SENSOR_NAMES

    _check(name)
    inner = controller_function(RIDE_CONTROLLERS[name])
    z = ca.SX.sym("z", inner.size1_in(0))
    names = OUTPUT_NAMES if layout is None else layout.output_names
    y = ca.SX.sym("y", len(names))
    settings = ca.SX.sym("settings", inner.size1_in(2))
    sensors = ca.vertcat(*(y[names.index(signal)] for signal in SENSOR_NAMES))
    z_next, u = inner(z, sensors, settings)
    return ca.Function(
        f"{inner.name()}_on_plant",
        [z, y, settings],
        [z_next, u],
        ["z", "y", "settings"],
        ["z_next", "u"],
    )


def controller_setup(
    name: str, params: np.ndarray, pressure_norm_pa: float, settings: Any = None
) -> tuple[np.ndarray, np.ndarray]:
    """Settings vector and initial state (the fixed point at the static readings) of ``name``.

    Parameters
    ----------
    name : str
        One of :data:`RIDE_CONTROLLERS`.
    params : numpy.ndarray
        Plant parameters.
    pressure_norm_pa : float
        ‖p_A‖∞ of the bucket load (section 3.3: 100 bar empty, 200 bar full).
    settings : loader_model.control.settings.ControllerSettings, optional
        Default: the shipped Table 3 settings.

    Notes
    -----
    Computes the plant's equilibrium; :func:`plant_controller_setup` takes it from a
    :class:`~loader_model.plant.scenario.PlantScenario` instead.
    """
    from loader_model.plant.scenario import PlantScenario

    _check(name)
    return plant_controller_setup(
        name, PlantScenario.from_vector(params), pressure_norm_pa, settings
    )


def plant_controller_setup(
    name: str, plant: PlantScenario, pressure_norm_pa: float, settings: Any = None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`controller_setup` on a resolved plant: its parameters, u0 and static outputs y0,
    without computing the equilibrium again."""
    from loader_model.control.linear_controller import operating_state
    from loader_model.control.sensors import sensor_signals
    from loader_model.control.settings import default_settings, settings_vector_for_plant

    _check(name)
    vector = settings_vector_for_plant(
        settings or default_settings(),
        plant.params,
        pressure_norm_pa,
        hold_command=plant.u0,
        layout=plant.layout,
    )
    readings = sensor_signals(plant.y0, plant.layout)
    fixed = operating_state(RIDE_CONTROLLERS[name], vector, readings)
    return vector, np.asarray(fixed, dtype=float).ravel()


def _check(name: str) -> None:
    if name not in RIDE_CONTROLLERS:
        raise ValueError(f"controller {name!r} is unknown; allowed: {list(RIDE_CONTROLLERS)}")
