"""Discrete controllers as the simulator sees them, and the baseline that holds the boom.

The interface: a controller is a CasADi Function

.. math:: (z_{k+1}, u_k) = \\mathrm{controller}(z_k, y_k, \\theta_c)

evaluated every controller period (1 ms, 1 kHz) with zero-order hold on u. z is its state vector
(may be empty), y the plant's output vector in :data:`~loader_model.plant.plant.OUTPUT_NAMES`
order (after a sensor model, if any), θ_c a numeric settings vector, u the pump displacement
command V_p,ref in m³/rev. Inputs and outputs are named ``z``, ``y``, ``settings`` and ``z_next``,
``u``. :func:`check_controller` checks a Function against this.
"""

from __future__ import annotations

import casadi as ca

from loader_model.plant.layout import SKID_STEER, PlantLayout

__all__ = ["CONTROLLER_PERIOD_S", "check_controller", "hold_command_controller", "hold_controller"]

#: Controller period in s (the paper's 1 kHz real-time target).
CONTROLLER_PERIOD_S = 1e-3


def _outputs(layout: PlantLayout) -> int:
    return len(layout.output_names)


def hold_controller(u0: float, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """The baseline controller: the pump holds the boom at the static command ``u0``.

    Parameters
    ----------
    u0 : float
        Pump displacement command in m³/rev, normally the second value of
        :func:`~loader_model.plant.equilibrium.static_state`.

    Returns
    -------
    casadi.Function
        ``hold(z, y, settings) -> (z_next, u)`` with empty z and settings, u = u0.
    """
    z = ca.SX.sym("z", 0)
    y = ca.SX.sym("y", _outputs(layout))
    settings = ca.SX.sym("settings", 0)
    return ca.Function(
        "hold",
        [z, y, settings],
        [z, ca.SX(float(u0))],
        ["z", "y", "settings"],
        ["z_next", "u"],
    )


def hold_command_controller(layout: PlantLayout = SKID_STEER) -> ca.Function:
    """The baseline controller with the held command as its one setting.

    ``hold(z, y, settings) -> (z_next, u)`` with empty z and u = settings[0] (m³/rev). The same
    Function for every plant, so the simulator compiles its period once, whatever the static
    command (:func:`hold_controller` builds the command into the Function).
    """
    z = ca.SX.sym("z", 0)
    y = ca.SX.sym("y", _outputs(layout))
    settings = ca.SX.sym("settings", 1)
    return ca.Function(
        "hold", [z, y, settings], [z, settings[0]], ["z", "y", "settings"], ["z_next", "u"]
    )


def check_controller(controller: object, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """Check that ``controller`` has the controller interface (module notes); return it.

    Raises
    ------
    ValueError
        If it is not a casadi.Function with inputs (z, y, settings) and outputs (z_next, u) of
        matching sizes: y of len(OUTPUT_NAMES), u scalar, z_next as long as z, all column vectors.
    """
    if not isinstance(controller, ca.Function):
        raise ValueError(f"controller must be a casadi.Function; got {type(controller).__name__}")
    if controller.n_in() != 3 or controller.n_out() != 2:
        raise ValueError(
            f"controller {controller.name()!r} must map (z, y, settings) to (z_next, u); it has "
            f"{controller.n_in()} inputs and {controller.n_out()} outputs"
        )
    for index in range(3):
        if controller.size2_in(index) > 1:
            raise ValueError(f"controller input {index} must be a column vector")
    nz, ny = controller.size1_in(0), controller.size1_in(1)
    names = layout.output_names
    if ny != len(names):
        raise ValueError(
            f"controller {controller.name()!r} takes y of size {ny}; the plant has "
            f"{len(names)} outputs {names}"
        )
    if controller.numel_out(0) != nz or controller.numel_out(1) != 1:
        raise ValueError(
            f"controller {controller.name()!r} must return z_next of size {nz} and a scalar u; "
            f"got {controller.numel_out(0)} and {controller.numel_out(1)}"
        )
    return controller
