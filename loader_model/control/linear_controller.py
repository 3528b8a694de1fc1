r"""Linear equivalents of the discrete controllers and their closed loops with the linearised plant.

The equivalent is the Jacobian of the same CasADi Function (:mod:`loader_model.control.controllers`),
not a second copy of the laws:

.. math::

    \delta z_{k+1} = A_d\,\delta z_k + B_d\,\delta y_k, \qquad \delta u_k = C\,\delta z_k + D\,\delta y_k

at the operating point (z0, y0): y0 the sensor readings of the static plant, z0 the controller's
fixed point there (the filters are linear in z and y, so z0 = (I − A_d)⁻¹ z_next(0, y0)). The
continuous equivalent inverts the ZOH exactly (the filters were ZOH-discretised),

.. math::

    \begin{bmatrix} A_c & B_c \\ 0 & 0 \end{bmatrix}
    = \frac{1}{T}\log\begin{bmatrix} A_d & B_d \\ 0 & I \end{bmatrix}

with the same C and D, which gives back the continuous filters 1/(s + τ) and s/(s + ω_hp).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from loader_model.control.controllers import controller_function, controller_state_names
from loader_model.control.sensors import SENSOR_NAMES
from loader_model.control.settings import SETTINGS_NAMES

__all__ = ["LinearController", "closed_loop", "linear_controller"]


@dataclass(frozen=True)
class LinearController:
    """Linear equivalent of one controller at an operating point.

    Attributes
    ----------
    discrete, continuous : control.StateSpace
        Inputs :data:`~loader_model.control.sensors.SENSOR_NAMES`, output ``V_p_ref``, states
        named after the controller's; ``discrete.dt`` is the sample time.
    operating_state : numpy.ndarray
        z0, the controller's fixed point at the operating readings.
    operating_command : float
        u0 = u(z0, y0) [m³/rev].
    """

    discrete: Any
    continuous: Any
    operating_state: np.ndarray
    operating_command: float


def _jacobians(name: str) -> ca.Function:
    f = controller_function(name)
    z, y, s = (ca.SX.sym(n, f.size1_in(i)) for i, n in enumerate(("z", "y", "s")))
    z_next, u = f(z, y, s)
    return ca.Function(
        f"{name}_jacobians",
        [z, y, s],
        [z_next, u, *(ca.jacobian(out, v) for out in (z_next, u) for v in (z, y))],
    )


def _checked(settings: np.ndarray, y_sensor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    settings = np.asarray(settings, dtype=float).ravel()
    y0 = np.asarray(y_sensor, dtype=float).ravel()
    if settings.shape != (len(SETTINGS_NAMES),) or y0.shape != (len(SENSOR_NAMES),):
        raise ValueError(
            f"settings has {settings.size} entries, y_sensor {y0.size}; "
            f"expected {len(SETTINGS_NAMES)} and {len(SENSOR_NAMES)}"
        )
    return settings, y0


def operating_state(name: str, settings: np.ndarray, y_sensor: np.ndarray) -> np.ndarray:
    """Fixed point z0 of controller ``name`` at the constant readings ``y_sensor``.

    What :func:`linear_controller` returns as ``operating_state``, without building its
    python-control systems (for the simulator's start, which needs only z0).
    """
    settings, y0 = _checked(settings, y_sensor)
    n = len(controller_state_names(name))
    at_zero = _jacobians(name)(np.zeros(n), y0, settings)
    a_d, free = np.asarray(at_zero[2]).reshape(n, n), np.asarray(at_zero[0]).ravel()
    return np.linalg.solve(np.eye(n) - a_d, free) if n else np.zeros(0)


def linear_controller(name: str, settings: np.ndarray, y_sensor: np.ndarray) -> LinearController:
    """Linearise controller ``name`` at the sensor readings ``y_sensor`` (its fixed point).

    Parameters
    ----------
    name : str
        One of :data:`~loader_model.control.controllers.CONTROLLER_NAMES`.
    settings : numpy.ndarray
        Settings vector (:func:`~loader_model.control.settings.settings_vector`).
    y_sensor : numpy.ndarray
        Operating readings (order :data:`~loader_model.control.sensors.SENSOR_NAMES`), e.g.
        :func:`~loader_model.control.sensors.sensor_signals` of the static plant outputs.
    """
    import control
    import scipy.linalg  # here, not at the top: the simulator imports this package

    settings, y0 = _checked(settings, y_sensor)
    states = list(controller_state_names(name))
    n = len(states)
    z0 = operating_state(name, settings, y0)
    _, u0, a_d, b_d, c, d = (np.asarray(m, dtype=float) for m in _jacobians(name)(z0, y0, settings))
    m = len(SENSOR_NAMES)
    a_d, b_d = a_d.reshape(n, n), b_d.reshape(n, m)
    c, d = c.reshape(1, n), d.reshape(1, m)
    dt = float(settings[SETTINGS_NAMES.index("T_s")])
    signals = {"inputs": list(SENSOR_NAMES), "outputs": ["V_p_ref"], "states": states}
    discrete = control.ss(a_d, b_d, c, d, dt=dt, name=f"{name}_discrete", **signals)
    block = np.zeros((n + m, n + m))
    block[:n, :n], block[:n, n:], block[n:, n:] = a_d, b_d, np.eye(m)
    log = np.real(scipy.linalg.logm(block)) / dt if n else np.zeros_like(block)
    continuous = control.ss(log[:n, :n], log[:n, n:], c, d, name=f"{name}_continuous", **signals)
    return LinearController(discrete, continuous, z0, float(u0.item()))


def closed_loop(plant: Any, controller: Any, name: str = "closed_loop") -> Any:
    """Close the loop of a linearised plant and a linear controller (continuous or discrete).

    Parameters
    ----------
    plant : control.StateSpace
        Continuous plant with the actuator's command first (``V_p_ref``, or a valve's
        ``x_s_ref``: the controller's output drives it), outputs including
        :data:`~loader_model.control.sensors.SENSOR_NAMES`, and optionally exogenous inputs
        (:meth:`loader_model.plant.linear.PlantLinearisation.state_space`).
    controller : control.StateSpace
        :attr:`LinearController.continuous` or :attr:`LinearController.discrete`; a discrete one
        closes the loop with the plant discretised by ZOH at its sample time.

    Returns
    -------
    control.StateSpace
        Inputs: the plant's inputs other than the command; outputs: the plant's outputs, then
        the command.
    """
    import control

    if controller.dt not in (0, None) and plant.dt in (0, None):
        plant = control.sample_system(plant, controller.dt, method="zoh", name=plant.name)
    command = plant.input_labels[0]  # V_p_ref, or a valve circuit's spool command x_s_ref
    if list(controller.output_labels) != [command]:
        controller = control.ss(
            controller.A,
            controller.B,
            controller.C,
            controller.D,
            controller.dt,
            inputs=list(controller.input_labels),
            outputs=[command],
            states=list(controller.state_labels),
            name=controller.name,
        )
    inputs = [n for n in plant.input_labels if n != command]
    return control.interconnect(
        [plant, controller],
        inputs=inputs,
        outputs=[*plant.output_labels, command],
        name=name,
    )
