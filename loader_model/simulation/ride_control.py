"""The ride controllers of :mod:`loader_model.control` on the simulator's interface.

The controllers read the five sensor signals (:data:`loader_model.control.sensors.SENSOR_NAMES`),
the simulator hands them the plant's whole output vector; :func:`plant_controller` composes the
selection with the controller's own CasADi Function (one implementation, no copy), and
:func:`controller_setup` gives its settings vector for a plant and its initial state: the
controller's fixed point at the plant's static readings, so the high-pass on p_A and the
semi-integrators start settled instead of seeing the static pressure as a step.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from loader_model.plant.plant import OUTPUT_NAMES

__all__ = ["RIDE_CONTROLLERS", "controller_setup", "plant_controller"]

#: Command-line names of the ride controllers and the controller Function each one uses.
RIDE_CONTROLLERS = {
    "baseline": "baseline",
    "passive": "passive",
    "virtual-accumulator": "virtual_accumulator",
    "skyhook": "skyhook",
}


def plant_controller(name: str) -> ca.Function:
    """``controller(z, y, settings) -> (z_next, u)`` of ride controller ``name`` on the plant's
    output vector ``y`` (order :data:`~loader_model.plant.plant.OUTPUT_NAMES`)."""
    from loader_model.control.controllers import controller_function
    from loader_model.control.sensors import SENSOR_NAMES

    if name not in RIDE_CONTROLLERS:
        raise ValueError(f"controller {name!r} is unknown; allowed: {list(RIDE_CONTROLLERS)}")
    inner = controller_function(RIDE_CONTROLLERS[name])
    z = ca.SX.sym("z", inner.size1_in(0))
    y = ca.SX.sym("y", len(OUTPUT_NAMES))
    settings = ca.SX.sym("settings", inner.size1_in(2))
    sensors = ca.vertcat(*(y[OUTPUT_NAMES.index(signal)] for signal in SENSOR_NAMES))
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
    """
    from loader_model.control.linear_controller import operating_state
    from loader_model.control.sensors import sensor_signals
    from loader_model.control.settings import default_settings, settings_vector_for_plant
    from loader_model.plant.equilibrium import static_state
    from loader_model.plant.plant import plant_function

    if name not in RIDE_CONTROLLERS:
        raise ValueError(f"controller {name!r} is unknown; allowed: {list(RIDE_CONTROLLERS)}")
    vector = settings_vector_for_plant(settings or default_settings(), params, pressure_norm_pa)
    state, command = static_state(params)
    outputs = np.asarray(
        plant_function()(state, command, np.zeros(11), params)[1], dtype=float
    ).ravel()
    fixed = operating_state(RIDE_CONTROLLERS[name], vector, sensor_signals(outputs))
    return vector, np.asarray(fixed, dtype=float).ravel()
