"""The closed-loop simulator: the plant over a road input with a discrete controller at 1 kHz.

:func:`simulate` runs a :class:`~loader_model.simulation.scenario.Scenario` (plant, static
equilibrium, controller, its settings and start, resolved once; from a bare parameter vector and
controller arguments it builds one) from the plant's static equilibrium
(:func:`~loader_model.plant.equilibrium.static_state`), evaluates the controller every period h
(zero-order hold on its command) and integrates the plant over each period with the compiled
ROS2 scheme of :mod:`~loader_model.simulation.stepper`, rolled over chunks of periods by
``mapaccum``. A period whose substeps' error estimate flags a failed step (a linearly implicit
step across the tyres' stick-slip switch: :mod:`~loader_model.simulation.refinement`) has its
plant integrated again with finer substeps, its controller step kept, and the chunk resumes
after it; the result's metadata lists those periods (``refined_periods``). After each chunk it
checks the rows against the model's range of validity
(:mod:`~loader_model.simulation.validity`: tip-over pitch, boom angle beyond the end stops,
time in the air, seat acceleration) and stops at the first violation with
:class:`ModelValidityError`, which carries the time series up to it; then it checks that
everything is finite and raises :class:`SimulationError` naming the time and the state if not:
no NaN leaves the simulator.
Events (cavitation, tyre lift-off, end stops, pump saturation) are recorded in the result
(:mod:`~loader_model.simulation.events`). Accuracy against a CVODES reference at rtol 1e-10:
``tests/simulation/test_simulator.py``.
"""

from __future__ import annotations

import dataclasses
import itertools
import time
from collections.abc import Sequence

import casadi as ca
import numpy as np

from loader_model.control.sensors import SENSOR_NAMES, SensorModel, quantise
from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES
from loader_model.plant.scenario import PlantScenario
from loader_model.simulation import refinement, validity_check
from loader_model.simulation.adaptive import SUBSTEP_COUNTS
from loader_model.simulation.controllers import CONTROLLER_PERIOD_S
from loader_model.simulation.courses import Course
from loader_model.simulation.events import DEFAULT_AIRBORNE_MIN_S, find_events
from loader_model.simulation.period_inputs import disturbance_table, sensor_error_table
from loader_model.simulation.result import SimulationResult, machine_units
from loader_model.simulation.scenario import Scenario, as_plant, as_scenario
from loader_model.simulation.stepper import compile_period, rolled_period
from loader_model.simulation.tandem_cam import DEFAULT_ENVELOPE, check_envelope
from loader_model.simulation.travel import RoadInput
from loader_model.simulation.tyres import axle_cam, axle_tyres
from loader_model.simulation.validity import ValidityBounds, resolve_bounds
from loader_model.simulation.validity_check import ModelValidityError, SimulationError

__all__ = [
    "DEFAULT_CHUNK_PERIODS",
    "DEFAULT_SUBSTEPS",
    "ModelValidityError",
    "SimulationError",
    "course_input",
    "exogenous_table",
    "simulate",
]

#: Periods per ``mapaccum`` call (0.5 s): the finiteness check runs after each chunk; measured
#: fastest among 250-2000 on the development machine.
DEFAULT_CHUNK_PERIODS = 500
#: ROS2 steps per 1 ms period. On closed load-holding valves (baseline, passive) one step per
#: period parts from the CVODES reference at rtol 1e-10 (measured, empty bucket, 9 km/h paper
#: course, seat pad a_total: tandem-cam tyres −2.2 % with 1 substep, −1.6 % with 2, +0.24 % with
#: 4, 0.00 % with 8). ``substeps=None`` chooses them period by period by their error estimate
#: (:mod:`~loader_model.simulation.adaptive`): as accurate on the 18 runs of the simulation
#: guide, not measurably faster on this plant (the guide says why), so not the default.
DEFAULT_SUBSTEPS: int | None = 4
#: Outputs that are states of the same name and value; they appear once in the result.
_STATE_OUTPUTS = frozenset(OUTPUT_NAMES) & frozenset(STATE_NAMES)


def course_input(
    course: Course,
    params: np.ndarray | PlantScenario | Scenario,
    sample_rate_hz: float = 1000.0,
    envelope: str | None = None,
) -> RoadInput:
    """The road input table of ``course`` for the loader of ``params``.

    Every axle of the machine (front first, as described) at its distance behind the front
    axle, d_i = A_x − i_x from the parameters (two axles: the wheelbase A_x − B_x), each with
    its own static load, cam and delay d_i / v; and the horizontal input w_x = −c tan β with
    c_i = F_iy0 / k_ix (static tyre load over longitudinal stiffness), the first-order
    effective-plane force that :mod:`~loader_model.simulation.travel` recommends for this plant.
    ``params`` may be a parameter vector (its equilibrium is computed here) or a
    :class:`~loader_model.plant.scenario.PlantScenario` or
    :class:`~loader_model.simulation.scenario.Scenario` (its static tyre loads are used).

    ``envelope`` (:data:`~loader_model.simulation.tandem_cam.ENVELOPES`; default: the
    Scenario's, else ``"tandem-cam"``): ``"rigid"`` for a rigid disc per axle of its tyres' free
    radius R_i, ``"tandem-cam"`` for a tandem elliptical cam per axle of its tyres' shape
    (a_e / R_i, b_e / R_i, c_e) whose spacing follows that axle's static deflection
    δ_i = F_iy0 / k_iy (:meth:`~loader_model.simulation.tandem_cam.TandemCam.from_deflection`):
    the patch, and so the road, differs between bucket loads. The tyres are the machine's
    parameter set's (:func:`~loader_model.simulation.tyres.axle_tyres`).
    """
    if envelope is None:
        envelope = params.envelope if isinstance(params, Scenario) else DEFAULT_ENVELOPE
    check_envelope(envelope)
    plant = as_plant(params)
    axles = plant.layout.machine.axles
    loads = tuple(plant.output(f"F_{axle}y") for axle in axles)
    gains = tuple(
        load / plant.parameter(f"k_{axle}x") for axle, load in zip(axles, loads, strict=True)
    )
    tyres = axle_tyres(plant)
    radii = tuple(tyre.radius_m for tyre in tyres)
    cams = None
    if envelope == "tandem-cam":
        cams = tuple(
            axle_cam(plant, axle, tyre, load)
            for axle, tyre, load in zip(axles, tyres, loads, strict=True)
        )
    front = plant.parameter(f"{axles[0]}_x")
    if len(axles) == 2:  # the paper's two axles: exactly the table of before (bit-identical)
        wheelbase = front - plant.parameter(f"{axles[1]}_x")
        return course.road_input(
            wheelbase,
            tyre_radius_m=radii,
            sample_rate_hz=sample_rate_hz,
            slope_to_x_m=gains,
            cams=cams,
        )
    offsets = [front - plant.parameter(f"{axle}_x") for axle in axles]
    if any(b < a for a, b in itertools.pairwise(offsets)) or offsets[-1] > 10.0:
        positions = ", ".join(f"{a}_x = {plant.parameter(f'{a}_x'):.6g} m" for a in axles)
        raise ValueError(
            f"machine {plant.layout.name!r}: its axles must be described front first, each at "
            f"most 10 m behind the front axle; got {positions}"
        )
    return course.road_input(
        axle_offsets_m=offsets,
        axle_names=axles,
        tyre_radius_m=radii,
        sample_rate_hz=sample_rate_hz,
        slope_to_x_m=gains,
        cams=cams,
    )


def exogenous_table(
    road: RoadInput, time_s: np.ndarray, disturbance: np.ndarray | None = None
) -> np.ndarray:
    """The plant's exogenous input w at ``time_s``: (N, 4n + 3), road and road rate of the n
    axles, disturbance (11 columns for two axles)."""
    forces = np.zeros((time_s.size, 3)) if disturbance is None else np.asarray(disturbance)
    if forces.shape != (time_s.size, 3):
        raise ValueError(
            f"disturbance must be ({time_s.size}, 3) (F_dx [N], F_dy [N], M_d [N*m]) at the "
            f"controller's instants; got shape {forces.shape}"
        )
    return np.column_stack([road.road(time_s), road.road_rate(time_s), forces])


def simulate(
    road: RoadInput,
    params: Sequence[float] | np.ndarray | PlantScenario | Scenario,
    controller: ca.Function | None = None,
    *,
    settings: Sequence[float] = (),
    controller_state: Sequence[float] | None = None,
    disturbance: np.ndarray | None = None,
    sensors: SensorModel | None = None,
    duration_s: float | None = None,
    period_s: float = CONTROLLER_PERIOD_S,
    substeps: int | None = DEFAULT_SUBSTEPS,
    jacobian: str = "substep",
    jit: bool = True,
    chunk_periods: int = DEFAULT_CHUNK_PERIODS,
    airborne_min_s: float = DEFAULT_AIRBORNE_MIN_S,
    validity: ValidityBounds | None = None,
) -> SimulationResult:
    """Simulate the closed loop over ``road`` from the static equilibrium (module notes).

    Parameters
    ----------
    road : RoadInput
        Road table (:func:`course_input`); interpolated at the controller's instants.
    params : array_like, PlantScenario or Scenario
        Plant parameters (:data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`;
        their equilibrium is computed here), a resolved plant
        (:class:`~loader_model.plant.scenario.PlantScenario`) or a whole closed loop
        (:class:`~loader_model.simulation.scenario.Scenario`, which holds the controller, its
        settings and its start: then ``controller``, ``settings`` and ``controller_state`` are
        not given). A Scenario whose ride control is off below a speed
        (:meth:`~loader_model.simulation.scenario.Scenario.at_speed`) drives ``road`` as the
        baseline when the road's speed is below it; the result's metadata says so
        (``ride_control``).
    controller : casadi.Function, optional
        ``controller(z, y, settings) -> (z_next, u)``; default: hold the static command
        (:func:`~loader_model.simulation.controllers.hold_command_controller` with u0 as its
        setting).
    settings : sequence of float
        The controller's settings vector.
    controller_state : sequence of float, optional
        Its initial state z_0 (default zeros).
    disturbance : numpy.ndarray, optional
        (N, 3) forces F_dx, F_dy [N] and moment M_d [N*m] at the controller's instants.
    sensors : SensorModel, optional
        Offset, noise (seeded) and quantisation of the controller's sensors
        (:class:`~loader_model.control.sensors.SensorModel`), applied in the compiled loop;
        their readings appear in the result as ``<signal>_measured``. Default: exact sensors.
    duration_s : float, optional
        Simulated time (default: the road table's); N = floor(duration / h) periods.
    period_s : float
        Controller period h in s.
    substeps : int, optional
        ROS2 steps per period (default :data:`DEFAULT_SUBSTEPS`); None: the fewest of
        :data:`~loader_model.simulation.adaptive.SUBSTEP_COUNTS` whose error estimate stays
        within :data:`~loader_model.simulation.adaptive.STEP_TOLERANCE`, period by period.
    jacobian : str
        ``"substep"`` (default): each ROS2 substep forms W from its own Jacobian; ``"period"``:
        the substeps of a period share the Jacobian of its start (ROS2 as a Rosenbrock-W method,
        :mod:`~loader_model.simulation.stepper`; fixed ``substeps`` only).
    jit : bool
        JIT-compile the period (falls back to the SX virtual machine without a C compiler).
    chunk_periods : int
        Periods per ``mapaccum`` call; the validity and finiteness checks run after each.
    airborne_min_s : float
        Shortest tyre lift-off recorded as an event, s.
    validity : ValidityBounds, optional
        The model's range of validity; default :func:`~loader_model.simulation.validity.
        validity_bounds` of ``params``.

    Returns
    -------
    SimulationResult
        Rows at t_k = k h, k = 0 .. N − 1.

    Raises
    ------
    ModelValidityError
        If the run leaves the range of validity: its ``violation`` and ``result`` (the rows up to
        and including the violating one).
    SimulationError
        If the run leaves the finite numbers (naming the time and the last finite state).
    """
    given = as_scenario(params, controller, settings, controller_state)
    scenario = given.at_speed(road.speed_m_s)  # the ride control off below its speed
    params, x0, u0 = scenario.params, scenario.x0, scenario.u0
    controller, settings_vector, z0 = (
        scenario.controller,
        scenario.settings,
        scenario.controller_state,
    )
    nz = z0.size
    total_s = road.duration_s if duration_s is None else float(duration_s)
    count = int(np.floor(total_s / period_s + 1e-9))
    if count < 2:
        raise ValueError(f"duration must hold at least 2 periods of {period_s:g} s; got {total_s}")
    time_s = np.arange(count + 1) * period_s
    exogenous = exogenous_table(
        road, time_s, None if disturbance is None else disturbance_table(disturbance, count)
    )
    layout = scenario.plant.layout
    state_names, output_names = layout.state_names, layout.output_names
    n_w = len(layout.exogenous_names)
    y_errors, y_steps = sensor_error_table(sensors, count, output_names)
    bounds = resolve_bounds(validity, params, layout=layout, tyre_radius_m=road.tyre_radii_m)
    monitor = validity_check.ValidityMonitor(bounds, period_s, layout)
    period, backend = compile_period(controller, period_s, substeps, jit, layout, jacobian)
    refine_from = max(SUBSTEP_COUNTS) if substeps is None else int(substeps)
    chunk = min(int(chunk_periods), count)
    roll = rolled_period(period, chunk)
    adaptive = substeps is None
    ncarry = period.size1_in(0)
    # Arrays in CasADi's column-major layout: a (chunk, n) C-order array is an (n, chunk) matrix.
    carry = np.concatenate([x0, z0, [0.0] if adaptive else [], [u0]])  # level 0: one substep
    w0, w1 = np.empty((chunk, n_w)), np.empty((chunk, n_w))
    e_block = np.zeros((chunk, len(output_names)))
    block = np.empty((chunk, ncarry))
    y_block, u_block = np.empty((chunk, len(output_names))), np.empty(chunk)
    error_block, count_block = np.empty(chunk), np.empty(chunk)
    buffer, trigger = roll.buffer()
    for index, array in enumerate((carry, w0, w1, params, settings_vector, e_block, y_steps)):
        buffer.set_arg(index, memoryview(array))
    for index, array in enumerate((block, y_block, u_block, error_block, count_block)):
        if index < roll.n_out():
            buffer.set_res(index, memoryview(array))
    carries = np.empty((count, ncarry))
    outputs = np.empty((count, len(output_names)))
    commands = np.empty(count)
    refined: list[int] = []
    taken: dict[int, int] = {}
    start_wall = time.perf_counter()
    start = 0
    while start < count:
        stop = min(start + chunk, count)
        rows = np.arange(start, start + chunk).clip(max=count - 1)
        w0[:] = exogenous[rows]
        w1[:] = exogenous[rows + 1]
        e_block[:] = y_errors[rows]
        trigger()
        size = stop - start
        failed = np.flatnonzero(error_block[:size] > refinement.STEP_ERROR_LIMIT)
        if failed.size:  # keep the rows up to the failed period, integrate it again finer
            size, index = int(failed[0]) + 1, start + int(failed[0])
            before = carry if failed[0] == 0 else block[failed[0] - 1]
            block[failed[0]] = refinement.refine_period(
                period_s, refine_from, layout, before, block[failed[0]], exogenous[index],
                exogenous[index + 1], params,
            )  # fmt: skip
            stop = start + size
            refined.append(index)
        carries[start] = carry
        carries[start + 1 : stop] = block[: size - 1]
        outputs[start:stop] = y_block[:size]
        counts, periods = np.unique(count_block[:size], return_counts=True) if adaptive else (
            [substeps], [size])  # fmt: skip
        for substep_count, number in zip(counts, periods, strict=True):
            taken[int(substep_count)] = taken.get(int(substep_count), 0) + int(number)
        commands[start:stop] = u_block[:size]
        violation = monitor.check(start, carries[start:stop], outputs[start:stop])
        if violation is not None:  # keep the rows up to it: the evidence
            count, carry = violation.index + 1, carries[violation.index].copy()
            break
        validity_check.raise_if_not_finite(
            block[:size].T, y_block[:size].T, start, period_s, state_names
        )
        carry[:] = block[size - 1]
        start = stop
    wall_s = time.perf_counter() - start_wall
    states, y_all, u_all = carries[:count].T, outputs[:count].T, commands[:count]
    columns_out: dict[str, np.ndarray] = dict(
        zip(state_names, states[: len(state_names)], strict=True)
    )
    for name, values in zip(output_names, y_all, strict=True):
        if name not in state_names:
            columns_out[name] = values
    columns_out[layout.input_names[0]] = u_all  # V_p_ref, or a valve's spool command x_s_ref
    if sensors is not None:
        for name in SENSOR_NAMES:
            column = output_names.index(name)
            reading = quantise(y_all[column] + y_errors[:count, column], y_steps[column])
            columns_out[f"{name}_measured"] = reading
    for index in range(nz):
        columns_out[f"z_{index}"] = states[len(state_names) + index]
    for name, values in zip(layout.exogenous_names, exogenous[:count].T, strict=True):
        columns_out[name] = values
    time_rows = time_s[:count]
    events = find_events(
        time_rows,
        columns_out,
        stroke_m=scenario.plant.parameter("stroke"),
        max_displacement=scenario.plant.command_limit(),
        airborne_min_s=airborne_min_s,
        axles=layout.machine.axles,
        max_rate=scenario.plant.rate_limit(),
        rate_signal=layout.state_names[layout.index("p_A") + 3],
    )
    metadata = {
        "controller": controller.name(),
        "backend": backend,
        "scheme": "ROS2" if jacobian == "substep" else "ROS2, one Jacobian a period (W)",
        "period_s": period_s,
        "substeps": "adaptive" if adaptive else int(substeps),
        "substep_periods": {str(n): taken[n] for n in sorted(taken)},
        "mean_substeps": sum(n * k for n, k in taken.items()) / max(sum(taken.values()), 1),
        "sensors": None if sensors is None else dataclasses.asdict(sensors),
        "wall_time_s": wall_s,
        "real_time_factor": count * period_s / wall_s,
        "refined_periods": [round(k * period_s, 6) for k in refined],
        "validity": dataclasses.asdict(monitor.bounds),
        "machine": layout.name,
    }
    if not layout.machine.is_default:  # the units of the columns its description names
        metadata["units"] = machine_units(layout.machine)
    if scenario is not given:
        metadata["ride_control"] = (
            f"{given.name} off: {road.speed_m_s * 3.6:g} km/h is below its "
            f"ride_control_min_speed of {given.min_speed_m_s * 3.6:g} km/h"
        )
    result = SimulationResult(
        time_rows, columns_out, carry[: len(state_names)].copy(), events, metadata
    )
    if violation is not None:
        raise ModelValidityError.stopping(violation, result)
    return result
