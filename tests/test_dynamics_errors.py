"""Bad arguments to the runtime wrappers raise a ValueError naming the argument and the rule."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.dynamics import LoaderDynamics


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
        ({"disturbance": ["a", 1, 2]}, r"disturbance must be numeric with shape \(3,\)"),
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
    with pytest.raises(ValueError, match=r"k_Ay must be finite; got \[nan\]"):
        LoaderDynamics(paper_layout)


def test_static_loads_are_required_without_equilibrium(paper_layout: dict[str, float]) -> None:
    with pytest.raises(ValueError, match=r"missing model parameters \['F_Ay0', 'F_By0'\]"):
        LoaderDynamics(paper_layout, equilibrium=False)


def test_mass_matrix_not_positive_definite_is_rejected(paper_layout: dict[str, float]) -> None:
    with pytest.raises(ValueError, match="mass matrix at p = 0 is not positive definite"):
        LoaderDynamics(paper_layout | {"J_2": -5000.0})


def test_unknown_parameter_name_lookup(model: LoaderDynamics) -> None:
    with pytest.raises(ValueError, match="unknown model parameter 'mass'"):
        model.parameter("mass")
