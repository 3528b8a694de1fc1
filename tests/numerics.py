"""Numerical references shared by the tests."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def central_difference(
    func: Callable[[np.ndarray], np.ndarray], point: np.ndarray, steps: np.ndarray
) -> np.ndarray:
    """Jacobian of ``func`` at ``point`` by central differences, one column per step."""
    columns = []
    for k, step in enumerate(steps):
        delta = np.zeros_like(point)
        delta[k] = step
        columns.append((func(point + delta) - func(point - delta)) / (2 * step))
    return np.column_stack(columns)
