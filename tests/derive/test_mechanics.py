"""Mass matrix and stiffness of the generated model against independent references.

References: the mass matrix Σ m JᵀJ + diag(J) with the point Jacobians taken by central finite
differences of the generated positions (a different route than the symbolic one), and the paper's
Eq. 32-34 written with its abs()-based distances for a layout that fits its sign assumptions, with
DESIGN.md errata 5 applied to K.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import loader_model_generated as generated
from loader_model.vehicle.dynamics import PARAMETER_NAMES, LoaderDynamics

MASS = generated.function("mass_matrix")
POSITIONS = generated.function("point_positions")
POINT_ORDER = "ABCDEGHNS"

coordinate = st.floats(-2.0, 2.0)
angle = st.floats(-np.pi, np.pi)


@st.composite
def parameter_vectors(draw: st.DrawFn) -> np.ndarray:
    values = {name: draw(coordinate) for name in PARAMETER_NAMES}
    for name in ("m_1", "m_2"):
        values[name] = draw(st.floats(1.0, 1.0e4))
    for name in ("J_1", "J_2"):
        values[name] = draw(st.floats(0.1, 1.0e4))
    return np.array([values[name] for name in PARAMETER_NAMES])


def _position(p: np.ndarray, params: np.ndarray, letter: str) -> np.ndarray:
    return np.asarray(POSITIONS(p, params)[POINT_ORDER.index(letter)]).ravel()


def _jacobian_fd(p: np.ndarray, params: np.ndarray, letter: str, step: float = 1e-6) -> np.ndarray:
    columns = []
    for k in range(4):
        dp = np.zeros(4)
        dp[k] = step
        plus, minus = _position(p + dp, params, letter), _position(p - dp, params, letter)
        columns.append((plus - minus) / (2 * step))
    return np.column_stack(columns)


@settings(max_examples=60, deadline=None)
@given(p=st.tuples(coordinate, coordinate, angle, angle).map(np.array), params=parameter_vectors())
def test_mass_matrix_is_symmetric_positive_definite(p: np.ndarray, params: np.ndarray) -> None:
    mass = np.asarray(MASS(p, params))
    np.testing.assert_allclose(mass, mass.T, rtol=1e-12, atol=1e-9)
    assert np.linalg.eigvalsh(mass).min() > 0.0


@settings(max_examples=40, deadline=None)
@given(p=st.tuples(coordinate, coordinate, angle, angle).map(np.array), params=parameter_vectors())
def test_mass_matrix_equals_kinetic_energy_of_finite_difference_jacobians(
    p: np.ndarray, params: np.ndarray
) -> None:
    named = dict(zip(PARAMETER_NAMES, params, strict=True))
    jac_h, jac_g = _jacobian_fd(p, params, "H"), _jacobian_fd(p, params, "G")
    reference = named["m_1"] * jac_h.T @ jac_h + named["m_2"] * jac_g.T @ jac_g
    reference += np.diag([0.0, 0.0, named["J_1"], named["J_2"]])
    mass = np.asarray(MASS(p, params))
    # central differences of smooth positions: error ~1e-10 relative to the largest entry
    np.testing.assert_allclose(mass, reference, rtol=1e-6, atol=1e-6 * np.abs(reference).max())


def _paper_distances(values: dict[str, float]) -> dict[str, float]:
    """The paper's abs()-based distances (Eq. 8-9) for the layout of its sign assumptions."""
    v = values
    r = {}
    for letter in "ABCD":
        r[f"{letter}Hx"], r[f"{letter}Hy"] = abs(v[f"{letter}_x"]), abs(v[f"{letter}_y"])
    r["DGx"], r["DGy"] = abs(v["G_x"] - v["D_x"]), abs(v["G_y"] - v["D_y"])
    return r


def test_layout_of_fixture_matches_paper_sign_assumptions(paper_layout: dict[str, float]) -> None:
    v = paper_layout
    assert (
        v["A_x"] > 0 > v["A_y"] and v["B_x"] < 0 and v["B_y"] < 0
    )  # A ahead/below, B behind/below
    assert v["C_x"] < 0 < v["C_y"] and v["D_x"] < 0 < v["D_y"]  # C, D behind and above H
    assert v["G_x"] > v["D_x"] and v["G_y"] < v["D_y"]  # G ahead of and below D
    assert v["E_x"] < v["G_x"] and v["E_y"] > v["G_y"]  # E behind and above G


def test_linearised_mass_matrix_equals_eq_32(paper_layout: dict[str, float]) -> None:
    model = LoaderDynamics(paper_layout)
    v, r = paper_layout, _paper_distances(paper_layout)
    m1, m2, j1, j2 = v["m_1"], v["m_2"], v["J_1"], v["J_2"]
    coupling = -(r["DHy"] * r["DGy"] + r["DHx"] * r["DGx"]) * m2
    eq_32 = np.array(
        [
            [m1 + m2, 0.0, -r["DHy"] * m2, r["DGy"] * m2],
            [0.0, m1 + m2, -r["DHx"] * m2, r["DGx"] * m2],
            [-r["DHy"] * m2, -r["DHx"] * m2, (r["DHy"] ** 2 + r["DHx"] ** 2) * m2 + j1, coupling],
            [r["DGy"] * m2, r["DGx"] * m2, coupling, (r["DGy"] ** 2 + r["DGx"] ** 2) * m2 + j2],
        ]
    )
    np.testing.assert_allclose(model.mass_matrix(np.zeros(4)), eq_32, rtol=1e-12)


def _stiffness(model: LoaderDynamics) -> np.ndarray:
    """K of M p̈ + K p = 0 (Eq. 27) from the linearisation: K = −M ∂p̈/∂p."""
    linear = model.linearise()
    acceleration_rows, position_columns = [1, 3, 5, 7], [0, 2, 4, 6]
    return -model.mass_matrix(np.zeros(4)) @ linear.A[np.ix_(acceleration_rows, position_columns)]


def test_linearised_tyre_stiffness_has_structure_of_eq_33_34(
    paper_layout: dict[str, float],
) -> None:
    """Zero gravity (as the paper): K is the tyres' only. Eq. 33-34 print −K (errata 5)."""
    paper_layout["g"] = 0.0
    paper_layout["k_Bx"], paper_layout["k_By"] = paper_layout["k_Ax"], paper_layout["k_Ay"]
    k_tx, k_ty = paper_layout["k_Ax"], paper_layout["k_Ay"]
    r = _paper_distances(paper_layout)
    k33 = -(r["AHy"] ** 2 + r["BHy"] ** 2) * k_tx - (r["AHx"] ** 2 + r["BHx"] ** 2) * k_ty
    printed = np.array(
        [
            [-2 * k_tx, 0.0, -(r["AHy"] + r["BHy"]) * k_tx, 0.0],
            [0.0, -2 * k_ty, -(r["AHx"] - r["BHx"]) * k_ty, 0.0],
            [-(r["AHy"] + r["BHy"]) * k_tx, -(r["AHx"] - r["BHx"]) * k_ty, k33, 0.0],
            [0.0, 0.0, 0.0, 0.0],
        ]
    )
    stiffness = _stiffness(LoaderDynamics(paper_layout))
    np.testing.assert_allclose(stiffness, -printed, rtol=1e-9, atol=1e-6)


def test_cylinder_spring_adds_keq_lever_squared(paper_layout: dict[str, float]) -> None:
    """Errata 5: the cylinder stiffness is k_eq (dx_cyl/dφ)² on [[1, −1], [−1, 1]] over (θ1, θ2),
    with dx_cyl/dφ from the geometry (independent numpy computation below)."""
    paper_layout["g"] = 0.0
    model = LoaderDynamics(paper_layout)
    c, d, e = (np.array([paper_layout[f"{k}_x"], paper_layout[f"{k}_y"]]) for k in "CDE")
    unit = (e - c) / np.linalg.norm(e - c)
    lever = unit @ np.array([-(e - d)[1], (e - d)[0]])
    generated_lever = model.cylinder_kinematics(np.zeros(4))["dx_cyl_dphi"]
    np.testing.assert_allclose(generated_lever, lever, rtol=1e-12)
    k_eq = 2.0e7
    linear = model.linearise()
    # the spring F_act = −k_eq Δx_cyl closes the loop u = −k_eq (dx/dφ)(θ2 − θ1)
    gain = np.zeros((1, 8))
    gain[0, 4], gain[0, 6] = -k_eq * lever, k_eq * lever
    closed = linear.A - linear.B @ gain
    mass = model.mass_matrix(np.zeros(4))
    stiffness = -mass @ closed[np.ix_([1, 3, 5, 7], [0, 2, 4, 6])]
    expected = _stiffness(model)
    expected[2:, 2:] += k_eq * lever**2 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    np.testing.assert_allclose(stiffness, expected, rtol=1e-9, atol=1e-3)
