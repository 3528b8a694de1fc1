r"""The simulator's own trajectory of a command table, and its linearisation period by period.

:func:`rollout` runs the closed-loop period of the simulator
(:func:`~loader_model.simulation.stepper.compile_period` with the held-command controller,
:data:`BOUND_SUBSTEPS` ROS2 steps per 1 ms period, the road table's samples at the periods'
ends) with u_k = u_{⌊k/M⌋}: the same compiled arithmetic :func:`~loader_model.bound.replay.
replay` runs (the simulator with that many substeps), so the bound's trajectory is the
simulator's. The count is fixed, not chosen by the error estimate as the simulator's default
(:mod:`~loader_model.simulation.adaptive`): a change of count moves the trajectory by about the
step's error, a jump in the cost that the optimiser's finite differences and line search would
see (measured on the 0.6 s gradient test: with the chosen counts the central differences of
a_total² parted from the model's gradient by 0.70 of its largest entry, 2.2e-2 with four
fixed). :func:`linearise` evaluates, along it, one Function of the same period
(:func:`linearised_period`) that gives, with the step,

.. math:: \delta x_{k+1} = A_k \delta x_k + B_k \delta u_k, \qquad \delta y_k = C_k \delta x_k

(y_k, the outputs at the period's start, do not depend on u_k), mapped over all periods on
two threads. C_k is exact; A_k and B_k are the sensitivities of the *flow* over the period:
the variational equation integrated by the simulator's own ROS2 substeps with their Jacobians
(:func:`~loader_model.simulation.stepper.ros2_period`), not the derivative of the discrete step.
The two agree where the plant is smooth (the gradient test: within 2.2e-2 of the largest entry,
cosine 0.99986), but where a 0.25 ms substep straddles the check valve's 10 kPa opening band
the discrete step also differentiates its frozen Jacobian and second stage, and its derivative
had eigenvalues up to 2.6e4 in one period (measured along the paper course at 9 km/h with the
pump held; finite differences of the step confirm it, with steps up to the band's width). Its
product grew by about 1e12 at each 40 mm board, so over 12 s single shooting overflowed; the
flow's sensitivities keep every eigenvalue below 1.45 there and their product bounded (a test).
The cost, the constraints and the line search stay on the simulated trajectory, so the
optimum is still the simulator's; only the search direction uses the flow's derivative.
Compiled to C once per machine, the period evaluates 12 000 periods in 0.6 s; CasADi's
virtual machine takes 3.2 s (development machine), so a single linearisation does not repay
the compilation (about 12 s) and :func:`linearise` compiles only when asked to.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import casadi as ca
import numpy as np

from loader_model.bound.problem import PATH_SIGNALS, BoundProblem, pump_states
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.plant import plant_function
from loader_model.simulation import refinement
from loader_model.simulation.compiled import CompilationError, cached_function, compiled_function
from loader_model.simulation.controllers import CONTROLLER_PERIOD_S, hold_command_controller
from loader_model.simulation.result import seat_signal_names
from loader_model.simulation.stepper import compile_period, ros2_period

__all__ = [
    "DivergedRollout",
    "Linearisation",
    "Trajectory",
    "linearise",
    "linearised_period",
    "rollout",
]

_CHUNK = 500
#: ROS2 substeps per period of the bound's rollout, fixed (module notes); the replay runs the
#: simulator with the same count.
BOUND_SUBSTEPS = 4


class DivergedRollout(ValueError):
    """The simulated trajectory of a command table left the finite numbers."""


@dataclass(frozen=True)
class Trajectory:
    """One simulated run of a command table.

    Attributes
    ----------
    command : numpy.ndarray
        (N,) u_j in m³/rev.
    states : numpy.ndarray
        (K_s + 1, nx) x_k.
    outputs : numpy.ndarray
        (K_s + 1, ny) y_k (the last at the end state).
    layout : PlantLayout
        The machine: the names of the states and outputs.
    """

    command: np.ndarray
    states: np.ndarray
    outputs: np.ndarray
    layout: PlantLayout

    def seat(self) -> np.ndarray:
        """(K_s, axes) seat samples minus their first (static) value, as the report reads them."""
        names = self.layout.output_names
        rows = [names.index(s) for s in seat_signal_names().values()]
        values = self.outputs[:-1, rows]
        return values - values[0]

    def path(self) -> np.ndarray:
        """(K_s, len(PATH_SIGNALS) + 1) the bounded outputs and V̇_p at every period."""
        rows = [self.layout.output_names.index(s) for s in PATH_SIGNALS]
        rate = self.states[:-1, self.layout.index(pump_states(self.layout)[1])]
        return np.column_stack([self.outputs[:-1, rows], rate])


@cache
def _period(layout: PlantLayout) -> ca.Function:
    controller = hold_command_controller(layout)
    return compile_period(controller, substeps=BOUND_SUBSTEPS, layout=layout)[0]


@cache
def _rolled(layout: PlantLayout, chunk: int) -> ca.Function:
    return _period(layout).mapaccum("bound_roll", chunk)


@cache
def linearised_period(layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``lin(x, u, w0, w1, params) -> (x_next, y, A, B, C)`` of the simulator's period (notes)
    for the machine ``layout``, every output dense (:func:`linearise` reads them as arrays)."""
    plant = plant_function(layout)
    nx, nw = len(layout.state_names), plant.size1_in(2)
    x, u = ca.SX.sym("x", nx), ca.SX.sym("u")
    w0, w1 = ca.SX.sym("w0", nw), ca.SX.sym("w1", nw)
    params = ca.SX.sym("params", plant.size1_in(3))
    y = plant(x, u, w0, params)[1]
    x_next, a, b, _ = ros2_period(
        plant, x, u, w0, w1, params, CONTROLLER_PERIOD_S, BOUND_SUBSTEPS, sensitivities=True
    )
    return ca.Function(
        "bound_linearised_period",
        [x, u, w0, w1, params],
        [ca.densify(e) for e in (x_next, y, a, b, ca.jacobian(y, x))],
        ["x", "u", "w0", "w1", "params"],
        ["x_next", "y", "A", "B", "C"],
    )


#: The mapped period of :func:`linearise` per machine: "compiled" once loaded or compiled;
#: "interpreted" while the cache does not hold it; "compile failed" when compiling was tried
#: and failed.
_MAPPED: dict[PlantLayout, dict[str, ca.Function | None]] = {}


def _mapped_linearised_period(layout: PlantLayout, compile_missing: bool) -> ca.Function:
    """:func:`linearised_period` mapped over chunks on two threads: compiled to C (8 times
    faster than CasADi's virtual machine) when the cache holds the library or
    ``compile_missing``, else interpreted (also when no C compiler works)."""
    mapped = _MAPPED.setdefault(layout, {})
    if "compiled" not in mapped:
        may_compile = compile_missing and "compile failed" not in mapped
        if may_compile or "interpreted" not in mapped:
            function = linearised_period(layout)
            try:
                compiled = (compiled_function if may_compile else cached_function)(function)
            except CompilationError:
                compiled, mapped["compile failed"] = None, None
            if compiled is not None:
                mapped["compiled"] = compiled.map(_CHUNK, "thread", 2)
            elif "interpreted" not in mapped:
                mapped["interpreted"] = function.map(_CHUNK, "thread", 2)
    return mapped["compiled"] if "compiled" in mapped else mapped["interpreted"]


def rollout(problem: BoundProblem, command: np.ndarray) -> Trajectory:
    """Simulate ``command`` (N values in m³/rev, each held M periods) from the equilibrium.

    The chunks run through the mapped period's function buffer, as the simulator's do (NumPy
    memory in and out, no conversion to CasADi matrices: the 11.55 s paper course at 18 km/h in
    0.12 s against 0.32-0.44 s with the converted call, the same trajectory to the last bit;
    development machine)."""
    command = np.asarray(command, dtype=float).ravel()
    if command.size != problem.intervals:
        raise ValueError(f"command must have {problem.intervals} values; got {command.size}")
    count, plant, layout = problem.periods, problem.plant, problem.layout
    exo = problem.exogenous
    u_k = np.repeat(command, problem.hold_periods)
    nx, ny, nw = len(layout.state_names), len(layout.output_names), exo.shape[1]
    states, outputs = np.empty((count + 1, nx)), np.empty((count + 1, ny))
    # column-major CasADi matrices read as C-order (chunk, n) arrays
    carry = np.concatenate([plant.x0, [plant.u0]])
    w0, w1 = np.empty((_CHUNK, nw)), np.empty((_CHUNK, nw))
    params = np.ascontiguousarray(np.tile(plant.params[None, :], (_CHUNK, 1)))
    settings, zeros = np.empty(_CHUNK), np.zeros((_CHUNK, ny))
    block, y_block, u_block = np.empty((_CHUNK, nx + 1)), np.empty((_CHUNK, ny)), np.empty(_CHUNK)
    error_block = np.empty(_CHUNK)
    buffer, evaluate = _rolled(layout, _CHUNK).buffer()
    for index, array in enumerate((carry, w0, w1, params, settings, zeros, zeros)):
        buffer.set_arg(index, memoryview(array))
    for index, array in enumerate((block, y_block, u_block, error_block)):
        buffer.set_res(index, memoryview(array))
    start = 0
    while start < count:
        size = min(_CHUNK, count - start)
        rows = np.arange(start, start + _CHUNK).clip(max=count - 1)
        w0[:], w1[:], settings[:] = exo[rows], exo[rows + 1], u_k[rows]
        evaluate()
        failed = np.flatnonzero(error_block[:size] > refinement.STEP_ERROR_LIMIT)
        if failed.size:  # as the simulator: the failed period integrated again finer
            size, index = int(failed[0]) + 1, start + int(failed[0])
            before = carry if failed[0] == 0 else block[failed[0] - 1]
            block[failed[0]] = refinement.refine_period(
                CONTROLLER_PERIOD_S, BOUND_SUBSTEPS, layout, before,
                block[failed[0]], exo[index], exo[index + 1], plant.params,
            )  # fmt: skip
        states[start] = carry[:nx]
        states[start + 1 : start + size] = block[: size - 1, :nx]
        outputs[start : start + size] = y_block[:size]
        carry[:] = block[size - 1]
        start += size
    states[count] = carry[:nx]
    outputs[count] = np.asarray(
        plant_function(layout)(carry[:nx], carry[nx], exo[count], plant.params)[1]
    ).ravel()
    if not np.all(np.isfinite(states)):
        raise DivergedRollout("command: the simulated trajectory left the finite numbers")
    return Trajectory(command, states, outputs, layout)


@dataclass(frozen=True)
class Linearisation:
    """A_k (K_s, nx, nx), B_k (K_s, nx) and C_k (K_s + 1, ny, nx) along a trajectory."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray


def linearise(
    problem: BoundProblem, trajectory: Trajectory, *, compile_missing: bool = False
) -> Linearisation:
    """The exact Jacobians of the simulator's period along ``trajectory`` (module notes).

    Evaluated in chunks of periods into NumPy memory through CasADi's function buffers (the
    conversion of the returned matrices took half the time of the compiled evaluation), by the
    compiled period if the machine's cache holds it or ``compile_missing`` (for callers that
    linearise many times, as the SQP does: its one-time compilation, about 12 s, is what
    CasADi's virtual machine takes for some 45 000 periods), else in the virtual machine."""
    layout = problem.layout
    count, nx, ny = problem.periods, len(layout.state_names), len(layout.output_names)
    buffer, evaluate = _mapped_linearised_period(layout, compile_missing).buffer()
    exo, params = problem.exogenous, problem.plant.params
    u_k = np.append(np.repeat(trajectory.command, problem.hold_periods), trajectory.command[-1])
    a = np.empty((count, nx, nx))
    b = np.empty((count, nx))
    c = np.empty((count + 1, ny, nx))
    tiled = np.ascontiguousarray(np.tile(params[None, :], (_CHUNK, 1)))
    # column-major CasADi outputs read as C-order (chunk, column, row) arrays
    x_next, y = np.empty((_CHUNK, nx)), np.empty((_CHUNK, ny))
    a_out, b_out, c_out = (
        np.empty((_CHUNK, nx, nx)),
        np.empty((_CHUNK, nx)),
        np.empty((_CHUNK, nx, ny)),
    )
    for index, out in enumerate((x_next, y, a_out, b_out, c_out)):
        buffer.set_res(index, memoryview(out))
    for start in range(0, count + 1, _CHUNK):
        size = min(_CHUNK, count + 1 - start)
        rows = np.arange(start, start + _CHUNK).clip(max=count)
        inputs = (
            np.ascontiguousarray(trajectory.states[rows]), np.ascontiguousarray(u_k[rows]),
            np.ascontiguousarray(exo[rows]), np.ascontiguousarray(exo[(rows + 1).clip(max=count)]),
            tiled,
        )  # fmt: skip
        for index, values in enumerate(inputs):
            buffer.set_arg(index, memoryview(values))
        evaluate()
        stop = min(size, count - start)
        if stop > 0:
            a[start : start + stop] = a_out[:stop].transpose(0, 2, 1)
            b[start : start + stop] = b_out[:stop]
        c[start : start + size] = c_out[:size].transpose(0, 2, 1)
    return Linearisation(a, b, c)
