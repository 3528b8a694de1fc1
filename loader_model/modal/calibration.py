"""Calibrate uncertain model parameters so that the modal analysis reproduces Table 1.

The paper's geometry and masses came from the manufacturer and are not published; tyre and boom
properties are the least known. :func:`calibrate` fits the free parameters of any model, given as a
callable returning (M, K), to a modal table (Eq. 27-29, Table 1) by bounded nonlinear least squares.
Table 1's columns are compared as momentum shapes M φ by default (errata 7).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import scipy.optimize

from loader_model.modal.modes import (
    TABLE_1,
    ModalTable,
    check_reading,
    compare_with_table,
    modal_analysis,
)

__all__ = ["CalibrationResult", "MatrixBuilder", "calibrate", "modal_residuals"]

#: Maps named parameter values to the (mass_matrix, stiffness_matrix) of Eq. 27.
MatrixBuilder = Callable[[Mapping[str, float]], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class CalibrationResult:
    """Outcome of :func:`calibrate`.

    Attributes
    ----------
    parameters : dict of str to float
        Fitted values of the free parameters, in the units of ``start``.
    reading : str
        ``"momentum"`` or ``"displacement"``: how the table's shapes were read.
    frequencies_hz, frequency_errors_percent, mac : ndarray, shape (k,)
        Model frequencies, their errors against the table in percent, and MAC per mode.
    cost : float
        Half the sum of squared normalised residuals (see :func:`modal_residuals`).
    meets_targets : bool
        Every |frequency error| ≤ ``frequency_tolerance_percent`` and every MAC ≥ ``mac_minimum``.
    at_bounds : tuple of str
        Free parameters that ended within 0.1 % of the bound range from a bound.
    jacobian_singular_values : ndarray
        Singular values, descending, of the Jacobian of the scaled residuals with respect to the free
        parameters scaled to their bound ranges; a value near zero flags a parameter combination
        that the table cannot identify (e.g. two stiffnesses that enter only as their sum).
    start_index : int
        Which start gave the result (0 is ``start``; the others are seeded random starts).
    n_evaluations : int
        Model evaluations summed over all starts.
    """

    parameters: dict[str, float]
    reading: str
    frequencies_hz: np.ndarray
    frequency_errors_percent: np.ndarray
    mac: np.ndarray
    cost: float
    meets_targets: bool
    at_bounds: tuple[str, ...]
    jacobian_singular_values: np.ndarray
    start_index: int
    n_evaluations: int


def _unit_vectors(shapes: np.ndarray) -> np.ndarray:
    return shapes / np.linalg.norm(shapes, axis=0)


def modal_residuals(
    mass_matrix: np.ndarray,
    stiffness_matrix: np.ndarray,
    table: ModalTable = TABLE_1,
    reading: str = "momentum",
    frequency_tolerance_percent: float = 1.0,
    mac_minimum: float = 0.99,
) -> np.ndarray:
    """Residuals of a model's modes against ``table``, each scaled by its acceptance tolerance.

    Parameters
    ----------
    mass_matrix, stiffness_matrix : ndarray, shape (n, n)
        M and K of Eq. 27.
    table : ModalTable
        Target frequencies and normalised shapes (default: Table 1).
    reading : {"momentum", "displacement"}
        Compare the table's columns with M φ (erratum 7) or with φ.
    frequency_tolerance_percent, mac_minimum : float
        Tolerances that scale the residuals.

    Returns
    -------
    ndarray, shape (k + n k,)
        Per mode (f_model / f_table − 1) / tolerance, then per mode the component of the model's unit
        shape orthogonal to the table's unit shape, divided by sqrt(1 − mac_minimum). That component
        has length sqrt(1 − MAC), so a residual entry of magnitude 1 sits at the tolerance.
    """
    check_reading(reading)
    result = modal_analysis(mass_matrix, stiffness_matrix)
    model = _unit_vectors(result.shapes(reading))
    if model.shape != table.shapes.shape:
        raise ValueError(
            f"the model has {model.shape} shapes but the table has {table.shapes.shape}; "
            "they must match"
        )
    target = _unit_vectors(table.shapes)
    cosines = np.sum(model * target, axis=0)
    model = model * np.where(cosines < 0.0, -1.0, 1.0)
    orthogonal = model - target * np.abs(cosines)
    frequency = (result.frequencies_hz / table.frequencies_hz - 1.0) * (
        100.0 / frequency_tolerance_percent
    )
    return np.concatenate([frequency, orthogonal.ravel(order="F") / np.sqrt(1.0 - mac_minimum)])


def _checked_bounds(
    start: Mapping[str, float], bounds: Mapping[str, tuple[float, float]]
) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    names = list(start)
    if not names:
        raise ValueError("start must name at least one free parameter; got an empty mapping")
    if set(bounds) != set(names):
        raise ValueError(
            f"bounds must have exactly the keys of start; missing {sorted(set(names) - set(bounds))}"
            f", extra {sorted(set(bounds) - set(names))}"
        )
    lower = np.array([float(bounds[name][0]) for name in names])
    upper = np.array([float(bounds[name][1]) for name in names])
    values = np.array([float(start[name]) for name in names])
    for name, low, high, value in zip(names, lower, upper, values, strict=True):
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise ValueError(
                f"bounds[{name!r}] must be finite with lower < upper; got {bounds[name]}"
            )
        if not low <= value <= high:
            raise ValueError(f"start[{name!r}] = {value} lies outside its bounds [{low}, {high}]")
    return names, lower, upper, values


def calibrate(
    build_matrices: MatrixBuilder,
    start: Mapping[str, float],
    bounds: Mapping[str, tuple[float, float]],
    reading: str = "momentum",
    *,
    table: ModalTable = TABLE_1,
    n_random_starts: int = 7,
    seed: int = 0,
    frequency_tolerance_percent: float = 1.0,
    mac_minimum: float = 0.99,
) -> CalibrationResult:
    """Fit the free parameters so that the modes of ``build_matrices`` match ``table``.

    Parameters
    ----------
    build_matrices : callable
        ``build_matrices(values) -> (M, K)`` for a mapping of the free parameters' values; fixed
        parameters are the caller's business (close over them).
    start : mapping of str to float
        Free parameters and their starting values.
    bounds : mapping of str to (float, float)
        Finite physical lower and upper bound of every free parameter.
    reading : {"momentum", "displacement"}
        How the table's shapes are read (erratum 7: ``"momentum"``).
    table : ModalTable
        Target modes (default Table 1); the model must have as many modes as the table.
    n_random_starts : int
        Extra starts, drawn uniformly within the bounds from ``numpy.random.default_rng(seed)``.
    seed : int
        Seed of the extra starts; the result is reproducible for equal inputs.
    frequency_tolerance_percent, mac_minimum : float
        Acceptance targets; they also scale the residuals (:func:`modal_residuals`).

    Returns
    -------
    CalibrationResult
        The best of all starts by cost.

    Raises
    ------
    ValueError
        For inconsistent ``start``/``bounds``, an unknown ``reading``, invalid tolerances, or when
        :func:`~loader_model.modal.modes.modal_analysis` rejects the builder's matrices (also mid-fit:
        choose bounds inside which M is positive definite and K positive semi-definite).

    Notes
    -----
    Each start runs ``scipy.optimize.least_squares`` (trust-region reflective, bounds) on the
    parameters scaled to [0, 1] within their bounds. Modes are paired with the table's columns in
    order of descending frequency, so a start whose modes cross ends with a large cost. Check
    ``jacobian_singular_values`` before trusting individual values: Table 1 has 4 frequencies and
    12 free shape entries, and e.g. the two axles' k_x enter only as their sum when A_y = B_y.
    """
    check_reading(reading)
    if int(n_random_starts) != n_random_starts or n_random_starts < 0:
        raise ValueError(f"n_random_starts must be a nonnegative integer; got {n_random_starts!r}")
    if not 0.0 < mac_minimum < 1.0 or frequency_tolerance_percent <= 0.0:
        raise ValueError(
            "need 0 < mac_minimum < 1 and frequency_tolerance_percent > 0; got "
            f"{mac_minimum!r} and {frequency_tolerance_percent!r}"
        )
    names, lower, upper, values = _checked_bounds(start, bounds)
    span = upper - lower
    evaluations = 0

    def values_of(scaled: np.ndarray) -> dict[str, float]:
        return dict(zip(names, (lower + span * scaled).tolist(), strict=True))

    def residuals(scaled: np.ndarray) -> np.ndarray:
        nonlocal evaluations
        evaluations += 1
        mass, stiffness = build_matrices(values_of(scaled))
        return modal_residuals(
            mass, stiffness, table, reading, frequency_tolerance_percent, mac_minimum
        )

    rng = np.random.default_rng(seed)
    starts = [(values - lower) / span, *rng.uniform(size=(int(n_random_starts), len(names)))]
    fits = [
        scipy.optimize.least_squares(
            residuals, scaled, bounds=(0.0, 1.0), method="trf", x_scale=1.0, xtol=1e-12, ftol=1e-12
        )
        for scaled in starts
    ]
    best_index = min(range(len(fits)), key=lambda index: (fits[index].cost, index))
    best = fits[best_index]
    fitted = values_of(best.x)
    comparison = compare_with_table(modal_analysis(*build_matrices(fitted)), table, reading)
    return CalibrationResult(
        parameters=fitted,
        reading=reading,
        frequencies_hz=comparison.frequencies_hz,
        frequency_errors_percent=comparison.frequency_errors_percent,
        mac=comparison.mac,
        cost=float(best.cost),
        meets_targets=comparison.meets(frequency_tolerance_percent, mac_minimum),
        at_bounds=tuple(
            name for name, x in zip(names, best.x, strict=True) if min(x, 1.0 - x) < 1e-3
        ),
        jacobian_singular_values=np.linalg.svd(best.jac, compute_uv=False),
        start_index=best_index,
        n_evaluations=evaluations,
    )
