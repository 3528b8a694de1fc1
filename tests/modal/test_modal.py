"""Tests of loader_model.modal.modes: modal analysis (Eq. 27-29), MAC and the Table 1 comparison.

Reference values come from closed forms (2-DOF chain), general eigensolvers (numpy.linalg.eig on
M⁻¹K and on K M⁻¹, the latter being Matlab's ``eig(K/M)`` of DESIGN.md erratum 7), algebraic
constructions from Table 1 and the paper's text.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from loader_model.modal.modes import (
    TABLE_1,
    ModalTable,
    compare_with_table,
    compare_with_table_1,
    modal_analysis,
    modal_assurance_criterion,
    normalise_shapes,
)

# the paper lies in ../shared beside the project (as in CI); the test is skipped without it
PAPER = Path(__file__).resolve().parents[3] / "shared" / "reference" / "000_a84aeb4c1d6a3ae9.txt"
RTOL = 1e-9


def random_system(seed: int, size: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Seeded symmetric positive definite M and K."""
    rng = np.random.default_rng(seed)
    a, b = rng.normal(size=(2, size, size))
    return a @ a.T + size * np.eye(size), b @ b.T + 0.1 * np.eye(size)


def as_matrix(values: np.ndarray) -> np.ndarray:
    """Symmetric positive definite matrix from a square array of bounded floats."""
    return values @ values.T + values.shape[0] * np.eye(values.shape[0])


square_arrays = st.integers(2, 5).flatmap(
    lambda n: arrays(np.float64, (n, n), elements=st.floats(-3.0, 3.0))
)


def closed_form_chain(m1: float, m2: float, k1: float, k2: float) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies (Hz, descending) and x2/x1 ratios of ground-k1-m1-k2-m2, by the quadratic."""
    a, b, c = m1 * m2, -(m1 * k2 + m2 * (k1 + k2)), k1 * k2
    root = np.sqrt(b * b - 4.0 * a * c)
    omega_squared = np.array([(-b + root) / (2.0 * a), (-b - root) / (2.0 * a)])
    return np.sqrt(omega_squared) / (2.0 * np.pi), (k1 + k2 - omega_squared * m1) / k2


@pytest.mark.parametrize(
    ("m1", "m2", "k1", "k2"),
    [(1.0, 1.0, 1.0, 1.0), (2.0, 0.5, 3.0e4, 1.0e4), (900.0, 40.0, 7.0, 2.0)],
)
def test_two_dof_chain_matches_closed_form(m1: float, m2: float, k1: float, k2: float) -> None:
    frequencies_hz, ratios = closed_form_chain(m1, m2, k1, k2)
    mass = np.diag([m1, m2])
    result = modal_analysis(mass, np.array([[k1 + k2, -k2], [-k2, k2]]))
    np.testing.assert_allclose(result.frequencies_hz, frequencies_hz, rtol=RTOL)
    expected_phi = normalise_shapes(np.vstack([np.ones(2), ratios]))
    np.testing.assert_allclose(result.displacement_shapes, expected_phi, rtol=RTOL, atol=1e-12)
    expected_psi = normalise_shapes(np.vstack([m1 * np.ones(2), m2 * ratios]))
    np.testing.assert_allclose(result.momentum_shapes, expected_psi, rtol=RTOL, atol=1e-12)


def test_equal_chain_has_golden_ratio_shapes() -> None:
    result = modal_analysis(np.eye(2), np.array([[2.0, -1.0], [-1.0, 1.0]]))
    golden = (1.0 + np.sqrt(5.0)) / 2.0
    np.testing.assert_allclose(
        result.frequencies_hz**2 * (2.0 * np.pi) ** 2, [golden + 1.0, 2.0 - golden], rtol=RTOL
    )
    np.testing.assert_allclose(result.displacement_shapes[:, 1], [golden - 1.0, 1.0], rtol=RTOL)


@pytest.mark.parametrize("seed", range(5))
def test_matches_general_eigensolvers(seed: int) -> None:
    mass, stiffness = random_system(seed)
    result = modal_analysis(mass, stiffness)
    # Right eigenvectors of M⁻¹K (Matlab eig(M\K)) are displacement shapes.
    values, vectors = np.linalg.eig(np.linalg.solve(mass, stiffness))
    order = np.argsort(-values.real)
    np.testing.assert_allclose(
        result.frequencies_hz, np.sqrt(values.real[order]) / (2.0 * np.pi), rtol=1e-9
    )
    np.testing.assert_allclose(
        result.displacement_shapes, normalise_shapes(vectors.real[:, order]), rtol=1e-7, atol=1e-9
    )
    # Eigenvectors of K M⁻¹ (Matlab eig(K/M), erratum 7) are momentum shapes M φ.
    values, vectors = np.linalg.eig(stiffness @ np.linalg.inv(mass))
    order = np.argsort(-values.real)
    np.testing.assert_allclose(
        result.momentum_shapes, normalise_shapes(vectors.real[:, order]), rtol=1e-7, atol=1e-9
    )
    reference = scipy.linalg.eigh(stiffness, mass, eigvals_only=True)
    np.testing.assert_allclose(np.sort(result.angular_frequencies_rad_s**2), reference, rtol=1e-10)


@settings(max_examples=60, deadline=None)
@given(
    square_arrays,
    st.data(),
)
def test_frequencies_invariant_under_change_of_units(
    values: np.ndarray, data: st.DataObject
) -> None:
    size = values.shape[0]
    mass = as_matrix(values)
    stiffness = as_matrix(values[::-1].T) - 0.5 * np.eye(size)
    scale = np.array(data.draw(st.lists(st.floats(1e-2, 1e2), min_size=size, max_size=size)))
    # p = S p': M' = S M S and K' = S K S describe the same motion in other units.
    original = modal_analysis(mass, stiffness)
    rescaled = modal_analysis(
        np.diag(scale) @ mass @ np.diag(scale), np.diag(scale) @ stiffness @ np.diag(scale)
    )
    np.testing.assert_allclose(
        rescaled.frequencies_hz, original.frequencies_hz, rtol=1e-7, atol=1e-9
    )
    omega_squared = original.angular_frequencies_rad_s**2
    assume(np.min(np.abs(np.diff(omega_squared))) > 1e-3 * np.max(omega_squared))
    mac_phi = modal_assurance_criterion(
        original.displacement_shapes, scale[:, None] * rescaled.displacement_shapes
    )
    mac_psi = modal_assurance_criterion(
        original.momentum_shapes, rescaled.momentum_shapes / scale[:, None]
    )
    np.testing.assert_allclose(np.diag(mac_phi), 1.0, atol=1e-6)
    np.testing.assert_allclose(np.diag(mac_psi), 1.0, atol=1e-6)


@settings(max_examples=60, deadline=None)
@given(square_arrays)
def test_shapes_are_orthogonal_and_normalised(values: np.ndarray) -> None:
    mass = as_matrix(values)
    stiffness = as_matrix(values.T @ values)
    result = modal_analysis(mass, stiffness)
    phi, psi = result.displacement_shapes, result.momentum_shapes
    gram = phi.T @ mass @ phi
    np.testing.assert_allclose(gram - np.diag(np.diag(gram)), 0.0, atol=1e-8 * np.max(np.abs(gram)))
    np.testing.assert_allclose(np.diag(gram), result.modal_masses, rtol=1e-9)
    gram = psi.T @ np.linalg.solve(mass, psi)
    np.testing.assert_allclose(gram - np.diag(np.diag(gram)), 0.0, atol=1e-8 * np.max(np.abs(gram)))
    for shapes in (phi, psi):
        np.testing.assert_allclose(np.max(shapes, axis=0), 1.0, rtol=1e-12)
        assert np.all(np.abs(shapes) <= 1.0 + 1e-12)
    assert np.all(np.diff(result.frequencies_hz) <= 0.0)


@settings(max_examples=100, deadline=None)
@given(
    arrays(np.float64, 5, elements=st.floats(-1e3, 1e3)),
    arrays(np.float64, 5, elements=st.floats(-1e3, 1e3)),
    st.floats(-1e3, 1e3).filter(lambda c: abs(c) > 1e-3),
)
def test_mac_range_and_parallel_vectors(a: np.ndarray, b: np.ndarray, factor: float) -> None:
    assume(np.linalg.norm(a) > 1e-3 and np.linalg.norm(b) > 1e-3)
    mac = modal_assurance_criterion(a, b)
    assert 0.0 <= mac <= 1.0
    assert mac == pytest.approx(modal_assurance_criterion(b, a), rel=1e-12, abs=1e-15)
    cosine = abs(a @ b) / (np.linalg.norm(a) * np.linalg.norm(b))
    assert mac == pytest.approx(cosine**2, rel=1e-9, abs=1e-12)
    assert modal_assurance_criterion(a, factor * a) == pytest.approx(1.0, rel=1e-12)


def test_mac_of_orthogonal_vectors_and_matrix_form() -> None:
    assert modal_assurance_criterion(np.array([1.0, 0.0]), np.array([0.0, 2.0])) == 0.0
    matrix = modal_assurance_criterion(np.eye(3), np.eye(3)[:, :2] * 4.0)
    np.testing.assert_allclose(matrix, np.eye(3)[:, :2], atol=0.0)


def table_1_from_paper() -> tuple[np.ndarray, np.ndarray]:
    text = PAPER.read_text(encoding="utf-8")
    block = text[text.index("Table 1: Natural frequencies") :][:600]
    rows = [re.findall(r"-?\d+\.\d+", line) for line in block.splitlines()]
    rows = [[float(x) for x in row] for row in rows if len(row) == 4]
    return np.array(rows[0]), np.array(rows[1:5])


@pytest.mark.skipif(not PAPER.exists(), reason="paper text not available")
def test_table_1_transcribes_the_paper() -> None:
    frequencies_hz, shapes = table_1_from_paper()
    np.testing.assert_array_equal(TABLE_1.frequencies_hz, frequencies_hz)
    np.testing.assert_array_equal(TABLE_1.shapes, shapes)
    assert not TABLE_1.shapes.flags.writeable
    assert TABLE_1.coordinates == ("x_H", "y_H", "theta_1", "theta_2")


def reconstruct(reading: str, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(M, K) whose modes are exactly Table 1 under ``reading``, for positive modal weights."""
    omega_squared = (2.0 * np.pi * TABLE_1.frequencies_hz) ** 2
    shapes = TABLE_1.shapes
    if reading == "momentum":  # ψᵀ M⁻¹ ψ diagonal: M = Ψ W Ψᵀ, K = Ψ W Ω² Ψᵀ
        return shapes @ np.diag(weights) @ shapes.T, shapes @ np.diag(
            weights * omega_squared
        ) @ shapes.T
    inverse = np.linalg.inv(shapes)  # φᵀ M φ diagonal: M = Φ⁻ᵀ W Φ⁻¹
    return inverse.T @ np.diag(weights) @ inverse, inverse.T @ np.diag(
        weights * omega_squared
    ) @ inverse


@pytest.mark.parametrize("reading", ["momentum", "displacement"])
def test_comparison_of_exact_reconstruction(reading: str) -> None:
    mass, stiffness = reconstruct(reading, np.array([1.0, 2.0, 0.5, 3.0]))
    result = modal_analysis(mass, stiffness)
    comparison = compare_with_table_1(result, reading)
    np.testing.assert_allclose(comparison.frequency_errors_percent, 0.0, atol=1e-9)
    np.testing.assert_allclose(comparison.mac, 1.0, rtol=1e-12)
    assert comparison.meets()
    other = compare_with_table_1(result, "displacement" if reading == "momentum" else "momentum")
    assert np.min(other.mac) < 0.99 and not other.meets()


def test_comparison_reports_frequency_error_in_percent() -> None:
    mass, stiffness = reconstruct("momentum", np.ones(4))
    comparison = compare_with_table_1(modal_analysis(mass, stiffness * 1.02**2))
    np.testing.assert_allclose(comparison.frequency_errors_percent, 2.0, rtol=1e-9)
    assert not comparison.meets(frequency_tolerance_percent=1.0)
    assert comparison.meets(frequency_tolerance_percent=2.5)


def structural_violation(reading: str) -> float:
    """Smallest max violation of the model's zero pattern (DESIGN.md 'The model') over weights."""

    def violations(log_weights: np.ndarray) -> np.ndarray:
        m, k = reconstruct(reading, np.exp(log_weights))
        return np.array(
            [
                m[0, 1] / np.sqrt(m[0, 0] * m[1, 1]),  # no x-y mass coupling
                (m[0, 0] - m[1, 1]) / (m[0, 0] + m[1, 1]),  # same total mass in x and y
                k[0, 1] / np.sqrt(k[0, 0] * k[1, 1]),  # tyres do not couple x and y
                k[0, 3] / np.sqrt(k[0, 0] * k[3, 3]),  # θ2 has only the cylinder spring
                k[1, 3] / np.sqrt(k[1, 1] * k[3, 3]),
                (k[2, 3] + k[3, 3]) / np.sqrt(k[2, 2] * k[3, 3]),  # spring on φ = θ2 − θ1
            ]
        )

    starts = np.random.default_rng(0).normal(size=(20, 4))
    fits = [scipy.optimize.least_squares(violations, start) for start in starts]
    return min(float(np.max(np.abs(fit.fun))) for fit in fits)


def test_erratum_7_table_1_columns_are_momentum_shapes() -> None:
    # Rounding the table to two decimals moves these normalised terms by about 0.01.
    assert structural_violation("momentum") < 0.01
    assert structural_violation("displacement") > 0.1


@pytest.mark.parametrize(
    ("mass", "stiffness", "match"),
    [
        (np.eye(3)[:2], np.eye(3)[:2], "mass_matrix must be square"),
        (np.eye(2), np.eye(3), "must match mass_matrix"),
        ([[1.0, 0.5], [0.0, 1.0]], np.eye(2), "mass_matrix must be symmetric"),
        (
            np.eye(2),
            [[1.0, np.nan], [np.nan, 1.0]],
            "stiffness_matrix must be a nonempty, finite 2-D array",
        ),
        (np.diag([1.0, -1.0]), np.eye(2), "mass_matrix must be positive definite.*-1"),
        (np.eye(2), np.diag([1.0, -4.0]), "negative eigenvalue"),
        (np.ones(2), np.eye(2), "mass_matrix must be a nonempty, finite 2-D array"),
        ([["a"]], np.eye(1), "mass_matrix must be a real 2-D array"),
    ],
)
def test_invalid_matrices_are_rejected(mass: object, stiffness: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        modal_analysis(mass, stiffness)  # type: ignore[arg-type]


def test_other_invalid_inputs_are_rejected() -> None:
    result = modal_analysis(np.eye(2), np.diag([1.0, 2.0]))
    with pytest.raises(ValueError, match="reading must be one of"):
        compare_with_table_1(result, "velocity")
    with pytest.raises(ValueError, match=r"result has \(2, 2\) shapes but the table has \(4, 4\)"):
        compare_with_table(result, TABLE_1, "momentum")
    with pytest.raises(ValueError, match="b contains a zero vector"):
        modal_assurance_criterion(np.ones(2), np.zeros(2))
    with pytest.raises(ValueError, match="both be vectors or both matrices"):
        modal_assurance_criterion(np.ones(2), np.ones(3))
    with pytest.raises(ValueError, match="shapes has a zero column"):
        normalise_shapes(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="positive finite values in descending order"):
        ModalTable(np.array([1.0, -2.0]), np.eye(2), ("a", "b"), "test")
    with pytest.raises(ValueError, match="positive finite values in descending order"):
        ModalTable(np.array([1.0, 2.0]), np.eye(2), ("a", "b"), "test")
    with pytest.raises(ValueError, match=r"shapes must have shape .* got \(2, 3\)"):
        ModalTable(np.array([2.0, 1.0]), np.ones((2, 3)), ("a", "b"), "test")


def test_round_off_asymmetry_is_accepted_and_symmetrised() -> None:
    mass, stiffness = random_system(11)
    skewed = stiffness + 1e-12 * np.max(np.abs(stiffness)) * np.triu(np.ones_like(stiffness), 1)
    reference = scipy.linalg.eigh(stiffness, mass, eigvals_only=True)
    result = modal_analysis(mass, skewed)
    np.testing.assert_allclose(np.sort(result.angular_frequencies_rad_s**2), reference, rtol=1e-9)
    with pytest.raises(ValueError, match="stiffness_matrix must be symmetric"):
        modal_analysis(mass, skewed, symmetry_rtol=1e-14)


def test_rigid_body_modes_have_zero_frequency() -> None:
    # A free-free pair (no ground spring) has one rigid-body mode with ω = 0 and equal motion.
    result = modal_analysis(np.diag([1.0, 3.0]), np.array([[2.0, -2.0], [-2.0, 2.0]]))
    np.testing.assert_allclose(
        result.frequencies_hz, [np.sqrt(2.0 * 4.0 / 3.0) / (2 * np.pi), 0.0], atol=1e-9
    )
    np.testing.assert_allclose(result.displacement_shapes[:, 1], [1.0, 1.0], rtol=1e-9)
