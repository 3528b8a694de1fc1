r"""a_total of a closed-loop run and its exact gradient with respect to the controller's gains.

The run is the simulator's (:func:`~loader_model.simulation.simulator.simulate`): the same
period, ROS2 substeps, sensors and refinement of failed periods, from the same static
equilibrium, so its a_total equals the simulator's. Along it the sensitivities
S_k = ∂(x_k, z_k, u_{k−1}) / ∂K of the carry to the chosen settings K (the skyhook's K_fb) are
carried by CasADi's automatic differentiation of the controller and by the variational equation
of the plant's flow integrated by the period's own ROS2 substeps
(:func:`~loader_model.simulation.stepper.ros2_period` with a seed: the same linear update the
optimal-control bound uses, which stays bounded where the discrete step's own derivative is
amplified by a substep that straddles a valve's opening band):

.. math::

    δu_k = \frac{∂u}{∂(x, z, K)} (S^x_k, S^z_k, I), \qquad
    S^x_{k+1} = Φ_k(S^x_k, δu_k), \qquad
    \frac{∂y_k}{∂K} = \frac{∂y}{∂x} S^x_k .

ISO 2631-1's weightings are linear and start at rest, so the weighted seat signal's derivative
is the weighting applied to ∂y/∂K, and with a_w,i² = mean(W_i(y_i)²) (Eq. 49),

.. math::

    \frac{∂ a_{total}}{∂K} = \frac{1}{a_{total}} \sum_i k_i^2\,
        \mathrm{mean}\big(W_i(y_i)\, W_i(∂y_i/∂K)\big) \quad (\text{Eq. } 50).

A period the simulator integrates again with finer substeps (its error estimate failed) keeps
its coarse sensitivity: the number of such periods is returned, and where there are many the
gradient is approximate. Where tyres lift off, the cost is not smooth in K; the gradient is
that of the trajectory at K (agreement with central differences is tested on courses without
lift-off). Measured on the paper course (40 mm boards, 9 km/h, full bucket, Table 3's gains, 20
lift-offs): the gradient (−0.0010, 0.0268, −0.0217, 0.0449) m/s² per unit gain against central
differences of the simulator with steps of 1e-2, 1e-3 and 1e-4 of each gain: k_y 0.0282, 0.0235,
0.0235; k_θ −0.0209, −0.0466, −0.0117; k_φ 0.0523, 0.0411, 0.0653; k_x −0.0002, 0.0116, 0.0111.
The differences disagree with one another by as much as with the gradient: a step of the gains
moves a lift-off's timing and the cost jumps, so there no derivative describes more than the
trajectory at hand.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from loader_model.control.sensors import quantise
from loader_model.plant.layout import CIRCUITS, PlantLayout
from loader_model.plant.plant import plant_function
from loader_model.simulation import refinement
from loader_model.simulation.compiled import CompilationError, compiled_function
from loader_model.simulation.stepper import rolled_period, ros2_period, step_error_scales

__all__ = ["FIXED_SUBSTEPS", "GainGradient", "gain_gradient", "sensitivity_period"]

#: ROS2 substeps per period when the simulator's default chooses them by their error estimate.
FIXED_SUBSTEPS = 4


@functools.cache
def sensitivity_period(
    controller: ca.Function,
    period_s: float,
    substeps: int,
    layout: PlantLayout,
    gains: tuple[int, ...],
) -> ca.Function:
    """The simulator's period with the carry's sensitivities to ``gains`` (indices into the
    settings vector) appended to the carry (module notes).

    Returns ``period(carry, w0, w1, params, settings, y_error, y_step) -> (carry_next, y, u,
    step_error)`` in the simulator's signature, where carry = (x, z, u_previous, vec(S)) and y
    = (y, vec(∂y/∂K)), so that it rolls and compiles as the simulator's does.
    """
    plant = plant_function(layout)
    nx, nz = len(layout.state_names), controller.size1_in(0)
    ny, nw = len(layout.output_names), len(layout.exogenous_names)
    ncarry, m = nx + nz + 1, len(gains)
    augmented = ca.SX.sym("carry", ncarry * (1 + m))
    x, z, u_previous = augmented[:nx], augmented[nx : nx + nz], augmented[nx + nz]
    sens = ca.reshape(augmented[ncarry:], ncarry, m)
    w0, w1 = ca.SX.sym("w0", nw), ca.SX.sym("w1", nw)
    params = ca.SX.sym("params", plant.size1_in(3))
    settings = ca.SX.sym("settings", controller.size1_in(2))
    y_error, y_step = ca.SX.sym("y_error", ny), ca.SX.sym("y_step", ny)
    _, y = plant(x, u_previous, w0, params)
    z_next, u = controller(z, quantise(y + y_error, y_step), settings)
    seed_settings = ca.SX.zeros(settings.shape[0], m)
    for column, index in enumerate(gains):
        seed_settings[index, column] = 1.0
    carry = augmented[:ncarry]
    dy = ca.jtimes(y, carry, sens)
    dzu = ca.jtimes(
        ca.vertcat(z_next, u), ca.vertcat(carry, settings), ca.vertcat(sens, seed_settings)
    )
    du = dzu[nz:, :]
    state, dstate, _, error = ros2_period(
        plant,
        x,
        u,
        w0,
        w1,
        params,
        period_s,
        substeps,
        error_scales=step_error_scales(layout),
        seed=ca.vertcat(sens[:nx, :], du),
    )
    carry_next = ca.vertcat(state, z_next, u, ca.vec(ca.vertcat(dstate, dzu)))
    outputs = ca.cse(ca.vertcat(carry_next, y, ca.vec(dy), u, error))
    size = carry_next.shape[0]
    return ca.Function(
        "closed_loop_period_gain_sensitivity",
        [augmented, w0, w1, params, settings, y_error, y_step],
        [outputs[:size], outputs[size : size + ny * (1 + m)], outputs[-2], outputs[-1]],
        ["carry", "w0", "w1", "params", "settings", "y_error", "y_step"],
        ["carry_next", "y", "u", "step_error"],
    )


@functools.cache
def _compiled(
    controller: ca.Function,
    period_s: float,
    substeps: int,
    layout: PlantLayout,
    gains: tuple[int, ...],
) -> ca.Function:
    period = sensitivity_period(controller, period_s, substeps, layout, gains)
    try:
        return compiled_function(period)
    except CompilationError:  # no working C compiler: CasADi's virtual layout
        return period


@dataclass(frozen=True)
class GainGradient:
    """a_total of one run and its gradient.

    Attributes
    ----------
    a_total : float
        ISO 2631-1 a_total at the seat [m/s²] (Eq. 50, the paper's k = 1, 1, 0.4).
    gradient : numpy.ndarray
        ∂a_total/∂K for each chosen setting [m/s² per unit of the setting].
    refined_periods : int
        Periods integrated again finer (their sensitivity is the coarse period's).
    time_s : numpy.ndarray
        The controller's instants.
    columns : dict of str to numpy.ndarray
        The command ``V_p_ref``, the displacement rate ``Vd_p`` (a valve circuit's ``x_s_ref``
        and ``xd_s``), the seat's signals and the
        exogenous inputs at those instants (what
        :func:`~loader_model.simulation.settling.limit_duty` and
        :func:`~loader_model.simulation.settling.settle_measure` read).
    """

    a_total: float
    gradient: np.ndarray
    refined_periods: int
    time_s: np.ndarray
    columns: dict[str, np.ndarray]


def gain_gradient(
    scenario: object,
    road: object,
    *,
    gains: tuple[int, ...] = (0, 1, 2, 3),
    sensors: object | None = None,
    duration_s: float | None = None,
    chunk_periods: int = 500,
    jit: bool = True,
) -> GainGradient:
    """a_total of the run of ``scenario`` over ``road`` and its gradient to the settings
    ``gains`` (default the skyhook's K_fb, Table 3; module notes).

    Parameters
    ----------
    scenario : Scenario
        The closed loop (:func:`~loader_model.simulation.scenario.ride_scenario`).
    road : RoadInput
        The road table (:func:`~loader_model.simulation.simulator.course_input`).
    gains : tuple of int
        Indices of the differentiated settings (:data:`~loader_model.control.settings.
        SETTINGS_NAMES`).
    sensors : SensorModel, optional
        The sensors' errors, as in :func:`~loader_model.simulation.simulator.simulate`.
    duration_s : float, optional
        Simulated time (default the road table's).
    chunk_periods : int
        Periods per compiled call.
    jit : bool
        Compile the period to C (cached per machine; without a working compiler, or with
        False, CasADi's virtual machine evaluates it).

    Raises
    ------
    SimulationError
        If the run leaves the finite numbers.
    """
    from loader_model.simulation.period_inputs import sensor_error_table
    from loader_model.simulation.result import seat_signal_names
    from loader_model.simulation.simulator import (
        CONTROLLER_PERIOD_S,
        DEFAULT_SUBSTEPS,
        exogenous_table,
    )
    from loader_model.simulation.validity_check import raise_if_not_finite

    off = scenario.at_speed(road.speed_m_s)  # type: ignore[attr-defined]
    if off is not scenario:  # the ride control is off at this speed: no gain acts
        return _without_ride_control(off, road, len(gains), sensors, duration_s)
    # fixed substeps, as the optimal-control bound's rollout: a change of the error-controlled
    # count would be a jump in the cost (the simulator's default is fixed too)
    period_s, substeps = CONTROLLER_PERIOD_S, DEFAULT_SUBSTEPS or FIXED_SUBSTEPS
    plant, controller = scenario.plant, scenario.controller
    layout = plant.layout
    nx, nz = len(layout.state_names), controller.size1_in(0)
    ny, ncarry, m = len(layout.output_names), nx + nz + 1, len(gains)
    total_s = road.duration_s if duration_s is None else float(duration_s)
    count = int(np.floor(total_s / period_s + 1e-9))
    time_s = np.arange(count + 1) * period_s
    exogenous = exogenous_table(road, time_s, None)
    y_errors, y_steps = sensor_error_table(sensors, count, layout.output_names)
    period = (
        _compiled(controller, period_s, substeps, layout, tuple(gains))
        if jit
        else sensitivity_period(controller, period_s, substeps, layout, tuple(gains))
    )
    chunk = min(int(chunk_periods), count)
    roll = rolled_period(period, chunk)
    carry = np.concatenate([scenario.x0, scenario.controller_state, [scenario.u0]])
    carry = np.concatenate([carry, np.zeros(ncarry * m)])
    outputs = np.empty((count, ny * (1 + m)))
    commands, rates = np.empty(count), np.empty(count)
    command_name, rate_name = layout.input_names[0], CIRCUITS[layout.circuit][1]
    rate_row = layout.state_names.index(rate_name)
    refined = 0
    start = 0
    while start < count:
        rows = np.arange(start, start + chunk).clip(max=count - 1)
        result = roll(
            carry,
            exogenous[rows].T,
            exogenous[rows + 1].T,
            scenario.params,
            scenario.settings,
            y_errors[rows].T,
            y_steps,
        )
        block, y_block, u_block, errors = (
            np.asarray(r, dtype=float) for r in (result[0], result[1], result[2], result[3])
        )
        size = min(chunk, count - start)
        failed = np.flatnonzero(errors.ravel()[:size] > refinement.STEP_ERROR_LIMIT)
        if failed.size:
            size, index = int(failed[0]) + 1, start + int(failed[0])
            before = carry if failed[0] == 0 else block[:, failed[0] - 1]
            fine = refinement.refine_period(
                period_s, substeps, layout, before[:ncarry], block[:ncarry, failed[0]],
                exogenous[index], exogenous[index + 1], scenario.params,
            )  # fmt: skip
            block[:ncarry, failed[0]] = fine
            refined += 1
        raise_if_not_finite(block[:, :size], y_block[:, :size], start, period_s, layout.state_names)
        outputs[start : start + size] = y_block[:, :size].T
        commands[start : start + size] = u_block.ravel()[:size]
        rates[start] = carry[rate_row]
        rates[start + 1 : start + size] = block[rate_row, : size - 1]
        carry = block[:, size - 1].copy()
        start += size
    a_total, gradient = _cost_and_gradient(outputs, ny, m, layout.output_names, seat_signal_names())
    columns = {name: outputs[:, i] for i, name in enumerate(layout.output_names)}
    columns |= {command_name: commands, rate_name: rates}
    columns |= dict(zip(layout.exogenous_names, exogenous[:count].T, strict=True))
    return GainGradient(a_total, gradient, refined, time_s[:count], columns)


def _without_ride_control(
    scenario: Any, road: Any, m: int, sensors: Any, duration_s: float | None
) -> GainGradient:
    """The run with the ride control off below its speed (:meth:`~loader_model.simulation.
    scenario.Scenario.at_speed`): the simulator's, with a zero gradient."""
    from loader_model.simulation.simulator import simulate

    run = simulate(road, scenario, sensors=sensors, duration_s=duration_s)
    layout = scenario.plant.layout
    kept = (*layout.output_names, layout.input_names[0], CIRCUITS[layout.circuit][1])
    columns = {name: run.columns[name] for name in (*kept, *layout.exogenous_names)}
    return GainGradient(run.seat_evaluation().total_m_s2, np.zeros(m), 0, run.time_s, columns)


def _cost_and_gradient(
    outputs: np.ndarray,
    ny: int,
    m: int,
    names: tuple[str, ...],
    seat: dict[str, str],
) -> tuple[float, np.ndarray]:
    from loader_model.iso2631 import PAPER_K_FACTORS, weight_acceleration, weighted_rms
    from loader_model.iso2631.evaluation import DEFAULT_AXIS_WEIGHTINGS

    total, gradient = 0.0, np.zeros(m)
    for axis, signal in seat.items():
        row = names.index(signal)
        weighting = DEFAULT_AXIS_WEIGHTINGS["z" if axis == "z" else axis]
        k = PAPER_K_FACTORS[axis]
        values = outputs[:, row]
        weighted = weight_acceleration(values - values[0], 1000.0, weighting)
        rms = weighted_rms(weighted)
        total += (k * rms) ** 2
        for j in range(m):
            derivative = outputs[:, ny * (1 + j) + row]
            weighted_derivative = weight_acceleration(derivative - derivative[0], 1000.0, weighting)
            gradient[j] += k**2 * float(np.mean(weighted * weighted_derivative))
    a_total = float(np.sqrt(total))
    return a_total, gradient / a_total
