"""Validation of numeric arguments at the package's public entry points.

Arguments must be real numbers (Python or NumPy ints and floats; not booleans, strings or
complex numbers), finite, of the stated shape, and optionally within a plausible magnitude;
every failure is a ValueError naming the argument. Where one number is expected
(:func:`real_number`, :func:`real_integer`), an array is refused too, even a 0-d or one-element
one: ``[2830.0]`` for a mass is a mistake, not a mass.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["finite_scalar", "finite_vector", "real_array", "real_integer", "real_number"]

#: What :func:`real_number` accepts, for its messages.
NUMBER = "a real number (int, float or NumPy scalar)"
_SHOWN_CHARACTERS = 60


def _shown(value: Any) -> str:
    """``repr`` of ``value``, shortened: huge integers by their digit count, long text cut."""
    if isinstance(value, int) and not isinstance(value, bool) and len(str(abs(value))) > 20:
        return f"{str(value)[:20]}... ({len(str(abs(value)))} digits)"
    text = repr(value.item() if isinstance(value, np.generic) else value)
    return text if len(text) <= _SHOWN_CHARACTERS else text[: _SHOWN_CHARACTERS - 3] + "..."


def _kind(value: Any) -> str:
    """What ``value`` is, for a message that says it is not a number."""
    if isinstance(value, bool | np.bool_):
        return "a boolean"
    if isinstance(value, str | bytes):
        return "a string"
    if isinstance(value, np.ndarray):
        return f"an array of shape {value.shape}"
    if isinstance(value, numbers.Complex):
        return "a complex number"
    if value is None:
        return "None"
    return f"a {type(value).__name__}"


def real_number(name: str, value: Any, allowed: str = NUMBER) -> float:
    """Return one real number ``value`` as a float, or raise a ValueError naming ``name``.

    Parameters
    ----------
    name : str
        The argument's or parameter's name, used in messages.
    value : object
        A Python int or float or a NumPy integer or floating scalar (any
        :class:`numbers.Real` but a boolean). Refused: booleans, strings, complex numbers,
        arrays (also 0-d and one-element ones), lists, tuples, None and other objects.
    allowed : str
        What is allowed, for the message.

    Returns
    -------
    float
        The value (not checked for finiteness: the caller's range says what is allowed).
    """
    if isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_):
        try:
            return float(value)
        except OverflowError:
            raise ValueError(
                f"{name}: value {_shown(value)} is not a finite float; allowed: a finite number"
            ) from None
    raise ValueError(
        f"{name}: value {_shown(value)} is not a number; allowed: {allowed}, not {_kind(value)}"
    )


def real_integer(name: str, value: Any) -> int:
    """Return one integer ``value`` (Python or NumPy int, not a boolean) as an int, or raise a
    ValueError naming ``name``; floats are refused even when integral (``2.0`` for a count)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_):
        return int(value)
    real_number(name, value, "an integer")  # names a non-number by its kind
    raise ValueError(f"{name}: value {_shown(value)} is not an integer; allowed: an integer")


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
    """Return one real number ``value`` (see :func:`real_number`; no array, not even one of one
    element) as a finite float, optionally at most ``limit`` in magnitude, or raise a ValueError
    naming ``name``."""
    number = real_number(name, value)
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite; got {number}")
    if limit is not None and abs(number) > limit:
        raise ValueError(
            f"{name} = {number!r} is implausible; allowed: |{name}| <= {limit:g} {unit}".rstrip()
        )
    return number
