r"""The closed-loop period with its ROS2 substeps chosen by their error estimate.

:func:`adaptive_period_function` is the period of :func:`~loader_model.simulation.stepper.
period_function` (sensors, controller at the period's start, the command held over it, the
exogenous input linear inside it) whose plant takes the fewest substeps of :data:`SUBSTEP_COUNTS`
whose error estimate, the largest |½ h (k_1 + k_2)| of the substeps in units of
:func:`~loader_model.simulation.stepper.step_error_scales` (the embedded linearly implicit Euler
step's distance from the ROS2 step), stays within :data:`STEP_TOLERANCE`. The carry holds the
count to start the next period with: a period starts with the previous period's count, one
level lower when that period's estimate was below a quarter of the tolerance over
:data:`DECREASE_MARGIN` (the estimate scales as the substep squared: half the substeps, four
times the estimate; the margin keeps the count from alternating period by period), and a
period whose estimate passes the tolerance is integrated again from its start with twice the
substeps, up to the largest count. Where the plant is at rest a period takes one substep; a
board, a tyre's lift-off or a valve's switching take more, and so does the ringing of the seat
pad and the occupant after a board (their velocities set the estimate in most periods).

The substeps of one period share the Jacobian of the period's start, so W = I − γ (h/n) J is
factored once per period (ROS2 is second order for any W; the stepper's notes): a further
substep costs two right-hand sides and two triangular solves, about 45 % of a substep with its
own Jacobian and factorisation (the SX instruction counts: 2 900 of 6 425).

Compiled without Python per period: one SX Function of the plant's steps per count, selected by
CasADi's ``Function.conditional`` (only the chosen branch runs), the retries as a chain of
conditionals that either keep the attempt or integrate again. The controller stays at 1 kHz on
the outputs at the period's start, as in the fixed-substep period. Accuracy against CVODES at
rtol 1e-10 and the cost: the simulation guide.
"""

from __future__ import annotations

import functools

import casadi as ca
import numpy as np

from loader_model.control.sensors import quantise
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.plant import plant_function
from loader_model.simulation.stepper import ros2_period, step_error_scales

__all__ = [
    "DECREASE_MARGIN",
    "STEP_TOLERANCE",
    "SUBSTEP_COUNTS",
    "adaptive_period_function",
    "counted_steps",
]

#: The substep counts a period may take, cheapest first (2**level, level 0 .. 3).
SUBSTEP_COUNTS: tuple[int, ...] = (1, 2, 4, 8)
#: Largest accepted error estimate of a period's substeps, in units of the states' scales.
STEP_TOLERANCE = 0.1
#: A period starts one level lower when the previous estimate was below a quarter of the
#: tolerance divided by this margin (module notes).
DECREASE_MARGIN = 8.0


@functools.cache
def counted_steps(period_s: float, substeps: int, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``steps(x, u, w0, w1, params) -> (x_next, error)``: ``substeps`` ROS2 steps of the plant
    over ``period_s`` with u held and the exogenous input linear from w0 to w1, all with the
    Jacobian of the period's start and so one factorisation of W (module notes), and their
    largest error estimate (SX)."""
    plant = plant_function(layout)
    nx, n_w = len(layout.state_names), len(layout.exogenous_names)
    x = ca.SX.sym("x", nx)
    u = ca.SX.sym("u")
    w0, w1 = ca.SX.sym("w0", n_w), ca.SX.sym("w1", n_w)
    params = ca.SX.sym("params", plant.size1_in(3))
    state, _, _, error = ros2_period(
        plant, x, u, w0, w1, params, period_s, substeps,
        error_scales=step_error_scales(layout), jacobian="period",
    )  # fmt: skip
    return ca.Function(
        f"ros2_{substeps}",
        [x, u, w0, w1, params],
        [state, error],
        ["x", "u", "w0", "w1", "params"],
        ["x_next", "error"],
    )


def _controller_step(controller: ca.Function, layout: PlantLayout) -> ca.Function:
    """``head(x, z, u_previous, w0, params, settings, y_error, y_step) -> (y, z_next, u)``."""
    plant = plant_function(layout)
    nx, nz = len(layout.state_names), controller.size1_in(0)
    n_y = len(layout.output_names)
    x, z, u_previous = ca.SX.sym("x", nx), ca.SX.sym("z", nz), ca.SX.sym("u_previous")
    w0 = ca.SX.sym("w0", len(layout.exogenous_names))
    params = ca.SX.sym("params", plant.size1_in(3))
    settings = ca.SX.sym("settings", controller.size1_in(2))
    y_error, y_step = ca.SX.sym("y_error", n_y), ca.SX.sym("y_step", n_y)
    _, y = plant(x, u_previous, w0, params)  # y does not depend on u (checked in the tests)
    z_next, u = controller(z, quantise(y + y_error, y_step), settings)
    return ca.Function(
        "controller_step",
        [x, z, u_previous, w0, params, settings, y_error, y_step],
        [y, z_next, u],
    )


def adaptive_period_function(
    controller: ca.Function,
    period_s: float = 1e-3,
    layout: PlantLayout = SKID_STEER,
    tolerance: float | None = None,
) -> ca.Function:
    """One controller period with error-controlled substeps (module notes), as an MX Function.

    Same inputs and outputs as :func:`~loader_model.simulation.stepper.period_function`, but
    the carry is (x, z, level, u_previous): ``level`` the index into :data:`SUBSTEP_COUNTS` the
    next period starts with (0 at the start of a run), and ``step_error`` the accepted
    substeps' estimate; ``tolerance`` default :data:`STEP_TOLERANCE`.
    """
    tolerance = STEP_TOLERANCE if tolerance is None else float(tolerance)
    nx, nz = len(layout.state_names), controller.size1_in(0)
    n_w, n_y = len(layout.exogenous_names), len(layout.output_names)
    plant = plant_function(layout)
    carry = ca.MX.sym("carry", nx + nz + 2)
    x, z = carry[:nx], carry[nx : nx + nz]
    level, u_previous = carry[nx + nz], carry[nx + nz + 1]
    w0, w1 = ca.MX.sym("w0", n_w), ca.MX.sym("w1", n_w)
    params = ca.MX.sym("params", plant.size1_in(3))
    settings = ca.MX.sym("settings", controller.size1_in(2))
    y_error, y_step = ca.MX.sym("y_error", n_y), ca.MX.sym("y_step", n_y)
    y, z_next, u = _controller_step(controller, layout)(
        x, z, u_previous, w0, params, settings, y_error, y_step
    )
    branches = [counted_steps(period_s, n, layout) for n in SUBSTEP_COUNTS]
    attempt = ca.Function.conditional("ros2_counted", branches[:-1], branches[-1])
    retry = _retry_function(attempt, nx, n_w, plant.size1_in(3))
    top = float(len(SUBSTEP_COUNTS) - 1)
    state, error = attempt(level, x, u, w0, w1, params)
    for _ in range(len(SUBSTEP_COUNTS) - 1):
        again = ca.logic_and(error > tolerance, level < top)
        level = level + again
        state, error = retry(again, level, x, u, w0, w1, params, state, error)
    lower = ca.logic_and(error * 4.0 * DECREASE_MARGIN < tolerance, level > 0.0)
    carry_next = ca.vertcat(state, z_next, level - lower, u)
    taken = 2.0**level  # SUBSTEP_COUNTS are the powers of two from 1
    return ca.Function(
        "adaptive_period",
        [carry, w0, w1, params, settings, y_error, y_step],
        [carry_next, y, u, error, taken],
        ["carry", "w0", "w1", "params", "settings", "y_error", "y_step"],
        ["carry_next", "y", "u", "step_error", "substeps"],
    )


def _retry_function(attempt: ca.Function, nx: int, n_w: int, n_p: int) -> ca.Function:
    """``retry(again, level, x, u, w0, w1, params, state, error) -> (state, error)``: the
    attempt kept (again = 0) or the period integrated again at ``level`` (again = 1)."""
    symbols = [
        ca.MX.sym("level"),
        ca.MX.sym("x", nx),
        ca.MX.sym("u"),
        ca.MX.sym("w0", n_w),
        ca.MX.sym("w1", n_w),
        ca.MX.sym("params", n_p),
        ca.MX.sym("state", nx),
        ca.MX.sym("error"),
    ]
    keep = ca.Function("keep_attempt", symbols, [symbols[6], symbols[7]])
    redo = ca.Function("redo_attempt", symbols, attempt(*symbols[:6]))
    return ca.Function.conditional("retry_attempt", [keep], redo)


def initial_level() -> np.ndarray:
    """The carry's level entry at the start of a run (one substep)."""
    return np.zeros(1)
