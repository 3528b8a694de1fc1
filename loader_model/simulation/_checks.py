"""Input checks shared by the road modules; every failure is a ValueError naming the input."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["as_finite_array", "as_number", "as_seed", "shown"]


def shown(value: object) -> str:
    """``repr`` of ``value``, with numpy scalars shown as the plain Python number."""
    return repr(value.item() if isinstance(value, np.generic) else value)


def as_number(
    value: object,
    name: str,
    unit: str,
    *,
    minimum: float = -math.inf,
    maximum: float = math.inf,
    strict_minimum: bool = False,
) -> float:
    """Return ``value`` as a finite float in the allowed range, else raise ValueError naming it.

    Parameters
    ----------
    value : object
        The number to check.
    name, unit : str
        Argument name and unit shown in the error message.
    minimum, maximum : float
        Allowed closed range (``minimum`` open if ``strict_minimum``).
    strict_minimum : bool
        Require ``value > minimum`` instead of ``value >= minimum``.

    Returns
    -------
    float
        The checked value.
    """
    low = "(" if strict_minimum else "["
    allowed = f"{low}{minimum:g}, {maximum:g}] {unit}"
    if isinstance(value, bool):
        raise ValueError(f"{name} must be a number in {allowed}; got {value!r}")
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number in {allowed}; got {shown(value)}") from None
    below = number <= minimum if strict_minimum else number < minimum
    if not math.isfinite(number) or below or number > maximum:
        raise ValueError(f"{name} must be a finite number in {allowed}; got {shown(value)}")
    return number


def as_finite_array(value: object, name: str, unit: str) -> np.ndarray:
    """Return ``value`` as a finite 1-D float array (a copy), else raise ValueError naming it."""
    try:
        array = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} must be a 1-D array of numbers in {unit}; got {value!r}"
        ) from None
    if array.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array in {unit}; got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(
            f"{name} must be finite; got {array[bad[0]]} {unit} at index {bad[0]} "
            f"({bad.size} non-finite value(s))"
        )
    return array


def as_seed(value: object, name: str = "seed") -> int:
    """Return ``value`` as a non-negative int seed, else raise ValueError naming it."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 0:
        raise ValueError(f"{name} must be a non-negative integer; got {shown(value)}")
    return int(value)
