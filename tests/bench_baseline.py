"""The benchmark's baseline simulator, written the way users usually write one (issue 12).

SymPy ``lambdify`` of the model's equations, ``numpy.linalg.solve`` of the mass
matrix per right-hand side, ``scipy.integrate.solve_ivp`` over each 1 ms controller period with
the same discrete controller between periods (zero-order hold), from the same static equilibrium,
over the same road table (linear inside each period, as in
:mod:`loader_model.simulation.reference`).

Where the equations come from (the same equations, none written a second time):

- Multibody part: the SymPy expressions of ``derive/`` (:func:`derive.mechanics.derive_mechanics`):
  the mass matrix M(p), the right-hand side Q_act F_act + Q_g + Q_d + Q_tyre − C with the tyre
  contact law of ``derive/contact.py`` (its intermediates F_y, F_x, σ evaluated in order before
  the outputs, as the generated code does), the anchor rates, the specific forces and tyre
  forces (outputs), and the static tyre loads that complete the parameter vector.
- Hydraulic part (cylinders, pump, valves, accumulator): the runtime has it only as CasADi
  (:mod:`loader_model.plant.components` composed by ``loader_model.plant.plant.hydraulic_drive``), with
  ``ca.if_else``/``ca.fmax`` etc. that SymPy symbols cannot go through. Its SX graph is translated
  mechanically into SymPy, one instruction at a time (:func:`sx_to_sympy`): the same operations
  in the same order, no equation retyped. Piecewise results and results the graph shares are
  named intermediates (the graph's own common subexpressions; without them SymPy folds nested
  Piecewise conditions for minutes and the lambdified code repeats the shared terms).

Both parts are lambdified with the parameter vector as an argument, as a user would to vary it,
with ``modules="numpy"`` (what users usually write; each Piecewise becomes a ``numpy.select`` of
scalars, about 8 µs) or ``"math"`` (scalar Python, ``a if c else b``). Measured on the development
machine over the first 3 s of the paper's course, about 20 right-hand sides per 1 ms period:

===========================================  ===============  ==========================
variant                                      wall per 1 s     per right-hand side
===========================================  ===============  ==========================
"numpy", LSODA (finite-difference Jacobian)  20-32 s          1.0-1.3 ms incl. solve_ivp
"math", LSODA (finite-difference Jacobian)   1.8 s            0.09 ms incl. solve_ivp
"math", LSODA with the lambdified Jacobian   2.9 s            (Jacobian 0.6 ms)
"math", Radau with the lambdified Jacobian   5.6 s
"math", BDF                                  fails at 0.13 s  (step size underflow)
===========================================  ===============  ==========================

The Jacobian (``jacobian=True``): forward differentiation in SymPy of the multibody right-hand
side through the contact law's intermediates, ∂p̈/∂x = M⁻¹ (∂f/∂x − ∂(M p̈)/∂x), and CasADi's SX
Jacobian of the hydraulics translated like the hydraulics; it equals CasADi's AD Jacobian of the
plant to round-off.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
import sympy as sp

#: States of the loader without the seated occupant: p, ṗ, the tyre anchors, p_A, p_B, V_p, V̇_p,
#: V_acc. The occupant's reaction on the chassis is neglected in the plant (plant/occupant.py), so
#: these 15 evolve the same with the occupant on or off.
LOADER_STATES = 15

__all__ = [
    "BaselineModel",
    "baseline_model",
    "baseline_simulation",
    "seat_agreement",
    "sx_to_sympy",
]

Array = np.ndarray


def _is_condition(value: Any) -> bool:
    """Whether ``value`` is a SymPy condition (a Symbol is also a Boolean, but an expression)."""
    return isinstance(value, sp.logic.boolalg.Boolean) and not isinstance(value, sp.Expr)


class _Translation:
    """SymPy operands of an SX translation; piecewise and shared results become named
    intermediates."""

    def __init__(self, prefix: str) -> None:
        self.prefix = prefix
        self.definitions: list[tuple[sp.Symbol, sp.Expr]] = []

    def name(self, expression: sp.Expr) -> sp.Symbol:
        """A new real symbol defined as ``expression`` (kept in order in ``definitions``)."""
        symbol = sp.Symbol(f"{self.prefix}{len(self.definitions)}", real=True)
        self.definitions.append((symbol, expression))
        return symbol

    def number(self, value: Any) -> sp.Expr:
        """An operand as a number (a comparison becomes a named 0/1)."""
        if _is_condition(value):
            return self.name(sp.Piecewise((1, value), (0, True)))
        return value

    @staticmethod
    def boolean(value: Any) -> Any:
        """An operand as a condition (a number is true where it is non-zero)."""
        return value if _is_condition(value) else sp.Ne(value, 0)


_UNARY: dict[int, Callable[[Any], Any]] = {
    ca.OP_NEG: lambda a: -a,
    ca.OP_SQ: lambda a: a**2,
    ca.OP_TWICE: lambda a: 2 * a,
    ca.OP_SQRT: sp.sqrt,
    ca.OP_EXP: sp.exp,
    ca.OP_LOG: sp.log,
    ca.OP_SIN: sp.sin,
    ca.OP_COS: sp.cos,
    ca.OP_TAN: sp.tan,
    ca.OP_TANH: sp.tanh,
    ca.OP_ATAN: sp.atan,
    ca.OP_FABS: sp.Abs,
    ca.OP_SIGN: sp.sign,
    ca.OP_INV: lambda a: 1 / a,
    ca.OP_ASSIGN: lambda a: a,
}
_BINARY: dict[int, Callable[[Any, Any], Any]] = {
    ca.OP_ADD: lambda a, b: a + b,
    ca.OP_SUB: lambda a, b: a - b,
    ca.OP_MUL: lambda a, b: a * b,
    ca.OP_DIV: lambda a, b: a / b,
    ca.OP_POW: lambda a, b: a**b,
    ca.OP_CONSTPOW: lambda a, b: a**b,
    ca.OP_FMIN: sp.Min,
    ca.OP_FMAX: sp.Max,
    ca.OP_ATAN2: sp.atan2,
}
_COMPARISONS: dict[int, Callable[[Any, Any], Any]] = {
    ca.OP_LE: sp.Le,
    ca.OP_LT: sp.Lt,
    ca.OP_EQ: sp.Eq,
    ca.OP_NE: sp.Ne,
}


def sx_to_sympy(
    function: ca.Function, inputs: Sequence[Sequence[sp.Symbol]], prefix: str = "_h"
) -> tuple[list[sp.Matrix], list[tuple[sp.Symbol, sp.Expr]]]:
    """Translate an SX Function into SymPy, instruction by instruction.

    Each piecewise result (CasADi's ``if_else_zero``, a comparison used as a number) becomes a
    named intermediate, so that no Piecewise sits inside another's condition (SymPy would fold
    them, which takes minutes on the plant's hydraulics); the intermediates are evaluated in
    order before the outputs, as the contact law's are in ``derive/``.

    Parameters
    ----------
    function : casadi.Function
        An SX Function with dense column-vector inputs and outputs.
    inputs : sequence of sequences of sympy.Symbol
        One symbol per entry of each input.
    prefix : str
        Name prefix of the intermediates.

    Returns
    -------
    outputs : list of sympy.Matrix
        Each output as a column of SymPy expressions in ``inputs`` and the intermediates.
    definitions : list of (sympy.Symbol, sympy.Expr)
        The intermediates in evaluation order.

    Raises
    ------
    NotImplementedError
        For an operation without a SymPy counterpart here.
    """
    ops = _Translation(prefix)
    work: dict[int, Any] = {}
    outputs = [[sp.S.Zero] * function.nnz_out(i) for i in range(function.n_out())]
    uses = _use_counts(function)
    for k in range(function.n_instructions()):
        op = function.instruction_id(k)
        args = function.instruction_input(k)
        res = function.instruction_output(k)
        if op == ca.OP_OUTPUT:
            outputs[res[0]][res[1]] = ops.number(work[args[0]])
            continue
        if op == ca.OP_CONST:
            value = float(function.instruction_constant(k))
            result = sp.Integer(int(value)) if value.is_integer() else sp.Float(value)
        elif op == ca.OP_INPUT:
            result = inputs[args[0]][args[1]]
        elif op in _UNARY:
            result = _UNARY[op](ops.number(work[args[0]]))
        elif op in _BINARY:
            result = _BINARY[op](ops.number(work[args[0]]), ops.number(work[args[1]]))
        elif op in _COMPARISONS:
            result = _COMPARISONS[op](ops.number(work[args[0]]), ops.number(work[args[1]]))
        elif op == ca.OP_NOT:
            result = sp.Not(ops.boolean(work[args[0]]))
        elif op == ca.OP_AND:
            result = sp.And(ops.boolean(work[args[0]]), ops.boolean(work[args[1]]))
        elif op == ca.OP_OR:
            result = sp.Or(ops.boolean(work[args[0]]), ops.boolean(work[args[1]]))
        elif op == ca.OP_IF_ELSE_ZERO:
            condition, value = ops.boolean(work[args[0]]), ops.number(work[args[1]])
            result = ops.name(sp.Piecewise((value, condition), (0, True)))
        else:
            raise NotImplementedError(f"SX operation {op} of {function.name()!r} at {k}")
        shared = uses[k] > 1 and isinstance(result, sp.Expr) and not result.is_Atom
        work[res[0]] = ops.name(result) if shared else result
    return [sp.Matrix(column) for column in outputs], ops.definitions


def _use_counts(function: ca.Function) -> list[int]:
    """How many later instructions read each instruction's result (CasADi reuses work slots)."""
    producer: dict[int, int] = {}
    uses = [0] * function.n_instructions()
    for k in range(function.n_instructions()):
        op = function.instruction_id(k)
        if op not in (ca.OP_CONST, ca.OP_INPUT):
            for slot in function.instruction_input(k):
                uses[producer[slot]] += 1
        if op != ca.OP_OUTPUT:
            for slot in function.instruction_output(k):
                producer[slot] = k
    return uses


def _forward_jacobian(
    outputs: sp.Matrix, definitions: Sequence[tuple[sp.Symbol, sp.Expr]], wrt: Sequence[sp.Symbol]
) -> tuple[sp.Matrix, list[tuple[sp.Symbol, sp.Expr]]]:
    """Jacobian of ``outputs`` with respect to ``wrt`` through ordered intermediates (forward
    mode: each intermediate's gradient is named after it), for :func:`_lambdify`."""
    ops = _Translation("_d")
    gradients: dict[sp.Symbol, list[sp.Expr]] = {}

    def gradient(expression: sp.Expr) -> list[sp.Expr]:
        inner = [symbol for symbol in gradients if expression.has(symbol)]
        row = []
        for j, variable in enumerate(wrt):
            entry = sp.diff(expression, variable)
            for symbol in inner:
                entry += sp.diff(expression, symbol) * gradients[symbol][j]
            row.append(entry)
        return row

    for symbol, expression in definitions:
        ops.definitions.append((symbol, expression))
        gradients[symbol] = [
            entry if entry.is_Atom else ops.name(entry) for entry in gradient(expression)
        ]
    return sp.Matrix([gradient(entry) for entry in outputs]), ops.definitions


def _lambdify(
    args: Sequence[Any],
    expressions: Sequence[sp.Matrix],
    definitions: Sequence[tuple[sp.Symbol, sp.Expr]] = (),
    modules: str = "numpy",
) -> Callable[..., Any]:
    """``sympy.lambdify(args, expressions, modules)`` evaluating ``definitions`` first, in order.

    Matrices are passed as nested lists, so that the ``"math"`` printer (no NumPy) can print them.
    """
    ordered = list(definitions)
    lists = [matrix.tolist() for matrix in expressions]
    return sp.lambdify(args, lists, modules, cse=lambda exprs: (ordered, exprs))


@dataclass(frozen=True)
class BaselineModel:
    """The lambdified pieces of the plant (NumPy functions) and the closed-loop right-hand side.

    ``params`` is the plant parameter vector
    (:data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`), ``mechanical`` its
    completed multibody part (static tyre loads of the equilibrium filled in).
    """

    complete: Callable[..., Any]
    """complete(mechanical params) -> completed mechanical params."""
    mass_matrix: Callable[..., Any]
    """mass_matrix(p, mechanical) -> M (4, 4)."""
    forces: Callable[..., Any]
    """forces(p, pd, anchor, F_act, road, road_rate, disturbance, mechanical) -> [rhs, ξ̇]."""
    outputs: Callable[..., Any]
    """outputs(p, pd, pdd, anchor, road, road_rate, mechanical) -> [f_H, f_N, f_S, F_tyre]."""
    hydraulics: Callable[..., Any]
    """hydraulics(x, u, params) -> [F_act, x_piston, Q_pump, p_acc, (ṗ_A, ṗ_B, V̇_p, V̈_p, V̇_acc)]."""
    n_mechanical: int
    force_jacobian: Callable[..., Any] | None = None
    """force_jacobian(p, pd, anchor, F_act, road, road_rate, disturbance, mechanical) ->
    [∂(rhs, ξ̇)/∂(p, ṗ, ξ, F_act)] (6, 11)."""
    inertia_jacobian: Callable[..., Any] | None = None
    """inertia_jacobian(p, pdd, mechanical) -> [∂(M(p) p̈)/∂p at fixed p̈] (4, 4)."""
    hydraulics_jacobian: Callable[..., Any] | None = None
    """hydraulics_jacobian(x, u, params) -> [∂(F_act, rates)/∂x] (90,), column-major (6, 15)."""

    def jacobian(self, x: Array, u: float, w: Array, params: Array, mechanical: Array) -> Array:
        """∂ẋ/∂x (15, 15): p̈ = M⁻¹ f gives ∂p̈/∂x = M⁻¹ (∂f/∂x − ∂(M p̈)/∂x at fixed p̈)."""
        if self.force_jacobian is None or self.inertia_jacobian is None:
            raise ValueError("built without Jacobians: baseline_model(jacobian=True)")
        assert self.hydraulics_jacobian is not None
        p, pd, anchor = x[0:4], x[4:8], x[8:10]
        _, pdd, force, *_ = self._dynamics(x, u, w, params, mechanical)
        hydraulic = np.asarray(self.hydraulics_jacobian(x, [u], params)[0], dtype=float)
        hydraulic = hydraulic.reshape((6, x.size), order="F")
        forces = np.asarray(
            self.force_jacobian(p, pd, anchor, [force], w[0:4], w[4:8], w[8:11], mechanical)[0],
            dtype=float,
        )
        inertia = np.asarray(self.inertia_jacobian(p, pdd, mechanical)[0], dtype=float)
        mass = np.asarray(self.mass_matrix(p, mechanical)[0], dtype=float)
        d_force = np.zeros((4, x.size))
        d_force[:, 0:10] = forces[0:4, 0:10]
        d_force[:, 0:4] -= inertia
        d_force += np.outer(forces[0:4, 10], hydraulic[0])
        jacobian = np.zeros((x.size, x.size))
        jacobian[0:4, 4:8] = np.eye(4)
        jacobian[4:8] = np.linalg.solve(mass, d_force)
        jacobian[8:10, 0:10] = forces[4:6, 0:10]
        jacobian[10:15] = hydraulic[1:6]
        return jacobian

    def completed(self, params: Array) -> Array:
        """The completed multibody parameters of the plant parameters ``params``."""
        values = self.complete(np.asarray(params, dtype=float)[: self.n_mechanical])
        return np.asarray(values, dtype=float).ravel()

    def rhs(self, x: Array, u: float, w: Array, params: Array, mechanical: Array) -> Array:
        """ẋ of the plant (state order :data:`~loader_model.plant.plant.STATE_NAMES`)."""
        return self._dynamics(x, u, w, params, mechanical)[0]

    def plant_outputs(
        self, x: Array, u: float, w: Array, params: Array, mechanical: Array
    ) -> Array:
        """y of the plant (order :data:`~loader_model.plant.plant.OUTPUT_NAMES`)."""
        _, pdd, force, position, pump_flow, p_acc = self._dynamics(x, u, w, params, mechanical)
        p, pd, anchor = x[0:4], x[4:8], x[8:10]
        f_h, f_n, f_s, tyres = (
            np.asarray(value, dtype=float).ravel()
            for value in self.outputs(p, pd, pdd, anchor, w[0:4], w[4:8], mechanical)
        )
        # the order of OUTPUT_NAMES
        return np.array(
            [
                *pd[0:3],
                p[3] - p[2],
                f_h[0],
                f_h[1],
                f_n[1],
                f_s[0],
                f_s[1],
                pdd[2],
                x[10],
                x[11],
                force,
                position,
                x[12],
                pump_flow,
                tyres[1],
                tyres[3],
                p_acc,
                f_s[0],  # the seat pad reads the chassis with the occupant off
                f_s[1],
            ]
        )

    def _dynamics(
        self, x: Array, u: float, w: Array, params: Array, mechanical: Array
    ) -> tuple[Array, Array, float, float, float, float]:
        """ẋ, p̈ and the hydraulic outputs F_act, x_piston, Q_pump, p_acc."""
        p, pd, anchor = x[0:4], x[4:8], x[8:10]
        force, position, pump_flow, p_acc, rates = self.hydraulics(x, [u], params)
        force = float(np.ravel(force)[0])
        mass = np.asarray(self.mass_matrix(p, mechanical)[0], dtype=float)
        rhs, anchor_rate = self.forces(p, pd, anchor, [force], w[0:4], w[4:8], w[8:11], mechanical)
        pdd = np.linalg.solve(mass, np.asarray(rhs, dtype=float).ravel())
        xdot = np.concatenate(
            [pd, pdd, np.asarray(anchor_rate, float).ravel(), np.asarray(rates, float).ravel()]
        )
        scalars = (float(np.ravel(value)[0]) for value in (position, pump_flow, p_acc))
        return (xdot, pdd, force, *scalars)


def _hydraulic_function(jacobian: bool = False) -> ca.Function:
    """The plant's hydraulic part as an SX Function of (x, u, params) (plant.py's own code), or
    with ``jacobian`` the dense ∂(F_act, rates)/∂x, column-major as one column."""
    import loader_model_generated as generated
    from loader_model.plant import plant
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    # the loader's 15 states; the occupant's (issue 21) are not in this baseline: the plant runs
    # with PlantOptions(occupant=False), so they do not act on the loader and the pad reads f_S
    x = ca.SX.sym("x", LOADER_STATES)
    full = ca.vertcat(x, ca.SX.zeros(len(plant.STATE_NAMES) - LOADER_STATES))
    u = ca.SX.sym("u", 1)
    params = ca.SX.sym("params", len(PLANT_PARAMETER_NAMES))
    n_mechanical = len(generated.PARAMETER_NAMES)
    completed, _ = generated.function("complete_parameters")(params[:n_mechanical])
    drive = plant.hydraulic_drive(full, u, plant.named_parameters(params), completed)
    names = ("force", "position", "pump_flow", "p_acc", "rates")
    if jacobian:
        d_drive = ca.jacobian(ca.vertcat(drive["force"], drive["rates"]), x)
        return ca.Function("d_hydraulics", [x, u, params], [ca.vec(ca.densify(d_drive))])
    return ca.Function("hydraulics", [x, u, params], [drive[name] for name in names])


def baseline_model(modules: str = "numpy", jacobian: bool = False) -> BaselineModel:
    """Derive, translate and lambdify the plant (module notes); about 2-5 s.

    Parameters
    ----------
    modules : str
        ``lambdify``'s modules: ``"numpy"`` (what users usually write; Piecewise becomes
        ``numpy.select``) or ``"math"`` (scalar Python: Piecewise becomes ``a if c else b``).
    """
    from derive.mechanics import derive_mechanics
    from derive.symbols import (
        ANCHORS,
        COORDINATE_ACCELERATIONS,
        COORDINATE_RATES,
        COORDINATES,
        DISTURBANCES,
        FORCE,
        PARAMETERS,
        ROAD,
        ROAD_RATES,
        parameter_symbol,
    )
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    mech = derive_mechanics()
    symbols = [parameter_symbol(item.name) for item in PARAMETERS]
    completed = [
        mech.static_loads.get(item.name, parameter_symbol(item.name)) for item in PARAMETERS
    ]
    p, pd, pdd = list(COORDINATES), list(COORDINATE_RATES), list(COORDINATE_ACCELERATIONS)
    anchor, road, road_rate = list(ANCHORS), list(ROAD), list(ROAD_RATES)
    rhs = (
        mech.actuator_map * FORCE
        + mech.gravity_forces
        + mech.disturbance_map * DISTURBANCES
        + mech.contact_tyre_forces
        - mech.coriolis_centrifugal
    )
    contact = mech.contact_definitions
    forces = _lambdify(
        [p, pd, anchor, [FORCE], road, road_rate, list(DISTURBANCES), symbols],
        [rhs, mech.anchor_rates],
        contact,
        modules,
    )
    outputs = _lambdify(
        [p, pd, pdd, anchor, road, road_rate, symbols],
        [*(mech.specific_forces[letter] for letter in "HNS"), mech.tyre_forces],
        contact,
        modules,
    )
    x = list(sp.symbols(f"x0:{15}", real=True))
    u = [sp.Symbol("u", real=True)]
    theta = list(sp.symbols(f"theta0:{len(PLANT_PARAMETER_NAMES)}", real=True))
    hydraulic, steps = sx_to_sympy(_hydraulic_function(), [x, u, theta])
    extra: dict[str, Any] = {}
    if jacobian:
        wrt = [*p, *pd, *anchor, FORCE]
        matrix, chain = _forward_jacobian(rhs.col_join(mech.anchor_rates), contact, wrt)
        extra["force_jacobian"] = _lambdify(
            [p, pd, anchor, [FORCE], road, road_rate, list(DISTURBANCES), symbols],
            [matrix],
            chain,
            modules,
        )
        inertia = (mech.mass_matrix * sp.Matrix(pdd)).jacobian(p)
        extra["inertia_jacobian"] = _lambdify([p, pdd, symbols], [inertia], (), modules)
        d_hydraulic, d_steps = sx_to_sympy(_hydraulic_function(jacobian=True), [x, u, theta])
        extra["hydraulics_jacobian"] = _lambdify([x, u, theta], d_hydraulic, d_steps, modules)
    return BaselineModel(
        complete=_lambdify([symbols], [sp.Matrix(completed)], (), modules),
        mass_matrix=_lambdify([p, symbols], [mech.mass_matrix], (), modules),
        forces=forces,
        outputs=outputs,
        hydraulics=_lambdify([x, u, theta], hydraulic, steps, modules),
        n_mechanical=len(symbols),
        **extra,
    )


def baseline_simulation(
    road: Any,
    params: Sequence[float] | np.ndarray,
    controller: ca.Function | None = None,
    *,
    settings: Sequence[float] = (),
    controller_state: Sequence[float] | None = None,
    duration_s: float,
    method: str = "LSODA",
    rtol: float = 1e-6,
    atol: float = 1e-9,
    model: BaselineModel | None = None,
) -> dict[str, np.ndarray]:
    """The closed loop with ``solve_ivp`` per 1 ms period (module notes).

    Returns ``time``, ``x`` (N, 15), ``y`` (N, 19), ``u`` (N,) at the controller's instants, as
    :func:`~loader_model.simulation.reference.reference_simulation`, and ``nfev`` (total
    right-hand sides).
    """
    from scipy.integrate import solve_ivp

    from loader_model.plant.equilibrium import static_state
    from loader_model.plant.plant import OUTPUT_NAMES
    from loader_model.simulation.controllers import CONTROLLER_PERIOD_S, hold_controller
    from loader_model.simulation.simulator import exogenous_table

    model = baseline_model() if model is None else model
    params = np.asarray(params, dtype=float).ravel()
    mechanical = model.completed(params)
    x, command = static_state(params)
    x = x[:LOADER_STATES]
    controller = hold_controller(command) if controller is None else controller
    z = np.zeros(controller.size1_in(0)) if controller_state is None else controller_state
    z = np.asarray(z, dtype=float).ravel()
    settings_vector = np.asarray(settings, dtype=float).ravel()
    period = CONTROLLER_PERIOD_S
    count = int(np.floor(duration_s / period + 1e-9))
    time_s = np.arange(count + 1) * period
    exogenous = exogenous_table(road, time_s)
    states = np.empty((count, LOADER_STATES))
    outputs = np.empty((count, len(OUTPUT_NAMES)))
    commands = np.empty(count)
    evaluations = 0

    def rhs(t: float, state: Array, u: float, k: int) -> Array:
        fraction = (t - time_s[k]) / period
        w = exogenous[k] + (exogenous[k + 1] - exogenous[k]) * fraction
        return model.rhs(state, u, w, params, mechanical)

    def jacobian(t: float, state: Array, u: float, k: int) -> Array:
        fraction = (t - time_s[k]) / period
        w = exogenous[k] + (exogenous[k + 1] - exogenous[k]) * fraction
        return model.jacobian(state, u, w, params, mechanical)

    options = {} if model.force_jacobian is None else {"jac": jacobian}
    for k in range(count):
        y = model.plant_outputs(x, command, exogenous[k], params, mechanical)
        z_next, u = controller(z, y, settings_vector)
        command = float(u)
        states[k], outputs[k], commands[k] = x, y, command
        solution = solve_ivp(
            rhs,
            (time_s[k], time_s[k + 1]),
            x,
            method=method,
            args=(command, k),
            rtol=rtol,
            atol=atol,
            **options,
        )
        if not solution.success:
            raise RuntimeError(f"solve_ivp failed at t = {time_s[k]:.4f} s: {solution.message}")
        evaluations += solution.nfev
        x = solution.y[:, -1]
        z = np.asarray(z_next, dtype=float).ravel()
    return {
        "time": time_s[:count],
        "x": states,
        "y": outputs,
        "u": commands,
        "nfev": np.array(evaluations),
    }


def seat_agreement(trace: Array, reference: Array) -> Array:
    """Per column ‖s − s_ref‖_rms / ‖s_ref − s_ref(0)‖_rms: the seat trace norm of
    ``tests/simulation/test_simulator.py`` (rows: the controller's instants)."""
    error = np.sqrt(np.mean((trace - reference) ** 2, axis=0))
    return error / np.sqrt(np.mean((reference - reference[0]) ** 2, axis=0))
