"""Tests of loader_model.modal.calibration: recovery of known parameters from a model's own modes.

The synthetic model has the structure of DESIGN.md "The model" (Eq. 32-34 with errata 2, 5, 6):
a chassis on two tyre axles and a boom on a hydraulic spring, written out here independently of
the code under test. Its true parameters are the reference values.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pytest

from loader_model.modal.calibration import calibrate, modal_residuals
from loader_model.modal.modes import TABLE_1, ModalTable, modal_analysis

COORDINATES = ("x_H", "y_H", "theta_1", "theta_2")
FIXED = {
    "m_1": 2800.0,  # kg
    "m_2": 1000.0,  # kg
    "A_x": 1.1,  # m, front axle relative to H
    "A_y": -0.45,
    "B_x": -0.1,
    "B_y": -0.45,
    "D_x": -0.7,  # m, boom pivot relative to H
    "D_y": 0.75,
    "G_x": 1.35,  # m, boom CoG relative to H
    "G_y": -0.3,
}
TRUE = {
    "k_x": 2.0e6,  # N/m per axle
    "k_Ay": 2.4e6,  # N/m
    "k_By": 1.8e6,  # N/m
    "J_1": 1500.0,  # kg m²
    "J_2": 500.0,  # kg m²
    "k_phi": 1.1e7,  # N m/rad, k_eq (dx_cyl/dφ)²
}
BOUNDS = {name: (0.4 * value, 2.5 * value) for name, value in TRUE.items()}


def loader_matrices(values: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """Linearised M and K of the brief's loader structure; k_Ax, k_Bx default to k_x."""
    p = {**FIXED, **TRUE, **values}
    m2 = p["m_2"]
    d = np.array([p["D_x"], p["D_y"]])
    g = np.array([p["G_x"], p["G_y"]]) - d
    mass = np.array(
        [
            [p["m_1"] + m2, 0.0, -m2 * d[1], -m2 * g[1]],
            [0.0, p["m_1"] + m2, m2 * d[0], m2 * g[0]],
            [-m2 * d[1], m2 * d[0], p["J_1"] + m2 * d @ d, m2 * d @ g],
            [-m2 * g[1], m2 * g[0], m2 * d @ g, p["J_2"] + m2 * g @ g],
        ]
    )
    stiffness = np.zeros((4, 4))
    for axle in "AB":
        a_x, a_y = p[f"{axle}_x"], p[f"{axle}_y"]
        k_x, k_y = p.get(f"k_{axle}x", p["k_x"]), p[f"k_{axle}y"]
        stiffness[np.ix_([0, 1, 2], [0, 1, 2])] += [
            [k_x, 0.0, -k_x * a_y],
            [0.0, k_y, k_y * a_x],
            [-k_x * a_y, k_y * a_x, k_x * a_y**2 + k_y * a_x**2],
        ]
    stiffness[2:, 2:] += p["k_phi"] * np.array([[1.0, -1.0], [-1.0, 1.0]])
    return mass, stiffness


def own_table(reading: str, values: Mapping[str, float] = TRUE) -> ModalTable:
    result = modal_analysis(*loader_matrices(values))
    return ModalTable.from_result(result, reading, COORDINATES, "synthetic")


def perturbed_start(factor: float = 1.3) -> dict[str, float]:
    return {
        name: value * (factor if index % 2 else 1.0 / factor)
        for index, (name, value) in enumerate(TRUE.items())
    }


@pytest.mark.parametrize("reading", ["momentum", "displacement"])
def test_recovers_known_parameters_from_own_modes(reading: str) -> None:
    result = calibrate(
        loader_matrices,
        perturbed_start(),
        BOUNDS,
        reading,
        table=own_table(reading),
        n_random_starts=2,
    )
    assert result.parameters.keys() == TRUE.keys()
    for name, value in TRUE.items():
        assert result.parameters[name] == pytest.approx(value, rel=1e-6), name
    np.testing.assert_allclose(result.frequency_errors_percent, 0.0, atol=1e-6)
    np.testing.assert_allclose(result.mac, 1.0, atol=1e-10)
    assert result.meets_targets and result.at_bounds == () and result.reading == reading
    assert result.cost < 1e-12


def test_is_reproducible() -> None:
    table = own_table("momentum", {**TRUE, "J_2": 650.0})
    first, second = (
        calibrate(loader_matrices, TRUE, BOUNDS, table=table, n_random_starts=3, seed=7)
        for _ in range(2)
    )
    assert first.parameters == second.parameters
    assert first.cost == second.cost and first.start_index == second.start_index


def test_flags_parameters_that_enter_only_as_a_sum() -> None:
    # Both axles at the same height: k_Ax and k_Bx enter K only through k_Ax + k_Bx.
    start = {"k_Ax": 1.5e6, "k_Bx": 2.5e6, "J_1": 1400.0}
    bounds = {"k_Ax": (0.5e6, 4e6), "k_Bx": (0.5e6, 4e6), "J_1": (800.0, 2500.0)}
    result = calibrate(
        loader_matrices, start, bounds, table=own_table("momentum"), n_random_starts=0
    )
    singular_values = result.jacobian_singular_values
    assert singular_values[-1] < 1e-6 * singular_values[0]
    assert singular_values[-2] > 1e-3 * singular_values[0]
    assert result.parameters["k_Ax"] + result.parameters["k_Bx"] == pytest.approx(4.0e6, rel=1e-6)


def test_reports_bound_and_missed_targets_when_truth_is_excluded() -> None:
    table = own_table("momentum")
    result = calibrate(
        loader_matrices, {"k_phi": 2.5e7}, {"k_phi": (2.0e7, 3.0e7)}, table=table, n_random_starts=1
    )
    assert result.at_bounds == ("k_phi",)
    assert result.parameters["k_phi"] == pytest.approx(2.0e7, rel=1e-6)
    assert not result.meets_targets
    assert np.max(np.abs(result.frequency_errors_percent)) > 1.0


def test_residuals_are_scaled_by_the_tolerances() -> None:
    mass, stiffness = loader_matrices(TRUE)
    table = own_table("momentum")
    np.testing.assert_allclose(modal_residuals(mass, stiffness, table), 0.0, atol=1e-9)
    # Frequencies 1 % high (K scaled by 1.01²) sit exactly at the 1 % tolerance: residual 1.
    residuals = modal_residuals(mass, stiffness * 1.01**2, table, frequency_tolerance_percent=1.0)
    np.testing.assert_allclose(residuals[:4], 1.0, rtol=1e-9)
    np.testing.assert_allclose(residuals[4:], 0.0, atol=1e-9)
    # A shape rotated so that MAC = mac_minimum has a residual block of norm 1.
    shapes = table.shapes.copy()
    unit = shapes[:, 0] / np.linalg.norm(shapes[:, 0])
    other = np.linalg.qr(np.column_stack([unit, np.eye(4)[:, 1]]))[0][:, 1]
    angle = np.arccos(np.sqrt(0.99))
    shapes[:, 0] = np.cos(angle) * unit + np.sin(angle) * other
    rotated = ModalTable(table.frequencies_hz, shapes, COORDINATES, "rotated")
    residuals = modal_residuals(mass, stiffness, rotated, mac_minimum=0.99)
    assert np.linalg.norm(residuals[4:8]) == pytest.approx(1.0, rel=1e-9)
    np.testing.assert_allclose(residuals[8:], 0.0, atol=1e-9)


@pytest.mark.parametrize(
    ("start", "bounds", "kwargs", "match"),
    [
        ({}, {}, {}, "start must name at least one free parameter"),
        ({"J_1": 1500.0}, {"J_2": (1.0, 2.0)}, {}, r"missing \['J_1'\], extra \['J_2'\]"),
        (
            {"J_1": 1500.0},
            {"J_1": (2000.0, 1000.0)},
            {},
            r"bounds\['J_1'\] must be finite with lower < upper",
        ),
        ({"J_1": 1500.0}, {"J_1": (0.0, np.inf)}, {}, r"bounds\['J_1'\] must be finite"),
        ({"J_1": 3000.0}, {"J_1": (1000.0, 2000.0)}, {}, r"start\['J_1'\] = 3000.0 lies outside"),
        (
            {"J_1": 1500.0},
            {"J_1": (1000.0, 2000.0)},
            {"reading": "modal"},
            "reading must be one of",
        ),
        (
            {"J_1": 1500.0},
            {"J_1": (1000.0, 2000.0)},
            {"n_random_starts": -1},
            "n_random_starts must be",
        ),
        ({"J_1": 1500.0}, {"J_1": (1000.0, 2000.0)}, {"mac_minimum": 1.0}, "0 < mac_minimum < 1"),
    ],
)
def test_invalid_arguments_are_rejected(
    start: dict[str, float],
    bounds: dict[str, tuple[float, float]],
    kwargs: dict[str, object],
    match: str,
) -> None:
    with pytest.raises(ValueError, match=match):
        calibrate(loader_matrices, start, bounds, **kwargs)  # type: ignore[arg-type]


def test_builder_with_wrong_size_is_rejected() -> None:
    def two_dof(values: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        return np.eye(2), values["k"] * np.eye(2)

    with pytest.raises(ValueError, match=r"model has \(2, 2\) shapes but the table has \(4, 4\)"):
        calibrate(two_dof, {"k": 1.0}, {"k": (0.5, 2.0)}, table=TABLE_1)
