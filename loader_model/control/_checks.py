"""Validation of matrices, masks and python-control systems at the control entry points.

Every error names the argument, the value's shape or defect and what is allowed.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = [
    "finite_matrix",
    "gain_mask",
    "select_channels",
    "spectral_abscissa",
    "symmetric_matrix",
]


def finite_matrix(name: str, value: Any, shape: tuple[int | None, int | None]) -> np.ndarray:
    """Return ``value`` as a finite float matrix of ``shape`` (None: any size), or raise ValueError."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be a numeric matrix; got {value!r}") from error
    if array.ndim == 1 and shape[0] == 1:
        array = array.reshape(1, -1)
    expected = tuple("any" if s is None else s for s in shape)
    if array.ndim != 2 or any(
        s is not None and s != a for s, a in zip(shape, array.shape, strict=False)
    ):
        raise ValueError(f"{name} must have shape {expected}; got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(
            f"{name} must be finite; got non-finite entries {array[~np.isfinite(array)]}"
        )
    return array


def symmetric_matrix(name: str, value: Any, size: int, *, definite: bool) -> np.ndarray:
    """A symmetric positive (semi)definite ``size`` x ``size`` matrix, or ValueError naming it."""
    array = finite_matrix(name, value, (size, size))
    scale = max(1.0, float(np.max(np.abs(array))))
    if not np.allclose(array, array.T, rtol=0.0, atol=1e-12 * scale):
        asymmetry = float(np.max(np.abs(array - array.T)))
        raise ValueError(f"{name} must be symmetric; max |{name} - {name}ᵀ| = {asymmetry:.3g}")
    array = 0.5 * (array + array.T)
    smallest = float(np.min(np.linalg.eigvalsh(array)))
    if definite and smallest <= 0.0:
        raise ValueError(f"{name} must be positive definite; smallest eigenvalue {smallest:.3g}")
    if not definite and smallest < -1e-12 * scale:
        raise ValueError(
            f"{name} must be positive semidefinite; smallest eigenvalue {smallest:.3g}"
        )
    return array


def gain_mask(mask: Any, shape: tuple[int, int]) -> np.ndarray:
    """Boolean mask of free gain entries (all free when ``mask`` is None)."""
    if mask is None:
        return np.ones(shape, dtype=bool)
    array = np.asarray(mask)
    if array.shape != shape:
        raise ValueError(f"mask must have the gain's shape {shape}; got shape {array.shape}")
    if array.dtype != bool and not np.all(np.isin(array, (0, 1))):
        raise ValueError(f"mask must be boolean (True: free entry); got values {np.unique(array)}")
    array = array.astype(bool)
    if not array.any():
        raise ValueError("mask must leave at least one gain entry free; got all False")
    return array


def spectral_abscissa(matrix: np.ndarray) -> float:
    """Largest real part of the eigenvalues of ``matrix``."""
    return float(np.max(np.linalg.eigvals(matrix).real))


def _indices(kind: str, labels: Sequence[str], chosen: Sequence[str | int] | None) -> list[int]:
    if chosen is None:
        return list(range(len(labels)))
    result = []
    for item in chosen:
        if isinstance(item, (int, np.integer)) and 0 <= item < len(labels):
            result.append(int(item))
        elif item in labels:
            result.append(list(labels).index(item))
        else:
            raise ValueError(
                f"{kind} {item!r} is not a signal of the system; allowed: {list(labels)}"
            )
    return result


def select_channels(
    system: Any, inputs: Sequence[str | int] | None, outputs: Sequence[str | int] | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, list[str], list[str]]:
    """A, B, C, D and the names of the selected inputs and outputs of a StateSpace or (A, B, C)."""
    if hasattr(system, "A") and hasattr(system, "input_labels"):
        a, b, c, d = (np.asarray(getattr(system, k), dtype=float) for k in "ABCD")
        if getattr(system, "dt", 0) not in (0, None):
            raise ValueError(f"system must be continuous-time; got dt = {system.dt}")
        in_names, out_names = list(system.input_labels), list(system.output_labels)
    elif isinstance(system, (tuple, list)) and len(system) in (3, 4):
        a = finite_matrix("A", system[0], (None, None))
        n = a.shape[0]
        a = finite_matrix("A", a, (n, n))
        b = finite_matrix("B", system[1], (n, None))
        c = finite_matrix("C", system[2], (None, n))
        d = np.zeros((c.shape[0], b.shape[1]))
        if len(system) == 4:
            d = finite_matrix("D", system[3], (c.shape[0], b.shape[1]))
        in_names = [f"u[{i}]" for i in range(b.shape[1])]
        out_names = [f"y[{i}]" for i in range(c.shape[0])]
    else:
        raise ValueError(
            "system must be a python-control StateSpace or a tuple (A, B, C); "
            f"got {type(system).__name__}"
        )
    i_in, i_out = _indices("input", in_names, inputs), _indices("output", out_names, outputs)
    b, c, d = b[:, i_in], c[i_out, :], d[np.ix_(i_out, i_in)]
    for name, array in (("A", a), ("B", b), ("C", c)):
        if not np.all(np.isfinite(array)):
            raise ValueError(f"{name} of system must be finite")
    return a, b, c, d, [in_names[i] for i in i_in], [out_names[i] for i in i_out]
