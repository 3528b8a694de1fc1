"""Input checks shared by the ISO 2631-1 modules; every failure is a ValueError naming the input."""

from __future__ import annotations

import math

import numpy as np

from loader_model.io.arrays import real_array

__all__ = ["as_positive", "as_signal", "shown"]


def shown(value: object) -> str:
    """``repr`` of ``value``, with numpy scalars shown as the plain Python number."""
    return repr(value.item() if isinstance(value, np.generic) else value)


def as_signal(value: object, name: str) -> np.ndarray:
    """Return ``value`` as a non-empty, finite, 1-D float array or raise ValueError naming it.

    A float64 array is returned as it is, not copied (a long record is evaluated by several
    functions that each check it); callers do not write to it.
    """
    if isinstance(value, np.ndarray) and value.dtype == np.float64:
        array = value
    else:
        array = real_array(name, value, "a 1-D array of real numbers")
    if array.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array; got shape {array.shape}")
    if array.size == 0:
        raise ValueError(f"{name} must not be empty; got 0 samples")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(
            f"{name} must be finite; got {array[bad[0]]} at index {bad[0]} "
            f"({bad.size} non-finite sample(s))"
        )
    return array


def as_positive(value: object, name: str, unit: str) -> float:
    """Return ``value`` as a finite float > 0 or raise ValueError naming it and its unit."""
    try:
        if isinstance(value, bool | str | bytes):
            raise TypeError(value)
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        raise ValueError(
            f"{name} must be a positive number in {unit}; got {shown(value)}"
        ) from None
    if not math.isfinite(number) or number <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0 {unit}; got {shown(value)}")
    return number
