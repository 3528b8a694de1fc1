"""Validation of numeric arguments at the package's public entry points."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["finite_scalar", "finite_vector"]


def finite_vector(name: str, value: Any, size: int) -> np.ndarray:
    """Return ``value`` as a float vector of length ``size``, or raise a ValueError naming it.

    A scalar is accepted only when ``size`` is 1. NaN and infinity are rejected.
    """
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be numeric with shape ({size},); got {value!r}") from error
    if array.ndim == 0 and size == 1:
        array = array.reshape(1)
    if array.shape != (size,):
        raise ValueError(f"{name} must have shape ({size},); got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite; got {array.tolist()}")
    return array


def finite_scalar(name: str, value: Any) -> float:
    """Return ``value`` as a finite float, or raise a ValueError naming it."""
    return float(finite_vector(name, value, 1)[0])
