"""Validation of numeric arguments at the package's public entry points.

Arguments must be real numbers (Python or NumPy ints and floats; not booleans, strings or
complex numbers), finite, of the stated shape, and optionally within a plausible magnitude;
every failure is a ValueError naming the argument.
"""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np

__all__ = ["finite_scalar", "finite_vector", "real_array"]


def real_array(name: str, value: Any, expected: str = "real numbers") -> np.ndarray:
    """Return ``value`` as a float array, refusing strings, booleans, complex values and
    objects that are not real numbers with a ValueError naming ``name``."""
    if isinstance(value, str | bytes):
        raise ValueError(f"{name} must be {expected}; got the string {value!r}")
    if not isinstance(value, np.ndarray):  # a list may mix booleans into floats: look inside
        try:
            items = np.asarray(value, dtype=object).ravel().tolist()
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be {expected}; got {value!r}") from None
        if any(isinstance(v, bool | np.bool_) for v in items):
            raise ValueError(f"{name} must be {expected}, not booleans; got {value!r}")
        if any(isinstance(v, complex | np.complexfloating) for v in items):
            raise ValueError(f"{name} must be {expected}; got complex values {value!r}")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be {expected}; got {value!r}") from None
    kind = array.dtype.kind
    if kind == "O":
        items = array.ravel().tolist()
        if not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in items):
            raise ValueError(f"{name} must be {expected}; got {value!r}")
        try:
            array = np.array(items, dtype=float).reshape(array.shape)
        except OverflowError:
            raise ValueError(
                f"{name} must be finite; got an integer too large for a float"
            ) from None
    elif kind == "b":
        raise ValueError(f"{name} must be {expected}, not booleans; got {value!r}")
    elif kind == "c":
        raise ValueError(f"{name} must be {expected}; got complex values {value!r}")
    elif kind not in "iuf":
        raise ValueError(f"{name} must be {expected}; got {value!r}")
    return array.astype(float)


def finite_vector(
    name: str, value: Any, size: int, limit: float | None = None, unit: str = ""
) -> np.ndarray:
    """Return ``value`` as a float vector of length ``size``, or raise a ValueError naming it.

    Parameters
    ----------
    name : str
        The argument's name, used in messages.
    value : array_like
        Real numbers; a scalar is accepted only when ``size`` is 1.
    size : int
        Required length.
    limit : float, optional
        Largest plausible magnitude of an element.
    unit : str
        Unit of ``limit`` for the message.
    """
    array = real_array(name, value, f"real numbers with shape ({size},)")
    if array.ndim == 0 and size == 1:
        array = array.reshape(1)
    if array.shape != (size,):
        raise ValueError(f"{name} must have shape ({size},); got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite; got {array.tolist()}")
    if limit is not None and np.any(np.abs(array) > limit):
        raise ValueError(
            f"{name} = {array.tolist()} is implausible; allowed: |{name}[i]| <= {limit:g} {unit}".rstrip()
        )
    return array


def finite_scalar(name: str, value: Any, limit: float | None = None, unit: str = "") -> float:
    """Return ``value`` as a finite float, or raise a ValueError naming it."""
    return float(finite_vector(name, value, 1, limit, unit)[0])
