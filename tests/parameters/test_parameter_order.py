"""The parameter files map onto exactly the generated model's parameters (names owned by derive)."""

from __future__ import annotations

import numpy as np
import pytest

import loader_model_generated as generated
from loader_model import parameters
from loader_model.vehicle.dynamics import LoaderDynamics

STATIC_LOADS = {"F_Ay0", "F_By0"}


def test_parameter_files_cover_generated_parameters_exactly() -> None:
    assert set(parameters.MODEL_PARAMETER_NAMES) == set(generated.PARAMETER_NAMES) - STATIC_LOADS
    values = parameters.model_parameter_values(
        parameters.default_loader(), parameters.bucket_load("empty")
    )
    assert set(values) == set(generated.PARAMETER_NAMES) - STATIC_LOADS


def test_from_parameters_places_each_value_at_its_generated_index() -> None:
    loader, load = parameters.default_loader(), parameters.bucket_load("full")
    values = parameters.model_parameter_values(loader, load)
    model = LoaderDynamics.from_parameters(loader, load)
    for name, value in values.items():
        assert model.parameters[generated.PARAMETER_NAMES.index(name)] == value, name
    assert model.parameter("m_2") == pytest.approx(loader.boom.mass + load.mass, rel=1e-12)
    assert model.parameter("k_Ay") == loader.tyres.front.k_y
    assert model.parameter("k_By") == loader.tyres.rear.k_y


def test_default_loader_rests_on_both_tyres_with_positive_loads() -> None:
    for case in parameters.LOAD_CASES:
        model = LoaderDynamics.from_parameters(None, case)
        assert model.parameter("F_Ay0") > 0 and model.parameter("F_By0") > 0
        assert model.static_cylinder_force_N > 0  # the cylinders hold the boom up
        np.testing.assert_allclose(model.forward_dynamics(np.zeros(4), np.zeros(4)), 0.0, atol=1e-9)


def test_unknown_load_case_is_rejected() -> None:
    with pytest.raises(
        ValueError, match=r"load 'heavy' is neither a load case \['empty', 'full'\]"
    ):
        LoaderDynamics.from_parameters(None, "heavy")


def test_every_model_parameter_has_a_range() -> None:
    """The runtime API applies the parameter files' ranges to every generated parameter."""
    from loader_model.parameters.model_checks import MODEL_PARAMETER_RANGES

    assert set(MODEL_PARAMETER_RANGES) == set(generated.PARAMETER_NAMES)
