"""Undamped modal analysis of the linearised loader (Eq. 27-29) and its comparison with Table 1.

Free vibration M p̈ + K p = 0 (Eq. 27) gives K φ = ω² M φ with p = (x_H, y_H, θ1, θ2) in m and rad.
Table 1 lists per mode a column scaled so that its largest-magnitude entry is +1. Per errata 7
(guide page "Errata") those columns are left eigenvectors M φ (eigenvectors of K M⁻¹, what Matlab's
``eig(-K/M)`` returns), not displacement shapes φ; this module reports and compares both readings.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

__all__ = [
    "READINGS",
    "TABLE_1",
    "ModalComparison",
    "ModalResult",
    "ModalTable",
    "check_reading",
    "compare_with_table",
    "compare_with_table_1",
    "modal_analysis",
    "modal_assurance_criterion",
    "normalise_shapes",
]

#: How a table's columns are read: ``"displacement"`` (φ) or ``"momentum"`` (M φ, erratum 7).
READINGS = ("momentum", "displacement")


def check_reading(reading: str) -> None:
    """Raise ValueError unless ``reading`` is one of :data:`READINGS`."""
    if reading not in READINGS:
        raise ValueError(f"reading must be one of {READINGS}; got {reading!r}")


def _as_matrix(value: object, name: str, symmetry_rtol: float | None = None) -> np.ndarray:
    """Finite 2-D float array; square and symmetrised if ``symmetry_rtol`` is given."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real 2-D array; got {value!r}") from None
    if array.ndim != 2 or array.size == 0 or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be a nonempty, finite 2-D array; got {array!r}")
    if symmetry_rtol is None:
        return array
    if array.shape[0] != array.shape[1]:
        raise ValueError(f"{name} must be square; got shape {array.shape}")
    asymmetry, allowed = np.max(np.abs(array - array.T)), symmetry_rtol * np.max(np.abs(array))
    if asymmetry > allowed:
        raise ValueError(
            f"{name} must be symmetric: max|A - A.T| = {asymmetry:.3g} exceeds "
            f"symmetry_rtol * max|A| = {allowed:.3g}"
        )
    return 0.5 * (array + array.T)


def _frozen(values: np.ndarray) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.flags.writeable = False
    return array


def normalise_shapes(shapes: np.ndarray) -> np.ndarray:
    """Scale each column so that its largest-magnitude entry is +1 (the convention of Table 1).

    Parameters
    ----------
    shapes : ndarray, shape (n, k)
        Mode shapes as columns; no column may be zero.

    Returns
    -------
    ndarray, shape (n, k)
        The normalised columns. Ties in magnitude go to the first coordinate.
    """
    array = _as_matrix(shapes, "shapes")
    rows = np.argmax(np.abs(array), axis=0)
    pivots = array[rows, np.arange(array.shape[1])]
    if np.any(pivots == 0.0):
        raise ValueError("shapes has a zero column; a mode shape must have a nonzero entry")
    return array / pivots


@dataclass(frozen=True)
class ModalTable:
    """Natural frequencies and normalised mode shapes, one column per mode (the layout of Table 1).

    Attributes
    ----------
    frequencies_hz : ndarray, shape (k,)
        Natural frequencies in Hz, descending like Table 1.
    shapes : ndarray, shape (n, k)
        One column per mode, stored normalised so that its largest-magnitude entry is +1.
    coordinates : tuple of str
        Names of the n rows.
    source : str
        Where the numbers come from.
    """

    frequencies_hz: np.ndarray
    shapes: np.ndarray
    coordinates: tuple[str, ...]
    source: str

    def __post_init__(self) -> None:
        frequencies_hz = np.asarray(self.frequencies_hz, dtype=float)
        valid = np.all(np.isfinite(frequencies_hz) & (frequencies_hz > 0))
        if frequencies_hz.ndim != 1 or not valid or np.any(np.diff(frequencies_hz) > 0):
            raise ValueError(
                "frequencies_hz must be positive finite values in descending order (like Table 1); "
                f"got {frequencies_hz!r}"
            )
        shapes = normalise_shapes(self.shapes)
        if shapes.shape != (len(self.coordinates), frequencies_hz.size):
            raise ValueError(
                f"shapes must have shape (len(coordinates), len(frequencies_hz)) = "
                f"({len(self.coordinates)}, {frequencies_hz.size}); got {shapes.shape}"
            )
        object.__setattr__(self, "frequencies_hz", _frozen(frequencies_hz))
        object.__setattr__(self, "shapes", _frozen(shapes))

    @classmethod
    def from_result(
        cls, result: ModalResult, reading: str, coordinates: tuple[str, ...], source: str
    ) -> ModalTable:
        """Table of a model's own modes (``reading`` selects M φ or φ), e.g. a synthetic target."""
        return cls(result.frequencies_hz, result.shapes(reading), coordinates, source)


#: Paper Table 1 (section 2.2): empty-bucket loader (bucket load 340 kg per the project brief),
#: rows (x_H, y_H, θ1, θ2) in m and rad, columns ω1..ω4 in descending frequency. Transcribed from
#: reference/000_a84aeb4c1d6a3ae9.txt; per errata 7 the columns are momentum shapes M φ.
TABLE_1 = ModalTable(
    frequencies_hz=np.array([13.4, 5.6, 4.8, 2.9]),
    shapes=np.array(
        [
            [0.22, 1.00, 0.43, -0.78],
            [0.22, -0.65, 0.89, -0.10],
            [1.00, -0.08, -0.39, 0.39],
            [-0.70, 0.37, 1.00, 1.00],
        ]
    ),
    coordinates=("x_H", "y_H", "theta_1", "theta_2"),
    source="Williamson, Lee, Ivantysynova (2009), Int. J. Fluid Power, Table 1",
)


@dataclass(frozen=True)
class ModalResult:
    """Result of :func:`modal_analysis`, modes sorted by descending frequency like Table 1.

    Attributes
    ----------
    frequencies_hz : ndarray, shape (n,)
        Undamped natural frequencies ω/(2π) in Hz (Eq. 29).
    displacement_shapes : ndarray, shape (n, n)
        Right eigenvectors φ of K φ = ω² M φ (Eq. 27), columns normalised like Table 1.
    momentum_shapes : ndarray, shape (n, n)
        Left eigenvectors M φ (eigenvectors of K M⁻¹, erratum 7), normalised like Table 1.
    modal_masses : ndarray, shape (n,)
        φᵀ M φ of the normalised displacement shapes.
    """

    frequencies_hz: np.ndarray
    displacement_shapes: np.ndarray
    momentum_shapes: np.ndarray
    modal_masses: np.ndarray

    @property
    def angular_frequencies_rad_s(self) -> np.ndarray:
        """Natural angular frequencies ω in rad/s."""
        return 2.0 * np.pi * self.frequencies_hz

    def shapes(self, reading: str) -> np.ndarray:
        """Shapes for ``reading`` ``"momentum"`` (M φ) or ``"displacement"`` (φ)."""
        check_reading(reading)
        return self.momentum_shapes if reading == "momentum" else self.displacement_shapes


def modal_analysis(
    mass_matrix: np.ndarray,
    stiffness_matrix: np.ndarray,
    *,
    symmetry_rtol: float = 1e-8,
) -> ModalResult:
    """Undamped natural frequencies and mode shapes of M p̈ + K p = 0 (Eq. 27-29).

    Parameters
    ----------
    mass_matrix : array_like, shape (n, n)
        Symmetric positive definite mass matrix M.
    stiffness_matrix : array_like, shape (n, n)
        Symmetric stiffness matrix K; K must be positive semi-definite relative to M (no ω² < 0).
    symmetry_rtol : float
        Allowed asymmetry max|A − Aᵀ| relative to max|A|; the symmetric part is used.

    Returns
    -------
    ModalResult
        Frequencies in Hz (descending), displacement shapes φ and momentum shapes M φ.

    Raises
    ------
    ValueError
        If a matrix is not square, finite or symmetric, the shapes differ, M is not positive
        definite or K has a negative eigenvalue ω².

    Notes
    -----
    The symmetric-definite problem is solved with ``scipy.linalg.eigh(K, M)``, so φ is M-orthogonal.
    Eq. 29 writes ``eig(-M⁻¹K)``: with K printed as −K (erratum 5) that is the same problem.
    """
    mass = _as_matrix(mass_matrix, "mass_matrix", symmetry_rtol)
    stiffness = _as_matrix(stiffness_matrix, "stiffness_matrix", symmetry_rtol)
    if mass.shape != stiffness.shape:
        raise ValueError(
            f"stiffness_matrix has shape {stiffness.shape}; it must match mass_matrix {mass.shape}"
        )
    try:
        scipy.linalg.cholesky(mass, lower=True)
    except np.linalg.LinAlgError:
        smallest = float(np.linalg.eigvalsh(mass)[0])
        raise ValueError(
            f"mass_matrix must be positive definite; its smallest eigenvalue is {smallest:.6g}"
        ) from None
    eigenvalues, vectors = scipy.linalg.eigh(stiffness, mass)
    floor = -1e-10 * max(np.max(np.abs(eigenvalues)), np.max(np.abs(stiffness)) / np.max(mass))
    if eigenvalues[0] < floor:
        raise ValueError(
            f"stiffness_matrix gives a negative eigenvalue ω² = {eigenvalues[0]:.6g} (rad/s)²; "
            "K must be positive semi-definite for real natural frequencies"
        )
    order = np.argsort(-eigenvalues, kind="stable")
    omega_squared = np.clip(eigenvalues[order], 0.0, None)
    displacement = normalise_shapes(vectors[:, order])
    momentum = normalise_shapes(mass @ displacement)
    modal_masses = np.einsum("ij,ik,kj->j", displacement, mass, displacement)
    return ModalResult(
        frequencies_hz=_frozen(np.sqrt(omega_squared) / (2.0 * np.pi)),
        displacement_shapes=_frozen(displacement),
        momentum_shapes=_frozen(momentum),
        modal_masses=_frozen(modal_masses),
    )


def modal_assurance_criterion(a: np.ndarray, b: np.ndarray) -> float | np.ndarray:
    """Modal assurance criterion MAC = |aᴴ b|² / ((aᴴ a)(bᴴ b)).

    Parameters
    ----------
    a, b : array_like, shape (n,) or (n, k) and (n, l)
        Two vectors, or two sets of column vectors.

    Returns
    -------
    float or ndarray, shape (k, l)
        MAC in [0, 1]: 1 for parallel vectors, 0 for orthogonal ones; for two 2-D inputs the matrix
        of MAC values between their columns.
    """
    first, second = np.asarray(a), np.asarray(b)
    if first.ndim not in (1, 2) or first.ndim != second.ndim or first.shape[0] != second.shape[0]:
        raise ValueError(
            "a and b must both be vectors or both matrices of equal length; "
            f"got shapes {first.shape} and {second.shape}"
        )
    for name, array in (("a", first), ("b", second)):
        if array.size == 0 or not np.all(np.isfinite(array)):
            raise ValueError(f"{name} must be finite and nonempty; got {array!r}")
        if np.any(np.linalg.norm(array.reshape(array.shape[0], -1), axis=0) == 0.0):
            raise ValueError(f"{name} contains a zero vector; MAC is undefined for it")
    first_2d, second_2d = first.reshape(first.shape[0], -1), second.reshape(second.shape[0], -1)
    cross = np.abs(first_2d.conj().T @ second_2d) ** 2
    scale = np.outer(np.sum(np.abs(first_2d) ** 2, axis=0), np.sum(np.abs(second_2d) ** 2, axis=0))
    mac = np.clip(cross / scale, 0.0, 1.0)
    return float(mac[0, 0]) if first.ndim == 1 else mac


@dataclass(frozen=True)
class ModalComparison:
    """Mode-by-mode comparison of a :class:`ModalResult` with a table (modes paired in order).

    Attributes
    ----------
    reading : str
        ``"momentum"`` or ``"displacement"``: which model shapes were compared.
    frequencies_hz, table_frequencies_hz : ndarray, shape (k,)
        Model and table frequencies in Hz.
    frequency_errors_percent : ndarray, shape (k,)
        100 (f_model − f_table) / f_table.
    mac : ndarray, shape (k,)
        MAC between each model shape and the table column of the same mode.
    """

    reading: str
    frequencies_hz: np.ndarray
    table_frequencies_hz: np.ndarray
    frequency_errors_percent: np.ndarray
    mac: np.ndarray

    def meets(self, frequency_tolerance_percent: float = 1.0, mac_minimum: float = 0.99) -> bool:
        """True if every |frequency error| ≤ tolerance and every MAC ≥ ``mac_minimum``."""
        return bool(
            np.all(np.abs(self.frequency_errors_percent) <= frequency_tolerance_percent)
            and np.all(self.mac >= mac_minimum)
        )


def compare_with_table(result: ModalResult, table: ModalTable, reading: str) -> ModalComparison:
    """Compare ``result`` with ``table``, pairing the i-th model mode with the table's i-th column.

    Parameters
    ----------
    result : ModalResult
        Model modes, descending frequency.
    table : ModalTable
        Reference modes in the same order and coordinates.
    reading : {"momentum", "displacement"}
        Compare the table with M φ (erratum 7) or with φ.

    Returns
    -------
    ModalComparison
    """
    check_reading(reading)
    model_shapes = result.shapes(reading)
    if model_shapes.shape != table.shapes.shape:
        raise ValueError(
            f"result has {model_shapes.shape} shapes but the table has {table.shapes.shape}; "
            "they must match"
        )
    errors = 100.0 * (result.frequencies_hz / table.frequencies_hz - 1.0)
    mac = np.diag(modal_assurance_criterion(model_shapes, table.shapes))
    return ModalComparison(
        reading=reading,
        frequencies_hz=result.frequencies_hz,
        table_frequencies_hz=table.frequencies_hz,
        frequency_errors_percent=_frozen(errors),
        mac=_frozen(mac),
    )


def compare_with_table_1(result: ModalResult, reading: str = "momentum") -> ModalComparison:
    """Compare a 4-DOF ``result`` with the paper's Table 1 (see :func:`compare_with_table`)."""
    return compare_with_table(result, TABLE_1, reading)
