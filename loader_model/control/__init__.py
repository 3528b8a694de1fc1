"""Controllers (paper section 3): settings, sensors, the 1 kHz controllers and their linear
equivalents, output-feedback LQR and the H2 / ISO 2631 gain optimisation (certified BFGS or
IPOPT through CasADi), behind one entry point,
:func:`~loader_model.control.gain_design.design_gains`.

The algorithms are generic in the plant: they take numpy matrices or python-control systems.
"""

import importlib
from typing import Any

from loader_model.control.controllers import (
    CONTROLLER_NAMES,
    controller_function,
    controller_state_names,
)
from loader_model.control.design_plant import DesignPlant
from loader_model.control.linear_controller import LinearController, closed_loop, linear_controller
from loader_model.control.sensors import SENSOR_NAMES, SensorModel, sensor_signals
from loader_model.control.settings import (
    SETTINGS_NAMES,
    ControllerSettings,
    default_settings,
    load_settings,
    settings_vector,
    settings_vector_for_plant,
)

__all__ = [
    "CONTROLLER_NAMES",
    "SENSOR_NAMES",
    "SETTINGS_NAMES",
    "ControllerSettings",
    "DesignPlant",
    "GainDesign",
    "LinearController",
    "NoStabilisingGainError",
    "OutputFeedbackResult",
    "SensorModel",
    "closed_loop",
    "controller_function",
    "controller_state_names",
    "default_settings",
    "design_gains",
    "h2_cost_function",
    "h2_costs",
    "linear_controller",
    "load_settings",
    "output_feedback_lqr",
    "sensor_signals",
    "settings_vector",
    "settings_vector_for_plant",
]

#: Names of the design modules, loaded on first access (PEP 562): they import scipy.linalg and
#: scipy.optimize (about 0.4 s), which the simulator, importing this package, does not need.
_LAZY_ATTRIBUTES = {
    "GainDesign": "gain_design",
    "design_gains": "gain_design",
    "h2_cost_function": "h2_cost",
    "h2_costs": "h2_cost",
    "NoStabilisingGainError": "output_feedback",
    "OutputFeedbackResult": "output_feedback",
    "output_feedback_lqr": "output_feedback",
}


def __getattr__(name: str) -> Any:
    module = _LAZY_ATTRIBUTES.get(name)
    if module is None:
        raise AttributeError(f"module 'loader_model.control' has no attribute {name!r}")
    return getattr(importlib.import_module(f"loader_model.control.{module}"), name)
