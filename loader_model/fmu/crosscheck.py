r"""Cross-check of the plant FMU against the project's own integration of the same plant Function.

The FMI Cross-Check convention: a recorded input, reference results, tolerances. The input is a
cosine bump of the road under the front axle,

.. math:: w_{Ay}(t) = \frac{h}{2}\left(1 - \cos\frac{2\pi (t - t_0)}{T}\right),
          \quad t_0 \le t \le t_0 + T,

with its rate ``wd_Ay``, sampled every ``dt``; the pump command is held at the static command
u0. The input is held over each sample interval (zero-order hold) in both simulations: FMPy gets
it as a staircase table, whose steps are input events where its Model Exchange loop stops and
restarts CVode (a plain table is only applied at communication points while CVode, not restarted,
steps across them: that blurred the input's timing and left errors near 1 % at any tolerance);
the reference integrates the plant with CasADi's cvodes interval by interval, on states scaled
by their nominal values, at a tight tolerance. Errors are reported relative to each signal's
largest excursion from its static value (stricter than relative to its peak, as f_Py, f_Sy and
p_A sit on a large static value).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import casadi as ca
import numpy as np

from loader_model.fmu.variables import ACTUATOR_COMMANDS, state_nominals
from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import (
    SKID_STEER,
    MachineSource,
    PlantLayout,
    resolve_layout,
)
from loader_model.plant.plant import EXOGENOUS_NAMES, plant_function

__all__ = ["CrossCheck", "bump_input", "cross_check", "reference_response"]

#: Signals compared (seat pad and chassis at S, pressures: the acceptance signals) and more.
COMPARED = ("f_Px", "f_Py", "f_Sx", "f_Sy", "p_A", "p_B", "phi", "yd_H", "thetad_1")


@dataclass(frozen=True)
class CrossCheck:
    """Result of :func:`cross_check`.

    Attributes
    ----------
    time : numpy.ndarray
        Output grid [s].
    reference, fmu : dict of str to numpy.ndarray
        Signals of the reference integration and of the FMU on ``time``.
    relative_error : dict of str to float
        max |fmu − reference| / max |reference − reference[0]| per signal (a constant signal,
        such as the baseline's command: relative to its value).
    """

    time: np.ndarray
    reference: dict[str, np.ndarray]
    fmu: dict[str, np.ndarray]
    relative_error: dict[str, float]


def bump_input(
    stop_time: float = 0.5,
    dt: float = 1e-3,
    height_m: float = 0.02,
    start_s: float = 0.05,
    duration_s: float = 0.1,
) -> tuple[np.ndarray, np.ndarray]:
    """Time grid and exogenous input (rows: time; columns: EXOGENOUS_NAMES) of one bump."""
    time = np.arange(round(stop_time / dt) + 1) * dt
    phase = np.clip((time - start_s) / duration_s, 0.0, 1.0)
    inside = (phase > 0.0) & (phase < 1.0)
    w = np.zeros((time.size, len(EXOGENOUS_NAMES)))
    w[:, EXOGENOUS_NAMES.index("w_Ay")] = 0.5 * height_m * (1 - np.cos(2 * np.pi * phase))
    rate = 0.5 * height_m * 2 * np.pi / duration_s * np.sin(2 * np.pi * phase)
    w[:, EXOGENOUS_NAMES.index("wd_Ay")] = np.where(inside, rate, 0.0)
    return time, w


def reference_response(
    params: np.ndarray,
    time: np.ndarray,
    w: np.ndarray,
    reltol: float = 1e-11,
    controller: str | None = None,
    settings: np.ndarray | None = None,
    layout: PlantLayout = SKID_STEER,
) -> dict[str, np.ndarray]:
    """Outputs of the plant Function integrated by cvodes with the input held over each step.

    With ``controller``, the loop is closed as the 1 kHz target closes it: at each sample t_k the
    controller Function reads the sensors of y(t_k) and its command is held until t_{k+1}; its
    states start at their fixed point (:func:`~loader_model.control.linear_controller.
    linear_controller`). The time grid must then be the controller's sample grid. The command is
    returned as ``V_p_ref`` (a valve circuit's ``x_s_ref``). ``layout`` (default the skid-steer)
    is the plant's machine; ``w`` then has the columns of its exogenous inputs (the same names
    as the skid-steer's), and the controller reads its sensors by name from that machine's
    outputs.
    """
    plant = plant_function(layout)
    x0, u0 = static_state(params, layout)
    nominal = state_nominals(x0, params, layout)
    z = ca.SX.sym("z", x0.size)
    held = ca.SX.sym("w", len(layout.exogenous_names))
    command = ca.SX.sym("u")
    xdot, _ = plant(nominal * z, command, held, params)
    steps = np.diff(time)
    if not np.allclose(steps, steps[0], rtol=1e-9):
        raise ValueError("reference_response needs a uniform time grid")
    step = ca.integrator(
        "reference_step",
        "cvodes",
        {"x": z, "p": ca.vertcat(command, held), "ode": xdot / nominal},
        0.0,
        float(steps[0]),
        {"abstol": reltol, "reltol": reltol, "max_num_steps": 100000},
    )
    law = None
    if controller is not None:
        from loader_model.control.controllers import controller_function
        from loader_model.control.linear_controller import linear_controller
        from loader_model.control.sensors import sensor_signals

        law = controller_function(controller)

        def sensors(y: np.ndarray) -> np.ndarray:
            return sensor_signals(y, layout)

        y0 = np.asarray(plant(x0, u0, w[0], params)[1]).ravel()
        z_c = linear_controller(controller, settings, sensors(y0)).operating_state
    states, commands = [x0 / nominal], []
    for k in range(time.size):
        u = u0
        if law is not None:
            y = np.asarray(plant(states[-1] * nominal, u0, w[k], params)[1]).ravel()
            z_next, u_k = law(z_c, sensors(y), settings)
            z_c, u = np.asarray(z_next).ravel(), float(u_k)
        commands.append(u)
        if k + 1 < time.size:
            xf = step(x0=states[-1], p=np.concatenate([[u], w[k]]))["xf"]
            states.append(np.asarray(xf).ravel())
    x = np.array(states) * nominal
    outputs = plant.map(time.size)(x.T, np.array(commands)[None, :], w.T, params)[1]
    y = np.asarray(outputs)
    named = {name: y[i] for i, name in enumerate(layout.output_names)}
    return named | {ACTUATOR_COMMANDS[layout.circuit][0]: np.array(commands)}


def cross_check(
    fmu_path: str | Path,
    params: np.ndarray,
    reltol: float = 1e-8,
    controller: str | None = None,
    settings: np.ndarray | None = None,
    machine: MachineSource = SKID_STEER,
) -> CrossCheck:
    """Simulate ``fmu_path`` with FMPy over :func:`bump_input` and compare with the reference.

    Parameters
    ----------
    fmu_path : str or pathlib.Path
        A plant FMU written by :func:`~loader_model.fmu.build.export_plant_fmu` for ``params``.
    params : numpy.ndarray
        The plant parameter vector the FMU was built with.
    reltol : float
        Relative tolerance of FMPy's CVode (its absolute tolerance is this times the nominals).
    controller, settings
        For a closed-loop FMU: the controller and its settings vector it was built with; the
        pump command ``V_p_ref`` (a valve circuit's ``x_s_ref``) is then compared too.
    machine : PlantLayout, str or pathlib.Path
        The FMU's machine: resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name
        or description file resolved once here (default the skid-steer).
    """
    import fmpy

    layout = resolve_layout(machine)
    time, w = bump_input()
    reference = reference_response(
        params, time, w, controller=controller, settings=settings, layout=layout
    )
    command = ACTUATOR_COMMANDS[layout.circuit][0]
    compared = COMPARED if controller is None else (*COMPARED, command)
    # a staircase table (each sample repeated at the next sample's time): FMPy then stops at
    # every sample as an input event and restarts CVode there, so the input is exactly held
    exogenous = layout.exogenous_names
    names = exogenous if controller is not None else (command, *exogenous)
    stairs = np.repeat(time, 2)[1:]  # t0, t1, t1, t2, t2, ..., tN, tN
    held = np.repeat(w, 2, axis=0)[:-1]  # w0, w0, w1, w1, w2, ..., wN
    signal = np.zeros(stairs.size, dtype=[("time", float)] + [(name, float) for name in names])
    signal["time"] = stairs
    if controller is None:
        signal[command] = static_state(params, layout)[1]
    for i, name in enumerate(exogenous):
        signal[name] = held[:, i]
    result = fmpy.simulate_fmu(
        str(fmu_path),
        stop_time=float(time[-1]),
        output_interval=float(time[1] - time[0]),
        relative_tolerance=reltol,
        input=signal,
        record_events=False,
        output=list(compared),
    )
    if result["time"].size != time.size or not np.allclose(result["time"], time, atol=1e-12):
        raise RuntimeError("FMPy returned a different output grid than the input's")
    fmu = {name: np.asarray(result[name]) for name in compared}
    errors = {}
    for name in compared:
        excursion = np.max(np.abs(reference[name] - reference[name][0]))
        scale = excursion if excursion > 0 else max(np.max(np.abs(reference[name])), 1e-300)
        errors[name] = float(np.max(np.abs(fmu[name] - reference[name])) / scale)
    return CrossCheck(time, {n: reference[n] for n in compared}, fmu, errors)
