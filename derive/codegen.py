"""Print SymPy expressions as Python source that builds named CasADi Functions.

One generated file per function (the SymForce pattern): a header with the generator, the
"do NOT modify" warning, the input hash and the op count; CSE temporaries named ``_t0, _t1, ...``;
the function's docstring copied from the derivation. Output is deterministic for a fixed SymPy
version (pinned in pyproject.toml) and formatted with ruff.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

__all__ = ["CasadiPrinter", "FunctionSpec", "InputSpec", "OutputSpec", "emit_function"]

_CASADI_FUNCTIONS = {
    name: f"ca.{name}" for name in ("sin", "cos", "tan", "atan2", "exp", "log", "tanh", "sqrt")
} | {"Abs": "ca.fabs"}


class CasadiPrinter(PythonCodePrinter):
    """Python code printer whose functions are CasADi's (``ca.sin``, ``ca.if_else``, ...)."""

    def __init__(self) -> None:
        super().__init__({"user_functions": _CASADI_FUNCTIONS, "fully_qualified_modules": True})

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exponent = expr.as_base_exp()
        if exponent == sp.S.Half:
            return f"ca.sqrt({self._print(base)})"
        if exponent == -sp.S.Half:
            return f"1 / ca.sqrt({self._print(base)})"
        if exponent == 2:
            printed = self._print(base)
            return f"({printed} * {printed})" if base.is_Atom else f"({printed}) ** 2"
        return super()._print_Pow(expr, rational=rational)

    def _print_Max(self, expr: sp.Max) -> str:
        args = [self._print(arg) for arg in expr.args]
        out = args[0]
        for arg in args[1:]:
            out = f"ca.fmax({out}, {arg})"
        return out

    def _print_And(self, expr: sp.And) -> str:
        return self._nary("ca.logic_and", expr)

    def _print_Or(self, expr: sp.Or) -> str:
        return self._nary("ca.logic_or", expr)

    def _print_Not(self, expr: sp.Not) -> str:
        return f"ca.logic_not({self._print(expr.args[0])})"

    def _nary(self, function: str, expr: sp.Expr) -> str:
        args = sorted(self._print(arg) for arg in expr.args)
        out = args[0]
        for arg in args[1:]:
            out = f"{function}({out}, {arg})"
        return out

    def _print_Piecewise(self, expr: sp.Piecewise) -> str:
        *pieces, (last_value, last_condition) = expr.args
        if last_condition is not sp.true:
            raise ValueError("a Piecewise must end with an unconditional piece")
        out = self._print(last_value)
        for value, condition in reversed(pieces):
            out = f"ca.if_else({self._print(condition)}, {self._print(value)}, {out})"
        return out


@dataclass(frozen=True)
class InputSpec:
    """A vector input of a generated function and the scalar symbols it unpacks into."""

    name: str
    symbols: tuple[sp.Symbol, ...]
    description: str


@dataclass(frozen=True)
class OutputSpec:
    """A matrix output of a generated function."""

    name: str
    expression: sp.Matrix
    description: str


@dataclass(frozen=True)
class FunctionSpec:
    """Everything needed to emit one generated function file."""

    name: str
    summary: str
    details: str
    inputs: tuple[InputSpec, ...]
    outputs: tuple[OutputSpec, ...]
    epilogue: str = ""
    """Extra source lines (already indented) that derive outputs numerically from the printed ones,
    e.g. ``ca.solve``; they may reassign output variables."""
    extra_outputs: tuple[tuple[str, str], ...] = ()
    """(name, description) of outputs computed only in the epilogue."""
    return_names: tuple[str, ...] | None = None
    """Output variables returned, in order (default: all printed outputs)."""
    definitions: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    """Named intermediates, printed in order before the outputs (each with its own CSE); the
    outputs and later definitions may use their symbols."""


def _count_ops(expressions: Sequence[sp.Expr]) -> int:
    return int(sum(sp.count_ops(expression) for expression in expressions))


def emit_function(spec: FunctionSpec, header: str) -> str:
    """Return the Python source of the file that builds ``spec`` as a CasADi Function."""
    printer = CasadiPrinter()
    flat: list[sp.Expr] = []
    for output in spec.outputs:
        flat.extend(output.expression)
    replacements, reduced = sp.cse(
        flat, symbols=sp.numbered_symbols("_t"), order="canonical", ignore=()
    )
    definition_lines: list[str] = []
    definition_ops = 0
    defined = {symbol for symbol, _ in spec.definitions}
    expressions = [*reduced, *(r for _, r in replacements)]
    for index, (symbol, expression) in enumerate(spec.definitions):
        inner, (body,) = sp.cse(
            [expression], symbols=sp.numbered_symbols(f"_d{index}_"), order="canonical"
        )
        for temporary, value in inner:
            definition_lines.append(f"    {temporary.name} = {printer.doprint(value)}")
        definition_lines.append(f"    {symbol.name} = {printer.doprint(body)}")
        definition_ops += _count_ops([v for _, v in inner]) + _count_ops([body])
        expressions += [body, *(v for _, v in inner)]
    used = set().union(*(expr.free_symbols for expr in expressions)) - defined
    ops = _count_ops([r for _, r in replacements]) + _count_ops(reduced) + definition_ops

    lines = [header.format(ops=ops), f'"""{spec.summary}', "", spec.details.strip(), '"""', ""]
    lines += ["from __future__ import annotations", "", "import casadi as ca", "", ""]
    lines.append(f"def build_{spec.name}() -> ca.Function:")
    signature = ", ".join(i.name for i in spec.inputs)
    out_names = spec.return_names or tuple(o.name for o in spec.outputs)
    lines.append(f'    """Build ``{spec.name}({signature}) -> ({", ".join(out_names)})``.')
    lines.append("")
    lines.append("    Inputs")
    lines.append("    ------")
    for item in spec.inputs:
        lines.append(f"    {item.name} : ({len(item.symbols)},) {item.description}")
    lines.append("")
    lines.append("    Outputs")
    lines.append("    -------")
    described = {o.name: o.description for o in spec.outputs} | dict(spec.extra_outputs)
    for name in out_names:
        lines.append(f"    {name} : {described[name]}")
    lines.append('    """')
    for item in spec.inputs:
        lines.append(f'    {item.name} = ca.SX.sym("{item.name}", {len(item.symbols)})')
    for item in spec.inputs:
        for index, symbol in enumerate(item.symbols):
            if symbol in used:
                lines.append(f"    {symbol.name} = {item.name}[{index}]")
    lines += definition_lines
    for symbol, expression in replacements:
        lines.append(f"    {symbol.name} = {printer.doprint(expression)}")
    cursor = 0
    for output in spec.outputs:
        rows, cols = output.expression.shape
        lines.append(f"    {output.name} = ca.SX({rows}, {cols})")
        for index in range(rows * cols):
            value = reduced[cursor + index]
            if value != 0:
                row, col = divmod(index, cols)
                lines.append(f"    {output.name}[{row}, {col}] = {printer.doprint(value)}")
        cursor += rows * cols
    if spec.epilogue:
        lines.append(spec.epilogue.rstrip())
    inputs = ", ".join(i.name for i in spec.inputs)
    input_names = ", ".join(f'"{i.name}"' for i in spec.inputs)
    outputs = ", ".join(out_names)
    output_names = ", ".join(f'"{name}"' for name in out_names)
    lines.append(
        f'    return ca.Function("{spec.name}", [{inputs}], [{outputs}], '
        f"[{input_names}], [{output_names}])"
    )
    return "\n".join(lines) + "\n"
