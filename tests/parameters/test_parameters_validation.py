"""Every validation rule of the parameter files, fed a modified TOML file."""

from __future__ import annotations

import copy
import json
import math
import tomllib
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from loader_model.parameters.sets import (
    bucket_load,
    default_loader,
    load_bucket_load,
    load_loader,
    replace,
)
from loader_model.vehicle.statics import resolve_machine

DATA = resources.files("loader_model").joinpath("data")
LOADER = tomllib.loads(DATA.joinpath("default_loader.toml").read_text(encoding="utf-8"))
EMPTY = tomllib.loads(DATA.joinpath("load_empty.toml").read_text(encoding="utf-8"))

Edit = Callable[[dict[str, Any]], None]


def _node(data: dict[str, Any], path: str) -> dict[str, Any]:
    for key in path.split("."):
        data = data[key]
    return data


def set_value(path: str, value: Any) -> Edit:
    return lambda data: _node(data, path).__setitem__("value", value)


def set_key(path: str, key: str, value: Any) -> Edit:
    return lambda data: _node(data, path).__setitem__(key, value)


def delete(path: str) -> Edit:
    parent, _, key = path.rpartition(".")
    return lambda data: (_node(data, parent) if parent else data).pop(key)


def rename(path: str, new: str) -> Edit:
    parent, _, key = path.rpartition(".")

    def edit(data: dict[str, Any]) -> None:
        node = _node(data, parent) if parent else data
        node[new] = node.pop(key)

    return edit


def _literal(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_literal(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_literal(v)}" for k, v in value.items()) + " }"
    return repr(value)  # int or float, including nan and inf


def _toml(data: dict[str, Any], table: str = "") -> list[str]:
    """Independent minimal TOML writer: dicts holding dicts are tables, others inline."""
    is_table = {
        k: isinstance(v, dict) and any(isinstance(x, dict) for x in v.values())
        for k, v in data.items()
    }
    lines = [f"[{table}]"] if table else []
    lines += [f"{k} = {_literal(v)}" for k, v in data.items() if not is_table[k]]
    for key, value in data.items():
        if is_table[key]:
            lines += _toml(value, f"{table}.{key}" if table else key)
    return lines


def write(tmp_path: Path, base: dict[str, Any], *edits: Edit) -> Path:
    data = copy.deepcopy(base)
    for edit in edits:
        edit(data)
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(_toml(data)) + "\n", encoding="utf-8")
    return path


def test_the_test_writer_reproduces_the_shipped_file(tmp_path: Path) -> None:
    assert tomllib.loads(write(tmp_path, LOADER).read_text(encoding="utf-8")) == LOADER


STRUCTURE = [
    (rename("tyres.front.k_y", "k_yy"), r"tyres\.front\.k_yy: unknown key; did you mean 'k_y'\?"),
    (rename("chassis", "chasis"), r"chasis: unknown key; did you mean 'chassis'\?"),
    (rename("chassis.mass.source", "sourse"), r"chassis\.mass\.sourse: unknown key; .*'source'"),
    (delete("tyres.rear.c_x"), r"tyres\.rear\.c_x: missing key"),
    (delete("chassis.mass.unit"), r"chassis\.mass\.unit: missing key"),
    (delete("pump"), r"pump: missing key"),
    (set_key("chassis.mass", "unit", "t"), r"chassis\.mass: unit 't' is not allowed; the allowed"),
    (set_key("friction.f_c", "unit", "N/bar"), r"friction\.f_c: .*the allowed unit is 'N/Pa'"),
    (set_key("boom.mass", "source", ""), r"boom\.mass\.source: expected a non-empty string"),
    (set_value("hydraulics.bulk_modulus", math.nan), r"bulk_modulus: value nan is not finite"),
    (set_value("tyres.front.k_x", math.inf), r"tyres\.front\.k_x: value inf is not finite"),
    (set_value("geometry.A", [0.6, -math.inf]), r"geometry\.A\[1\]: value -inf is not finite"),
    (set_value("geometry.A", [0.6, -0.3, 0.0]), r"geometry\.A: value .* not a list of 2 numbers"),
    (set_value("cylinders.count", 2.5), r"cylinders\.count: value 2\.5 is not an integer"),
    (set_value("chassis.mass", True), r"chassis\.mass: value True is not a number"),
    (lambda d: d["chassis"].__setitem__("mass", 2700.0), r"chassis\.mass: expected a table"),
    (delete("tyres.rear.radius"), r"tyres\.rear\.radius: missing key"),
    (set_value("tyres.front.radius", math.nan), r"tyres\.front\.radius: value nan is not finite"),
]


@pytest.mark.parametrize(("edit", "message"), STRUCTURE)
def test_structure_units_and_types(tmp_path: Path, edit: Edit, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        load_loader(write(tmp_path, LOADER, edit))


NON_POSITIVE = [
    "chassis.mass",
    "chassis.inertia",
    "boom.mass",
    "boom.inertia",
    "tyres.front.k_y",
    "tyres.rear.k_x",
    "hydraulics.bulk_modulus",
    "cylinders.piston_diameter",
    "cylinders.rod_diameter",
    "cylinders.stroke",
    "cylinders.dead_volume_a",
    "cylinders.dead_volume_b",
    "accumulator.gas_volume",
    "accumulator.orifice_diameter",
    "pump.max_displacement",
    "environment.gravity",
]


@pytest.mark.parametrize("path", NON_POSITIVE)
@pytest.mark.parametrize("value", [0.0, -1.0])
def test_non_positive_values_are_rejected(tmp_path: Path, path: str, value: float) -> None:
    # every field's plausible range starts above zero here, and the message carries its reason
    message = rf"{path.replace('.', '[.]')} = {value!r} .* is out of range; allowed: \[[0-9.e+-]+, "
    message += r"[0-9.e+-]+\] \(.+\)$"
    with pytest.raises(ValueError, match=message):
        load_loader(write(tmp_path, LOADER, set_value(path, value)))


RANGES = [
    (
        "tyres.front.c_y",
        -1.0,
        r"tyres\.front\.c_y = -1\.0 N s/m is out of range; allowed: \[0, 1e\+06\]",
    ),
    (
        "tyres.rear.c_x",
        -1e-9,
        r"tyres\.rear\.c_x = -1e-09 N s/m .*allowed: \[0, 1e\+06\] \(undamped",
    ),
    ("friction.f_v", -5.0, r"friction\.f_v = -5\.0 N s/m .*allowed: \[0, 1e\+06\]"),
    ("cylinders.count", 0, r"cylinders\.count = 0 - is out of range; allowed: \[1, 4\] \(one to"),
    ("accumulator.discharge_coefficient", 1.5, r"discharge_coefficient = 1\.5 .*\[0\.1, 1\]"),
    ("chassis.mass", 1e-300, r"chassis\.mass = 1e-300 kg .*\[250, 45000\] \(chassis of a 0\.5 t"),
    ("tyres.front.k_y", 1e-300, r"tyres\.front\.k_y = 1e-300 N/m .*\[50000, 3e\+07\]"),
    ("geometry.C", [1e30, 0.0], r"geometry\.C = \(1e\+30, 0\.0\) m .*\[-10, 10\] \(within 10 m"),
    ("controller.k_fb", [1e30, 0, 0, 0], r"controller\.k_fb = \(1e\+30, 0\.0, 0\.0, 0\.0\)"),
    (
        "cylinders.count",
        10**400,
        r"cylinders\.count = 10{19}\.\.\. \(401 digits\) - is out of range; allowed: \[1, 4\]",
    ),
    ("accumulator.polytropic_exponent", 0.9, r"polytropic_exponent = 0\.9 .*\[1, 1\.7\]"),
    ("geometry.boom_angle", 2.0, r"geometry\.boom_angle = 2\.0 rad .*\[-1\.5708, 1\.5708\]"),
    (
        "tyres.front.radius",
        0.0,
        r"tyres\.front\.radius = 0\.0 m is out of range; allowed: \(0, 2\]",
    ),
    ("tyres.rear.radius", 2.5, r"tyres\.rear\.radius = 2\.5 m is out of range; allowed: \(0, 2\]"),
    ("tyres.rear.cam_exponent", 1.0, r"cam_exponent = 1\.0 - .*allowed: \(1, 10\] \(a convex"),
    ("tyres.front.cam_exponent", 10.5, r"cam_exponent = 10\.5 - .*allowed: \(1, 10\]"),
]


@pytest.mark.parametrize(("path", "value", "message"), RANGES)
def test_out_of_range_values(tmp_path: Path, path: str, value: float, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        load_loader(write(tmp_path, LOADER, set_value(path, value)))


def test_negative_leakage_velocity_coefficient_is_allowed(tmp_path: Path) -> None:
    # Table 5 identifies k_Lv < 0; it is a regression coefficient, not a physical conductance.
    loader = load_loader(write(tmp_path, LOADER, set_value("leakage.k_lv", -1e-3)))
    assert loader.leakage.k_lv == -1e-3


def test_rod_not_smaller_than_piston(tmp_path: Path) -> None:
    message = r"cylinders\.rod_diameter = 0\.065 m must be at most 0\.9 x cylinders\.piston_d"
    with pytest.raises(ValueError, match=message):
        load_loader(write(tmp_path, LOADER, set_value("cylinders.rod_diameter", 0.065)))


def test_huge_integer_as_a_float_value(tmp_path: Path) -> None:
    with pytest.raises(
        ValueError, match=r"chassis\.mass: value 10{19}\.\.\. \(401 digits\) is not"
    ):
        load_loader(write(tmp_path, LOADER, set_value("chassis.mass", 10**400)))


COINCIDENT = [
    (set_value("geometry.C", [-0.7, 0.7305]), r"geometry\.C = \(-0\.7, 0\.7305\) and geometry\.D"),
    (set_value("geometry.B", [1.08, -0.47]), r"geometry\.A = .* and geometry\.B = .* coincide"),
    (set_value("boom.cog", [-0.24, 0.6305]), r"geometry\.E = .* and boom\.cog = .* coincide"),
]


@pytest.mark.parametrize(("edit", "message"), COINCIDENT)
def test_coincident_points(tmp_path: Path, edit: Edit, message: str) -> None:
    with pytest.raises(ValueError, match="degenerate geometry: " + message):
        load_loader(write(tmp_path, LOADER, edit))


def test_front_axle_must_be_ahead_of_rear_axle(tmp_path: Path) -> None:
    swap = (set_value("geometry.A", [-0.6, -0.3]), set_value("geometry.B", [0.6, -0.3]))
    with pytest.raises(ValueError, match=r"geometry\.A = \(-0\.6, -0\.3\) must be ahead of geo"):
        load_loader(write(tmp_path, LOADER, *swap))


@pytest.mark.parametrize(
    ("edits", "interval"),
    [
        ((set_value("cylinders.retracted_length", 0.8),), r"\[0\.801, 1\.249\]"),
        (
            (set_value("cylinders.retracted_length", 0.5), set_value("cylinders.stroke", 0.15)),
            r"\[0\.501, 0\.649\]",
        ),
        # exactly at full stroke (|E - C| = retracted + stroke) is on the end stop: refused
        (
            (
                set_value("cylinders.stroke", 0.1),
                set_value(
                    "cylinders.retracted_length", math.dist((-0.24, 0.63), (-0.67, 0.08)) - 0.1
                ),
            ),
            r"\[0\.59914, 0\.69714\] m",
        ),
    ],
)
def test_cylinder_length_outside_stroke(tmp_path: Path, edits: tuple, interval: str) -> None:
    message = r"geometry\.E: cylinder length \|E - C\| = 0\.69814 m .* outside " + interval
    with pytest.raises(ValueError, match=message):
        load_loader(write(tmp_path, LOADER, *edits))


BUCKET = [
    (rename("cog", "cg"), r"cg: unknown key; did you mean 'cog'\?"),
    (delete("pressure_normalisation"), r"pressure_normalisation: missing key"),
    (set_key("pressure_normalisation", "unit", "bar"), r"the allowed unit is 'Pa'"),
    (set_value("mass", 0.0), r"mass = 0\.0 kg is out of range; allowed: \(0, 15000\] \(a mass is"),
    (set_value("mass", 1e6), r"mass = 1000000\.0 kg is out of range; allowed: \(0, 15000\]"),
    (set_value("inertia", -2.0), r"inertia = -2\.0 kg m\^2 is out of range; allowed: \(0, 50000\]"),
    (set_value("cog", [math.nan, 0.0]), r"cog\[0\]: value nan is not finite"),
]


@pytest.mark.parametrize(("edit", "message"), BUCKET)
def test_bucket_load_file(tmp_path: Path, edit: Edit, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        load_bucket_load(write(tmp_path, EMPTY, edit))


def test_error_names_the_file_and_leaves_defaults_intact(tmp_path: Path) -> None:
    before = default_loader()
    path = write(tmp_path, LOADER, set_value("chassis.mass", -5.0))
    with pytest.raises(ValueError, match=r"bad\.toml: chassis\.mass = -5\.0 kg"):
        load_loader(path)
    assert default_loader() == before
    assert default_loader().chassis.mass == before.chassis.mass


def test_malformed_toml_is_a_value_error(tmp_path: Path) -> None:
    path = tmp_path / "broken.toml"
    path.write_text("[chassis\nmass = 1\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"broken\.toml: "):
        load_loader(path)


def test_combined_centre_of_gravity_must_not_coincide_with_a_point() -> None:
    loader, load = default_loader(), bucket_load("empty")
    # choose the load CoG so that the combined G of boom and load lands on E
    m_b, m_l = loader.boom.mass, load.mass
    ex, ey = loader.geometry.E
    bx, by = loader.boom.cog
    cog = (((m_b + m_l) * ex - m_b * bx) / m_l, ((m_b + m_l) * ey - m_b * by) / m_l)
    on_e = replace(load, {"cog": cog})
    with pytest.raises(
        ValueError,
        match=r"geometry\.E = .* and combined G of boom\.cog and load\.cog = .* coincide",
    ):
        resolve_machine(loader, on_e)
