"""Bad arguments to the runtime wrappers raise a ValueError naming the argument and the rule."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.vehicle.dynamics import LoaderDynamics


@pytest.fixture
def model(paper_layout: dict[str, float]) -> LoaderDynamics:
    return LoaderDynamics(paper_layout)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"p": [0.0, 0.0, 0.0]}, r"p must have shape \(4,\); got shape \(3,\)"),
        ({"p": [0.0, np.nan, 0.0, 0.0]}, r"p must be finite; got \[0.0, nan, 0.0, 0.0\]"),
        ({"pd": np.zeros((4, 1))}, r"pd must have shape \(4,\); got shape \(4, 1\)"),
        ({"force_N": np.inf}, r"force_N must be finite; got \[inf\]"),
        ({"road_m": [0.0, 0.0]}, r"road_m must have shape \(4,\)"),
        (
            {"disturbance": ["a", 1, 2]},
            r"disturbance must be real numbers with shape \(3,\); got \['a', 1, 2\]",
        ),
    ],
)
def test_forward_dynamics_rejects_bad_arguments(
    model: LoaderDynamics, kwargs: dict, message: str
) -> None:
    arguments = {"p": np.zeros(4), "pd": np.zeros(4)} | kwargs
    with pytest.raises(ValueError, match=message):
        model.forward_dynamics(**arguments)
    with pytest.raises(ValueError, match=message):
        model.linearise(**arguments)


def test_mass_matrix_rejects_wrong_shape(model: LoaderDynamics) -> None:
    with pytest.raises(ValueError, match=r"p must have shape \(4,\); got shape \(2, 2\)"):
        model.mass_matrix(np.zeros((2, 2)))


def test_unknown_missing_and_nonfinite_parameters(paper_layout: dict[str, float]) -> None:
    with pytest.raises(ValueError, match=r"unknown model parameters \['m_3'\]"):
        LoaderDynamics(paper_layout | {"m_3": 1.0})
    del paper_layout["k_Ay"]
    with pytest.raises(ValueError, match=r"missing model parameters \['k_Ay'\]"):
        LoaderDynamics(paper_layout)
    paper_layout["k_Ay"] = float("nan")
    with pytest.raises(ValueError, match=r"model parameter k_Ay must be finite; got nan"):
        LoaderDynamics(paper_layout)


def test_static_loads_are_required_without_equilibrium(paper_layout: dict[str, float]) -> None:
    with pytest.raises(ValueError, match=r"missing model parameters \['F_Ay0', 'F_By0'\]"):
        LoaderDynamics(paper_layout, equilibrium=False)


def test_mass_matrix_not_positive_definite_is_rejected(paper_layout: dict[str, float]) -> None:
    with pytest.raises(ValueError, match="mass matrix at p = 0 is not positive definite"):
        LoaderDynamics(paper_layout | {"J_2": -5000.0}, check_ranges=False)
    with pytest.raises(ValueError, match=r"model parameter J_2 = -5000\.0 is out of range"):
        LoaderDynamics(paper_layout | {"J_2": -5000.0})


def test_unknown_parameter_name_lookup(model: LoaderDynamics) -> None:
    with pytest.raises(ValueError, match="unknown model parameter 'mass'"):
        model.parameter("mass")


TYPES = [
    ("a string", "0.0", r"p must be real numbers with shape \(4,\); got the string '0\.0'"),
    ("booleans", [True, False, False, False], r"p must be real numbers .*, not booleans"),
    ("complex", np.array([1j, 0, 0, 0]), r"p must be real numbers .*; got complex values"),
    ("huge int", [10**400, 0, 0, 0], r"p must be finite; got an integer too large for a float"),
    ("objects", [None, 0, 0, 0], r"p must be real numbers with shape \(4,\); got \[None"),
    ("1e308", [1e308, 0, 0, 0], r"p = \[1e\+308, 0\.0, 0\.0, 0\.0\] is implausible; allowed: "),
    ("angle", [0, 0, 4.0, 0], r"\|theta_1\|, \|theta_2\| <= pi rad"),
]


@pytest.mark.parametrize(("kind", "value", "message"), TYPES, ids=[t[0] for t in TYPES])
def test_arguments_must_be_real_plausible_numbers(
    model: LoaderDynamics, kind: str, value: object, message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        model.forward_dynamics(value, np.zeros(4))
    with pytest.raises(ValueError, match=message):
        model.mass_matrix(value)


def test_large_but_plausible_arguments_give_finite_results(model: LoaderDynamics) -> None:
    accelerations = model.forward_dynamics(
        [1e4, 0.0, 0.0, 0.0], np.zeros(4), road_m=[1e4, 0, 1e4, 0]
    )
    assert np.all(np.isfinite(accelerations))
    with pytest.raises(
        ValueError, match=r"force_N = \[1e\+30\] is implausible; allowed: .* 1e\+08 N"
    ):
        model.forward_dynamics(np.zeros(4), np.zeros(4), force_N=1e30)


CONSTRUCTOR = [
    ({"k_Ay": -1.0e6}, r"model parameter k_Ay = -1000000\.0 is out of range; allowed: \[50000"),
    ({"J_1": 0.0}, r"model parameter J_1 = 0\.0 is out of range; allowed: \[20, 500000\]"),
    ({"m_1": 1e-300}, r"model parameter m_1 = 1e-300 is out of range; allowed: \[250, 45000\] \("),
    ({"A_x": 1e30}, r"model parameter A_x = 1e\+30 is out of range; allowed: \[-10, 10\]"),
    ({"m_2": "600"}, r"model parameter m_2: value '600' is not a number; allowed: .*, not a str"),
    ({"g": True}, r"model parameter g: value True is not a number; .*, not a boolean"),
    (
        {"k_Ax": 1e6 + 1j},
        r"model parameter k_Ax: value \(1000000\+1j\) is not a number; .*, not a c",
    ),
]


@pytest.mark.parametrize(("change", "message"), CONSTRUCTOR)
def test_constructor_applies_the_parameter_file_rules(
    paper_layout: dict[str, float], change: dict, message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        LoaderDynamics(paper_layout | change)


def test_constructor_refuses_coincident_cylinder_points(paper_layout: dict[str, float]) -> None:
    change = {"E_x": paper_layout["C_x"], "E_y": paper_layout["C_y"] + 1e-4}
    with pytest.raises(ValueError, match=r"degenerate geometry: C = .* and E = .* coincide"):
        LoaderDynamics(paper_layout | change)


def test_constructor_and_factory_name_wrong_argument_types() -> None:
    with pytest.raises(ValueError, match=r"parameter_values must be a mapping .*; got list"):
        LoaderDynamics([1.0, 2.0])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"equilibrium must be True or False; got 'yes'"):
        LoaderDynamics({}, equilibrium="yes")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"loader must be a LoaderParameters, a path .*; got 3"):
        LoaderDynamics.from_parameters(3)
    with pytest.raises(ValueError, match=r"load must be a BucketLoad, a path .*; got True"):
        LoaderDynamics.from_parameters(None, True)


def test_a_boolean_inside_a_list_of_floats_is_refused(model: LoaderDynamics) -> None:
    # numpy would turn [True, 0.0, ...] into [1.0, 0.0, ...] silently
    with pytest.raises(ValueError, match=r"p must be real numbers with shape \(4,\), not booleans"):
        model.forward_dynamics([True, 0.0, 0.0, 0.0], np.zeros(4))
    with pytest.raises(ValueError, match=r"road_m must be real .*; got complex values"):
        model.forward_dynamics(np.zeros(4), np.zeros(4), road_m=[1j, 0.0, 0.0, 0.0])
