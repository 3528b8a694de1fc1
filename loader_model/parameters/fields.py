"""Building blocks of the parameter dataclasses: plausible ranges, unit metadata, sources.

Every leaf field of a parameter dataclass carries metadata: its SI unit string (checked against
the TOML file, no conversion), its allowed :class:`Range`, its shape (0 for a scalar, n for a
tuple of n floats) and whether it is an integer count.

The allowed range of a field is the range of *plausible* values for the machines this package is
for (compact and wheel loaders, backhoes and tractors, about 0.5 t to 50 t), with the reason
beside it; a hard physical limit (a mass is positive) is kept as an open bound. A value outside
is refused naming the field, the value, the range and the reason. A new field therefore needs
only its unit and a :class:`Range` with a reason (``tests/parameters/test_parameter_ranges.py`` checks that
every field has finite bounds and a reason).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

from loader_model.io.arrays import real_integer, real_number

__all__ = [
    "COORDINATE",
    "FINITE",
    "NONNEGATIVE",
    "POSITIVE",
    "Range",
    "Sourced",
    "TypedLeaves",
    "integer",
    "si",
    "sources_field",
    "unit_of",
]


@dataclass(frozen=True)
class Range:
    """Allowed interval of a parameter value; ``str()`` gives it for error messages.

    Attributes
    ----------
    low, high : float
        Bounds (infinite for an open end).
    low_open, high_open : bool
        Whether the bound itself is excluded.
    reason : str
        Why values outside are implausible (printed with the range in error messages).
    """

    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    reason: str = ""

    def contains(self, value: float) -> bool:
        """Return True when the finite ``value`` lies in the interval."""
        above = value > self.low if self.low_open else value >= self.low
        below = value < self.high if self.high_open else value <= self.high
        return above and below

    def describe(self) -> str:
        """The interval followed by its reason, e.g. ``"[250, 45000] (chassis of ...)"``."""
        return f"{self} ({self.reason})" if self.reason else str(self)

    def __str__(self) -> str:
        if math.isinf(self.low) and math.isinf(self.high):
            return "any finite value"
        if math.isinf(self.high):
            return f"{'>' if self.low_open else '>='} {self.low:g}"
        if math.isinf(self.low):
            return f"{'<' if self.high_open else '<='} {self.high:g}"
        left = "(" if self.low_open else "["
        right = ")" if self.high_open else "]"
        return f"{left}{self.low:g}, {self.high:g}{right}"


#: Any finite number.
FINITE = Range()
#: Strictly positive (masses, inertias, stiffnesses, volumes, diameters, ...).
POSITIVE = Range(0.0, low_open=True)
#: Zero or positive (damping, friction, leakage conductance).
NONNEGATIVE = Range(0.0)
#: A coordinate of a point in the chassis frame (m).
COORDINATE = Range(
    -10.0,
    10.0,
    reason="within 10 m of the chassis centre of gravity: the largest machines of this class "
    "(50 t wheel loaders) are about 11 m long with the bucket and reach about 6 m high",
)


def si(unit: str, allowed: Range = FINITE, shape: int = 0) -> dict[str, Any]:
    """Field metadata of a float (``shape=0``) or a tuple of ``shape`` floats in ``unit``."""
    return {"unit": unit, "allowed": allowed, "shape": shape, "integer": False}


def integer(allowed: Range = Range(1.0)) -> dict[str, Any]:
    """Field metadata of a dimensionless integer count (unit ``"-"``)."""
    return {"unit": "-", "allowed": allowed, "shape": 0, "integer": True}


def sources_field() -> Any:
    """Field holding ``(dotted path, source)`` pairs in schema order; compared, not printed."""
    return field(default=(), repr=False, metadata={"sources": True})


def unit_of(cls: type, name: str) -> str:
    """Return the SI unit string of leaf field ``name`` of parameter dataclass ``cls``."""
    return cls.__dataclass_fields__[name].metadata["unit"]


def _point(name: str, value: Any, shape: int) -> tuple[float, ...]:
    if isinstance(value, str | bytes) or not hasattr(value, "__len__") or len(value) != shape:
        raise ValueError(
            f"{name}: value {value!r} is not a sequence of {shape} numbers; allowed: a tuple, "
            f"list or 1-D array of {shape} real numbers"
        )
    return tuple(real_number(f"{name}[{i}]", item) for i, item in enumerate(value))


class TypedLeaves:
    """Mixin of the parameter dataclasses: on construction every leaf holds what its metadata says.

    Every way a parameter value enters a parameter set (a TOML file, :func:`~loader_model.
    parameters.replace`, the dataclass built in code, :func:`dataclasses.replace`) constructs the
    dataclass, so this is where a value of the wrong type is refused, naming the class, the field,
    the value and what is allowed: one real number (:func:`loader_model.io.arrays.real_number`: no
    array, not even a one-element one, no boolean or string), an integer count, or ``shape`` real
    numbers for a point. Values are stored as Python floats, ints and tuples. Ranges and
    consistency are checked by :func:`loader_model.parameters.sets.validate`.
    """

    def __post_init__(self) -> None:
        for leaf in dataclasses.fields(self):  # type: ignore[arg-type]
            if "unit" not in leaf.metadata:
                continue  # a section, or the sources
            name = f"{type(self).__name__}.{leaf.name}"
            value = getattr(self, leaf.name)
            if leaf.metadata["integer"]:
                checked: Any = real_integer(name, value)
            elif leaf.metadata["shape"]:
                checked = _point(name, value, leaf.metadata["shape"])
            else:
                checked = real_number(name, value)
            object.__setattr__(self, leaf.name, checked)


class Sourced(TypedLeaves):
    """Mixin of the top-level parameter sets: the one-line source or reason of every value."""

    sources: tuple[tuple[str, str], ...]

    def source(self, path: str) -> str:
        """Return the source/reason of the value at dotted ``path`` (e.g. ``"chassis.mass"``).

        Raises
        ------
        KeyError
            If no source is recorded for ``path``.
        """
        for key, text in self.sources:
            if key == path:
                return text
        raise KeyError(path)
