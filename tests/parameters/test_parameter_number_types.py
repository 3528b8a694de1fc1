"""One number where a number is expected (issue 19, item 6).

``LoaderDynamics`` and the parameter sets accept Python ints and floats and NumPy scalars; an
array (also a 0-d or one-element one), a list, a tuple, a boolean or a string is refused naming
the parameter, the value and what is allowed, on every way a value enters: the flat mapping of
``LoaderDynamics``, a TOML file, ``parameters.replace``, and the dataclasses built in code.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

from loader_model import cli
from loader_model.parameters.sets import default_loader, load_loader, replace
from loader_model.vehicle.dynamics import LoaderDynamics
from tests.conftest import PAPER_LAYOUT
from tests.mutations import LOADER_TEXT, mutate_leaf

ALLOWED = r"allowed: a real number \(int, float or NumPy scalar\), not "
#: (value, how its kind is named) of values that are not one number.
NOT_NUMBERS = [
    ([2700.0], "a list"),
    (np.array([2700.0]), r"an array of shape \(1,\)"),
    (np.array(2700.0), r"an array of shape \(\)"),
    ((2700.0,), "a tuple"),
    (True, "a boolean"),
    (np.bool_(True), "a boolean"),
    ("2700", "a string"),
    (2700.0 + 0j, "a complex number"),
    (None, "None"),
]
NUMBERS = [2700, 2700.0, np.float64(2700.0), np.float32(2700.0), np.int64(2700)]


def _shown(value: object) -> str:
    return re.escape(repr(value.item() if isinstance(value, np.generic) else value))


@pytest.mark.parametrize(("value", "kind"), NOT_NUMBERS)
def test_loader_dynamics_refuses_what_is_not_one_number(value: object, kind: str) -> None:
    with pytest.raises(
        ValueError,
        match=rf"model parameter m_1: value {_shown(value)} is not a number; {ALLOWED}{kind}$",
    ):
        LoaderDynamics(PAPER_LAYOUT | {"m_1": value})


@pytest.mark.parametrize("value", NUMBERS)
def test_loader_dynamics_accepts_ints_floats_and_numpy_scalars(value: object) -> None:
    model = LoaderDynamics(PAPER_LAYOUT | {"m_1": value})
    reference = LoaderDynamics(PAPER_LAYOUT | {"m_1": 2700.0})
    np.testing.assert_array_equal(model.parameters, reference.parameters)


@pytest.mark.parametrize(("value", "kind"), NOT_NUMBERS)
def test_replace_refuses_what_is_not_one_number(value: object, kind: str) -> None:
    with pytest.raises(
        ValueError, match=rf"chassis\.mass: value {_shown(value)} is not a number; {ALLOWED}{kind}$"
    ):
        replace(default_loader(), {"chassis.mass": value})


@pytest.mark.parametrize("value", NUMBERS)
def test_replace_stores_numbers_as_python_floats(value: object) -> None:
    loader = replace(default_loader(), {"chassis.mass": value, "cylinders.count": np.int64(2)})
    assert type(loader.chassis.mass) is float and loader.chassis.mass == 2700.0
    assert type(loader.cylinders.count) is int and loader.cylinders.count == 2


def test_points_take_a_sequence_of_two_numbers() -> None:
    point = default_loader().geometry.S
    moved = replace(default_loader(), {"geometry.S": np.array(point)})
    assert moved.geometry.S == point and type(moved.geometry.S[0]) is float
    with pytest.raises(
        ValueError, match=r"geometry\.S\[1\]: value True is not a number; .*boolean"
    ):
        replace(default_loader(), {"geometry.S": [point[0], True]})
    with pytest.raises(ValueError, match=r"geometry\.S: value .* is not a list of 2 numbers"):
        replace(default_loader(), {"geometry.S": np.array([point])})


def test_dataclasses_built_in_code_check_their_values() -> None:
    loader = default_loader()
    with pytest.raises(
        ValueError,
        match=rf"ChassisParameters\.mass: value \[2700\.0\] is not a number; {ALLOWED}a list$",
    ):
        dataclasses.replace(loader.chassis, mass=[2700.0])
    with pytest.raises(ValueError, match=r"ChassisParameters\.mass: value '2700' is not a number"):
        dataclasses.replace(loader.chassis, mass="2700")
    with pytest.raises(
        ValueError, match=r"CylinderParameters\.count: value 2\.0 is not an integer; allowed: an"
    ):
        dataclasses.replace(loader.cylinders, count=2.0)
    with pytest.raises(
        ValueError, match=r"Geometry\.A: value \(0\.6,\) is not a sequence of 2 numbers; allowed:"
    ):
        dataclasses.replace(loader.geometry, A=(0.6,))
    chassis = dataclasses.replace(loader.chassis, mass=np.float64(2700.0))
    assert type(chassis.mass) is float
    geometry = dataclasses.replace(loader.geometry, A=np.array(loader.geometry.A))
    assert geometry.A == loader.geometry.A
    built = dataclasses.replace(loader, chassis=chassis, geometry=geometry)
    model = LoaderDynamics.from_parameters(built)
    assert model.parameter("m_1") == 2700.0


def test_toml_array_where_a_number_is_expected(tmp_path: Path) -> None:
    path = tmp_path / "loader.toml"
    path.write_text(mutate_leaf(LOADER_TEXT, "chassis.mass", "[2700.0]"), encoding="utf-8")
    with pytest.raises(
        ValueError,
        match=rf"loader\.toml: chassis\.mass: value \[2700\.0\] is not a number; {ALLOWED}a list$",
    ):
        load_loader(path)


def test_command_reports_a_toml_array_without_a_traceback(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(cli, "COMMANDS", {"model": "loader_model.commands.model_command"})
    path = tmp_path / "loader.toml"
    path.write_text(mutate_leaf(LOADER_TEXT, "tyres.front.k_y", "[1.0e6]"), encoding="utf-8")
    assert cli.main(["model", "--params", str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("loader-model model: error: ")
    assert "tyres.front.k_y: value [1000000.0] is not a number" in err
    assert "Traceback" not in err
