"""A machine's parameter values (a flat ``{name: {value, unit, source}}`` set) checked against
its description (:mod:`derive.description`): every parameter and every tyre entry of its
``[tyres]`` given once, with its unit, a finite value inside its range and a source."""

from __future__ import annotations

import math
from typing import Any

from derive.description import DescriptionError, Machine, static_load_parameters
from derive.description_checks import shown
from derive.description_keys import closest

__all__ = ["check_values"]


def check_values(machine: Machine, values: dict[str, dict[str, Any]]) -> None:
    """Check a flat parameter set ``{name: {value, unit, source}}`` against ``machine``.

    The static loads (:func:`static_load_parameters`) may be left out.

    Raises
    ------
    DescriptionError
        For a missing or unknown name (a misspelt one: with the closest name and those still
        missing), a wrong unit, a value outside the range, no source, end stops whose travel
        limits do not hold the static position (s_min < 0 < s_max).
    """
    where = f"values for {machine.name}"
    known = {item.name: item for item in (*machine.parameters, *machine.tyres)}
    loads = static_load_parameters(machine)
    for name in values:
        if name not in known:
            left = [n for n in known if n not in values and n not in loads]
            guess = closest(name, left) or closest(name, known)
            hint = f" (did you mean {guess!r}?)" if guess else ""
            missing = f"; missing: {', '.join(left)}" if left else ""
            raise DescriptionError(where, name, f"not a parameter of the machine{hint}{missing}")
    for name, item in known.items():
        if name not in values and name in loads:
            continue  # computed at rest: the value given is not used
        if name not in values:
            raise DescriptionError(where, name, "missing")
        entry = values[name]
        if not isinstance(entry, dict):
            raise DescriptionError(where, name, f"{shown(entry)}: give {{ value, unit, source }}")
        value = entry.get("value")
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise DescriptionError(where, f"{name}.value", f"{shown(value)}: give a finite number")
        if entry.get("unit") != item.unit:
            raise DescriptionError(
                where, f"{name}.unit", f"{shown(entry.get('unit'))}, expected {item.unit!r}"
            )
        if not isinstance(entry.get("source"), str) or not entry["source"]:
            raise DescriptionError(where, f"{name}.source", "missing source")
        if item.range is not None and not item.range[0] <= value <= item.range[1]:
            raise DescriptionError(where, f"{name}.value", f"{value} outside {item.range}")
    for element in machine.stops:
        low, high = (values[f"s_{end}_{element}"]["value"] for end in ("min", "max"))
        if not low < 0 < high:
            raise DescriptionError(
                where,
                f"s_min_{element}, s_max_{element}",
                f"[{low}, {high}]: the travel limits must hold the static position inside, "
                "s_min < 0 < s_max (travel from p = 0, in m)",
            )
