"""Machine descriptions: the schema, the skid-steer's parameter order, and clear errors."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

import loader_model_generated as generated
from derive.description import (
    MACHINES_DIR,
    DescriptionError,
    available_machines,
    load_machine,
)
from derive.description_values import check_values

SKID_STEER = (MACHINES_DIR / "skid_steer.toml").read_text(encoding="utf-8")


@pytest.mark.parametrize("machine", available_machines())
def test_descriptions_follow_the_json_schema(machine: str) -> None:
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((MACHINES_DIR.parent / "machine.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(tomllib.loads((MACHINES_DIR / f"{machine}.toml").read_text()), schema)


def test_skid_steer_description_gives_the_generated_orders_and_units() -> None:
    machine = load_machine("skid_steer")
    assert tuple(item.name for item in machine.parameters) == generated.PARAMETER_NAMES
    assert {item.name: item.unit for item in machine.parameters} == generated.PARAMETER_UNITS
    assert {i.name: i.description for i in machine.parameters} == generated.PARAMETER_DESCRIPTIONS


def test_default_loader_lies_within_the_description_ranges() -> None:
    from loader_model import parameters
    from loader_model.vehicle.dynamics import LoaderDynamics

    ranges = {item.name: item.range for item in load_machine("skid_steer").parameters}
    for case in parameters.LOAD_CASES:
        values = LoaderDynamics.from_parameters(None, case).parameters
        for name, value in zip(generated.PARAMETER_NAMES, np.asarray(values).ravel(), strict=True):
            low, high = ranges[name]
            assert low <= value <= high, (case, name, value)


def _broken(tmp_path: Path, old: str, new: str, text: str = SKID_STEER) -> Path:
    assert old in text, old
    path = tmp_path / "broken.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ('parent = "chassis"', 'parent = "chasis"', r"bodies\.boom\.parent: unknown parent body 'chasis'"),
        ('point = "B"', 'point = "Z"', r"axles\[1\]\.point: point 'Z' is on no body"),
        ('rod = "E"', 'rod = "D"', r"actuators\.lift: points 'C' and 'D' are both on body 'chassis'"),
        ('[[axles]]\npoint = "B"\nlabel = "rear axle"\n', "", r"axles: 1 axle\(s\) given, a machine needs at least two"),  # noqa: E501
        ('m_1 = { unit = "kg", ', "m_1 = { ", r"parameters\.m_1\.unit: missing unit"),
        ('J_1 = { unit = "kg*m^2"', 'J_1 = { unit = "kg m^2"', r"parameters\.J_1\.unit: 'kg m\^2', expected 'kg\*m\^2'"),  # noqa: E501
        ('mass = "m_2"', 'mas = "m_2"', r"bodies\.boom: unknown key 'mas'"),
        ('[sensors.H]\naxes = ["x", "y"]', '[sensors.H]\naxes = ["x", "y"]\ncolour = "red"', r"sensors\.H: unknown key 'colour'"),  # noqa: E501
        ('[sensors.S]', '[sensors.W]', r"sensors\.W: point 'W' is on no body"),
        ('at = "D"', 'at = "Y"', r"bodies\.boom\.at: point 'Y' is on no body"),
        ('g = { unit', 'gee = { unit', r"parameters: unknown parameter 'gee'; missing: g \[m/s\^2\]"),
    ],
)  # fmt: skip
def test_bad_descriptions_name_the_entry(tmp_path: Path, old: str, new: str, message: str) -> None:
    with pytest.raises(DescriptionError, match=message):
        load_machine(_broken(tmp_path, old, new))


def test_a_loop_in_the_body_tree_is_named(tmp_path: Path) -> None:
    text = (MACHINES_DIR / "compact_wheel_loader.toml").read_text(encoding="utf-8")
    # the boom hangs from the bucket, the bucket from the boom: neither reaches the chassis
    text = text.replace('parent = "chassis"\nat = "D"', 'parent = "bucket"\nat = "U"', 1)
    with pytest.raises(DescriptionError, match=r"bodies\.boom\.parent: loop in the body tree"):
        load_machine(_broken(tmp_path, "", "", text))


def test_parameter_values_are_checked_against_the_description() -> None:
    machine = load_machine("compact_wheel_loader")
    path = MACHINES_DIR / "values" / "compact_wheel_loader.toml"
    values = tomllib.loads(path.read_text(encoding="utf-8"))
    check_values(machine, values)
    with pytest.raises(DescriptionError, match=r"k_tilt\.unit: 'N/mm', expected 'N/m'"):
        check_values(machine, {**values, "k_tilt": {**values["k_tilt"], "unit": "N/mm"}})
    with pytest.raises(DescriptionError, match=r"m_1\.value: -1\.0 outside"):
        check_values(machine, {**values, "m_1": {**values["m_1"], "value": -1.0}})
    with pytest.raises(DescriptionError, match=r"values for compact_wheel_loader: m_3: missing"):
        check_values(machine, {k: v for k, v in values.items() if k != "m_3"})
