"""A tight-tolerance reference of the closed loop: CVODES over each controller period.

Same plant, same controller at the same instants and zero-order hold, same road table (linear
inside each period); only the integration differs: CVODES (BDF, Newton with the AD Jacobian) at
``rtol`` 1e-10 per period, restarted at each period so that the command's steps are exact. Slow
(seconds per simulated second): a check of :func:`~loader_model.simulation.simulator.simulate`,
not a tool. Any described machine (:mod:`loader_model.machines`; default the skid-steer): its
plant Function, its sizes and names (:func:`~loader_model.plant.layout.plant_layout`).
"""

from __future__ import annotations

from collections.abc import Sequence

import casadi as ca
import numpy as np

from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.plant import plant_function
from loader_model.simulation.controllers import (
    CONTROLLER_PERIOD_S,
    check_controller,
    hold_command_controller,
)
from loader_model.simulation.simulator import SimulationError, exogenous_table
from loader_model.simulation.travel import RoadInput

__all__ = ["reference_simulation"]


def _period_integrator(
    period_s: float, npar: int, rtol: float, atol: float, layout: PlantLayout = SKID_STEER
) -> ca.Function:
    plant = plant_function(layout)
    nw = len(layout.exogenous_names)
    x = ca.SX.sym("x", len(layout.state_names))
    t = ca.SX.sym("t")
    p = ca.SX.sym("p", 1 + 2 * nw + npar)
    u, w0, w1, params = p[0], p[1 : 1 + nw], p[1 + nw : 1 + 2 * nw], p[1 + 2 * nw :]
    w = w0 + (w1 - w0) * (t / period_s)
    dae = {"x": x, "t": t, "p": p, "ode": plant(x, u, w, params)[0]}
    options = {"reltol": rtol, "abstol": atol, "max_num_steps": 100_000}
    return ca.integrator("reference_period", "cvodes", dae, 0.0, period_s, options)


def reference_simulation(
    road: RoadInput,
    params: Sequence[float] | np.ndarray,
    controller: ca.Function | None = None,
    *,
    settings: Sequence[float] = (),
    controller_state: Sequence[float] | None = None,
    duration_s: float | None = None,
    period_s: float = CONTROLLER_PERIOD_S,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    machine: MachineSource = SKID_STEER,
) -> dict[str, np.ndarray]:
    """Reference run (module notes); returns ``time``, ``x`` (N, n_x), ``y`` (N, n_y), ``u`` (N,).

    Rows at the controller's instants t_k = k h, k = 0 .. N − 1, as in
    :func:`~loader_model.simulation.simulator.simulate`, whose arguments ``controller``,
    ``settings`` and ``controller_state`` (z_0, default zeros) these are. The run starts at the
    static state of ``params`` with its holding command (the skid-steer: x (N, 15), y (N, 19)).

    Parameters
    ----------
    road : RoadInput
        Road table (:func:`~loader_model.simulation.simulator.course_input`).
    params : array_like
        The machine's plant parameter vector (:func:`~loader_model.plant.layout.plant_layout`).
    controller : casadi.Function, optional
        ``controller(z, y, settings) -> (z_next, u)`` on the machine's outputs; default: the
        pump holds the static command.
    settings, controller_state : sequence of float
        The controller's settings vector and its start z_0 (default zeros).
    duration_s : float, optional
        Simulated time (default: the road table's).
    period_s : float
        The controller's period, s.
    rtol, atol : float
        CVODES tolerances.
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer).

    Raises
    ------
    ValueError
        If ``params`` does not have the machine's number of parameters.
    SimulationError
        If CVODES fails in a period (naming its start time and the state there).
    """
    layout = resolve_layout(machine)
    params = np.asarray(params, dtype=float).ravel()
    if params.size != len(layout.parameter_names):
        raise ValueError(
            f"params must have the {len(layout.parameter_names)} plant parameters of machine "
            f"{layout.name!r}; got {params.size}"
        )
    x, u_previous = static_state(params, layout)
    if controller is None:
        controller, settings = hold_command_controller(layout), (u_previous,)
    controller = check_controller(controller, layout)
    plant = plant_function(layout)
    z = (
        np.zeros(controller.size1_in(0))
        if controller_state is None
        else np.asarray(controller_state, dtype=float).ravel()
    )
    settings_vector = np.asarray(settings, dtype=float).ravel()
    total_s = road.duration_s if duration_s is None else float(duration_s)
    count = int(np.floor(total_s / period_s + 1e-9))
    time_s = np.arange(count + 1) * period_s
    exogenous = exogenous_table(road, time_s)
    integrator = _period_integrator(period_s, params.size, rtol, atol, layout)
    states = np.empty((count, len(layout.state_names)))
    outputs = np.empty((count, len(layout.output_names)))
    commands = np.empty(count)
    for k in range(count):
        _, y = plant(x, u_previous, exogenous[k], params)
        z_next, u = controller(z, y, settings_vector)
        u_value = float(u)
        states[k], outputs[k], commands[k] = x, np.asarray(y).ravel(), u_value
        parameters = np.concatenate([[u_value], exogenous[k], exogenous[k + 1], params])
        try:
            x = np.asarray(integrator(x0=x, p=parameters)["xf"]).ravel()
        except RuntimeError as error:
            named = ", ".join(f"{n}={v:.6g}" for n, v in zip(layout.state_names, x, strict=True))
            raise SimulationError(
                f"CVODES failed in the period starting at t = {k * period_s:.4f} s "
                f"({error}); state: {named}"
            ) from None
        z, u_previous = np.asarray(z_next).ravel(), u_value
    return {"time": time_s[:count], "x": states, "y": outputs, "u": commands}
