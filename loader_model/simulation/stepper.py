r"""One controller period of the closed loop as one CasADi Function, compiled and rolled out.

Integration scheme: the two-stage L-stable Rosenbrock method ROS2 (Verwer, Spee, Blom,
Hundsdorfer, SIAM J. Sci. Comput. 20, 1999), with γ = 1 + 1/√2 and W = I − γ h J,

.. math::

    W k_1 = f(t_n, x_n), \qquad W k_2 = f(t_n + h, x_n + h k_1) - 2 k_1, \qquad
    x_{n+1} = x_n + \tfrac{3}{2} h k_1 + \tfrac{1}{2} h k_2 ,

second order for any W (so freezing J at the step's start and ignoring ∂f/∂t keeps the order),
linearly implicit: no Newton iteration, one Jacobian and one factorisation per (sub)step. It is
stable on this plant's stiff hydraulic and tyre modes (eigenvalues to about −4e3 rad/s at rest),
where explicit RK at 1 ms is not. J is the AD Jacobian of the plant; W is factored by
an LU without pivoting written out in SX over its structural non-zeros (W = I − γ h J is close
to the identity in the mechanical rows; a symbolic QR divides by columns that are numerically zero
at rest and gave NaN). The road input enters as the table samples at the period's ends and is
interpolated linearly inside it (:mod:`~loader_model.simulation.travel`).

With ``jacobian="period"`` the period's substeps share one W, formed from J at the period's
start: ROS2 as a Rosenbrock-W method, still second order (the order holds for any W), with one
Jacobian and one factorisation per period instead of one per substep (about 13 100 instead of
21 100 instructions for the skid-steer's period with four substeps). The default stays one
Jacobian per substep (the shipped results were made with it); the simulation guide compares
the two against CVODES.

Each substep also gives the embedded first-order solution x_n + h k_1 (linearly implicit Euler)
and so the error estimate ½ h (k_1 + k_2); the period reports its largest entry over the
substeps in units of :func:`step_error_scales` (per state, by its unit). Where a substep
straddles the tyres' stick-slip switch the linearly implicit step can fail: on an AMD EPYC the
rear tyre's anchor ξ_B jumped by 2 cm in one period of the passive run (9 km/h, full bucket,
4.705 s), which put 461 J into the energy balance and, in the baseline's run over the nominal
boards, 600 m/s² onto the seat; those periods read 150 to 11 600 where every other period of
the 16 paper-course runs stays below 3 (up to 18 right after a failed step). The simulator
integrates such a period again with finer substeps (:mod:`~loader_model.simulation.simulator`).

One period (:func:`period_function`): y_k = h(x_k, w_k), (z_{k+1}, u_k) = controller(z_k, ỹ_k)
with ỹ_k the sensors' reading of y_k (offset, noise, quantisation),
then ``substeps`` ROS2 steps over the period with u_k held. The carry (x, z, u) rolls over many
periods with ``mapaccum``; the period is compiled to C once per machine where a C compiler works
(:mod:`~loader_model.simulation.compiled`), else evaluated by CasADi's SX virtual machine.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import casadi as ca
import numpy as np

from loader_model.control.sensors import quantise
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.plant import plant_function
from loader_model.simulation.compiled import CompilationError, compiled_function
from loader_model.simulation.result import column_unit

__all__ = [
    "ERROR_SCALE_BY_UNIT",
    "JACOBIAN_CHOICES",
    "compile_period",
    "lu_solver",
    "period_function",
    "plant_steps",
    "rolled_period",
    "ros2_period",
    "step_error_scales",
]

_GAMMA = 1.0 + 1.0 / math.sqrt(2.0)
#: Where W = I − γ h J takes its Jacobian (module notes): ``"substep"`` at each substep's start
#: (ROS2, the default), ``"period"`` once at the period's start for all its substeps (ROS2 as a
#: Rosenbrock-W method).
JACOBIAN_CHOICES = ("substep", "period")

#: Scale of one substep's error estimate per state unit (module notes): a tenth of a millimetre
#: or milliradian, a millimetre per second, a bar, a tenth of a cm³. Units not listed: 1e-3.
ERROR_SCALE_BY_UNIT: dict[str, float] = {
    "m": 1e-4,
    "rad": 1e-4,
    "m/s": 1e-3,
    "rad/s": 1e-3,
    "Pa": 1e5,
    "m^3": 1e-7,
    "m^3/rev": 1e-7,
    "m^3/(rev*s)": 1e-5,
}


def step_error_scales(layout: PlantLayout = SKID_STEER) -> np.ndarray:
    """The scale of each state's substep error estimate, by its unit (:data:`ERROR_SCALE_BY_UNIT`)."""
    names = layout.state_names
    return np.array([ERROR_SCALE_BY_UNIT.get(column_unit(name), 1e-3) for name in names])


def lu_solver(matrix: ca.SX) -> Callable[[ca.SX], ca.SX]:
    """LU factorisation without pivoting of a square SX ``matrix``, over its structural non-zeros.

    Returns a function that solves ``matrix @ v = b`` for an SX column ``b``. Symbolic zeros are
    skipped, so the expression grows with the fill-in of the sparsity pattern, not with n³.
    """
    n = matrix.shape[0]
    dense = ca.densify(matrix)
    a = [[dense[i, j] for j in range(n)] for i in range(n)]
    for k in range(n):
        for i in range(k + 1, n):
            if a[i][k].is_zero():
                continue
            factor = a[i][k] / a[k][k]
            a[i][k] = factor
            for j in range(k + 1, n):
                if not a[k][j].is_zero():
                    a[i][j] = a[i][j] - factor * a[k][j]

    def solve(b: ca.SX) -> ca.SX:
        v = [b[i] for i in range(n)]
        for i in range(n):
            for j in range(i):
                if not a[i][j].is_zero():
                    v[i] = v[i] - a[i][j] * v[j]
        for i in reversed(range(n)):
            for j in range(i + 1, n):
                if not a[i][j].is_zero():
                    v[i] = v[i] - a[i][j] * v[j]
            v[i] = v[i] / a[i][i]
        return ca.vertcat(*v)

    return solve


def period_function(
    controller: ca.Function,
    period_s: float = 1e-3,
    substeps: int = 1,
    layout: PlantLayout = SKID_STEER,
    jacobian: str = "substep",
) -> ca.Function:
    """One controller period of the closed loop (module notes) as an SX Function.

    Parameters
    ----------
    controller : casadi.Function
        ``controller(z, y, settings) -> (z_next, u)``
        (:func:`~loader_model.simulation.controllers.check_controller`).
    period_s : float
        Controller period h in s.
    substeps : int
        ROS2 steps per period.
    layout : PlantLayout
        The machine and its lift circuit.
    jacobian : str
        :data:`JACOBIAN_CHOICES`: one Jacobian per substep or one per period (module notes).

    Returns
    -------
    casadi.Function
        ``period(carry, w0, w1, params, settings, y_error, y_step) -> (carry_next, y, u,
        step_error)`` with carry = (x, z, u_previous), w0, w1 the exogenous input (road, road
        rate, disturbance; :data:`~loader_model.plant.plant.EXOGENOUS_NAMES`) at the period's
        start and end, y the plant's outputs at its start, u the command held over it and
        step_error the largest substep error estimate in units of :func:`step_error_scales`.
        The controller reads ``quantise(y + y_error, y_step)``
        (:func:`~loader_model.control.sensors.quantise`): the sensors' offset and noise of this
        period and their converter steps (0: exact).
    """
    plant = plant_function(layout)
    nx, nz = len(layout.state_names), controller.size1_in(0)
    n_w, n_y = len(layout.exogenous_names), len(layout.output_names)
    carry = ca.SX.sym("carry", nx + nz + 1)
    x, z, u_previous = carry[:nx], carry[nx : nx + nz], carry[nx + nz]
    w0 = ca.SX.sym("w0", n_w)
    w1 = ca.SX.sym("w1", n_w)
    params = ca.SX.sym("params", plant.size1_in(3))
    settings = ca.SX.sym("settings", controller.size1_in(2))
    y_error = ca.SX.sym("y_error", n_y)
    y_step = ca.SX.sym("y_step", n_y)
    _, y = plant(x, u_previous, w0, params)  # y does not depend on u (checked in the tests)
    z_next, u = controller(z, quantise(y + y_error, y_step), settings)
    scales = step_error_scales(layout)
    state, _, _, error = ros2_period(
        plant, x, u, w0, w1, params, period_s, substeps, error_scales=scales, jacobian=jacobian
    )
    outputs = ca.cse(ca.vertcat(state, z_next, u, y, u, error))
    carry_next = outputs[: nx + nz + 1]
    y_out = outputs[nx + nz + 1 : nx + nz + 1 + n_y]
    return ca.Function(
        "closed_loop_period",
        [carry, w0, w1, params, settings, y_error, y_step],
        [carry_next, y_out, outputs[-2], outputs[-1]],
        ["carry", "w0", "w1", "params", "settings", "y_error", "y_step"],
        ["carry_next", "y", "u", "step_error"],
    )


def ros2_period(
    plant: ca.Function,
    x: ca.SX,
    u: ca.SX,
    w0: ca.SX,
    w1: ca.SX,
    params: ca.SX,
    period_s: float,
    substeps: int,
    sensitivities: bool = False,
    error_scales: np.ndarray | None = None,
    seed: ca.SX | None = None,
    jacobian: str = "substep",
) -> tuple[ca.SX, ca.SX | None, ca.SX | None, ca.SX | None]:
    r"""``substeps`` ROS2 steps of ``plant`` over one period with u held (module notes).

    Returns (x_next, A, B, error); with ``error_scales`` (one per state) error is the largest
    |½ h (k_1 + k_2)| / scale over the states and substeps (the embedded first-order solution's
    distance, module notes), else None. With ``sensitivities`` A and B are the period's
    sensitivities of the *flow*: the variational equation δẋ = J δx + J_u δu integrated by the
    same ROS2 steps with each substep's Jacobians (J, J_u at its start: the linear ROS2 update
    δ ← δ + h (3/2 κ₁ + 1/2 κ₂), W κ₁ = J δ + J_u δu, W κ₂ = J (δ + h κ₁) + J_u δu − 2 κ₁).
    They approximate ∂x(t + h)/∂(x, u) of the ODE to the method's order; the derivative of the
    discrete step itself also differentiates J and the second stage's f, which where a substep
    straddles a valve's opening band amplifies by up to 2.6e4 in one period (measured along the
    paper course; ``loader_model.bound.trajectory``'s notes). Else (None, None). With a
    ``seed`` ((nx + 1) × m directions in (δx, δu)) the same variational steps carry only those m
    directions: A is the flow's derivative along them (nx × m) and B is None. ``jacobian``
    (:data:`JACOBIAN_CHOICES`, module notes): ``"period"`` forms W once from J at the period's
    start for every substep; sensitivities need one Jacobian per substep.
    """
    if jacobian not in JACOBIAN_CHOICES:
        raise ValueError(f"jacobian = {jacobian!r}; allowed: {', '.join(JACOBIAN_CHOICES)}")
    if jacobian == "period" and (sensitivities or seed is not None):
        raise ValueError("jacobian = 'period' carries no sensitivities; allowed: 'substep'")
    nx = x.shape[0]
    step = period_s / substeps
    sensitivities = sensitivities or seed is not None
    xs, us, ws = ca.SX.sym("x", nx), ca.SX.sym("u"), ca.SX.sym("w", w0.shape[0])
    rate_s = plant(xs, us, ws, params)[0]
    outputs = [rate_s, ca.jacobian(rate_s, xs)]
    if sensitivities:
        outputs.append(ca.jacobian(rate_s, us))
    rate_and_jacobian = ca.Function("rate_and_jacobian", [xs, us, ws, params], outputs)
    state, error = x, None
    flow = ca.SX.eye(nx + 1)[:nx, :] if sensitivities else None  # (A | B), δ per unit (δx, δu)
    if seed is not None:
        flow = seed[:nx, :]
    for index in range(substeps):
        w_start = w0 + (w1 - w0) * (index / substeps)
        w_end = w0 + (w1 - w0) * ((index + 1) / substeps)
        if index == 0 or jacobian == "substep":
            rate, jac, *rest = rate_and_jacobian(state, u, w_start, params)
            solve = lu_solver(ca.SX.eye(nx) - _GAMMA * step * jac)
        else:  # Rosenbrock-W: the period's first W
            rate = plant(state, u, w_start, params)[0]
        if sensitivities:
            forcing = (
                rest[0] @ seed[nx, :]
                if seed is not None
                else ca.horzcat(ca.SX.zeros(nx, nx), rest[0])
            )
            k1 = ca.horzcat(*(solve(c) for c in ca.horzsplit(jac @ flow + forcing)))
            second = jac @ (flow + step * k1) + forcing - 2.0 * k1
            k2 = ca.horzcat(*(solve(c) for c in ca.horzsplit(second)))
            flow = flow + 1.5 * step * k1 + 0.5 * step * k2
        k1 = solve(rate)
        k2 = solve(plant(state + step * k1, u, w_end, params)[0] - 2.0 * k1)
        if error_scales is not None:
            estimate = ca.mmax(ca.fabs(0.5 * step * (k1 + k2)) / ca.DM(error_scales))
            error = estimate if error is None else ca.fmax(error, estimate)
        state = state + 1.5 * step * k1 + 0.5 * step * k2
    if not sensitivities:
        return state, None, None, error
    if seed is not None:
        return state, flow, None, error
    return state, flow[:, :nx], flow[:, nx], error


@functools.cache
def plant_steps(period_s: float, substeps: int, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """``steps(x, u, w0, w1, params) -> x_next``: ``substeps`` ROS2 steps of the plant over
    ``period_s`` with u held and the exogenous input linear from w0 to w1, without a controller
    (:func:`ros2_period`), in CasADi's virtual machine: the simulator's refinement of a failed
    period (built in about 0.3 s, one evaluation 0.3 ms)."""
    plant = plant_function(layout)
    x = ca.SX.sym("x", len(layout.state_names))
    u = ca.SX.sym("u")
    w0, w1 = (
        ca.SX.sym("w0", len(layout.exogenous_names)),
        ca.SX.sym("w1", len(layout.exogenous_names)),
    )
    params = ca.SX.sym("params", plant.size1_in(3))
    x_next = ros2_period(plant, x, u, w0, w1, params, period_s, substeps)[0]
    return ca.Function(
        "plant_steps",
        [x, u, w0, w1, params],
        [x_next],
        ["x", "u", "w0", "w1", "params"],
        ["x_next"],
    )


_COMPILED: dict[tuple[str, float, int | None, bool, PlantLayout, str], tuple[ca.Function, str]] = {}


def compile_period(
    controller: ca.Function,
    period_s: float = 1e-3,
    substeps: int | None = 1,
    jit: bool = True,
    layout: PlantLayout = SKID_STEER,
    jacobian: str = "substep",
) -> tuple[ca.Function, str]:
    """The period Function, compiled to C if ``jit`` and a C compiler works; cached per process
    and, compiled, per machine (:mod:`~loader_model.simulation.compiled`). ``substeps`` None:
    the substeps chosen by their error estimate
    (:func:`~loader_model.simulation.adaptive.adaptive_period_function`, one Jacobian per
    substep); ``jacobian``: :data:`JACOBIAN_CHOICES` (:func:`period_function`).

    Returns
    -------
    (casadi.Function, str)
        The Function and its backend, ``"jit"`` (compiled C) or ``"sx"`` (the fallback when
        compiling fails).
    """
    if jacobian not in JACOBIAN_CHOICES or (substeps is None and jacobian != "substep"):
        allowed = "'substep'" if substeps is None else ", ".join(JACOBIAN_CHOICES)
        raise ValueError(f"jacobian = {jacobian!r} with substeps = {substeps}; allowed: {allowed}")
    key = (controller.serialize(), float(period_s), substeps, bool(jit), layout, jacobian)
    if key not in _COMPILED:
        if substeps is None:  # error-controlled substeps
            from loader_model.simulation.adaptive import adaptive_period_function

            period = adaptive_period_function(controller, period_s, layout)
        else:
            period = period_function(controller, period_s, int(substeps), layout, jacobian)
        compiled, backend = period, "sx"
        if jit:
            try:
                compiled, backend = compiled_function(period), "jit"
            except CompilationError:  # no working C compiler: interpret the SX graph
                compiled, backend = period, "sx"
        _COMPILED[key] = (compiled, backend)
    return _COMPILED[key]


_ROLLED: dict[tuple[int, int], tuple[ca.Function, ca.Function]] = {}


def rolled_period(period: ca.Function, chunk: int) -> ca.Function:
    """``period.mapaccum`` over ``chunk`` periods with params, settings and the sensors' steps
    given once (MX wrapper that repeats them), built once per period Function and chunk size."""
    key = (id(period), chunk)
    if key not in _ROLLED or _ROLLED[key][0] is not period:  # an id is reused after its object
        mapped = period.mapaccum("roll_mapped", chunk)
        carry = ca.MX.sym("carry", period.size1_in(0))
        w0 = ca.MX.sym("w0", period.size1_in(1), chunk)
        w1 = ca.MX.sym("w1", period.size1_in(2), chunk)
        params = ca.MX.sym("params", period.size1_in(3))
        settings = ca.MX.sym("settings", period.size1_in(4))
        y_error = ca.MX.sym("y_error", period.size1_in(5), chunk)
        y_step = ca.MX.sym("y_step", period.size1_in(6))
        outputs = mapped(
            carry,
            w0,
            w1,
            ca.repmat(params, 1, chunk),
            ca.repmat(settings, 1, chunk),
            y_error,
            ca.repmat(y_step, 1, chunk),
        )
        _ROLLED[key] = (
            period,
            ca.Function(
                "roll",
                [carry, w0, w1, params, settings, y_error, y_step],
                outputs,
                ["carry", "w0", "w1", "params", "settings", "y_error", "y_step"],
                period.name_out(),
            ),
        )
    return _ROLLED[key][1]
