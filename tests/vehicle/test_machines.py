"""The machine registry (loader_model.machines) and the flat parameter files of other machines."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

import loader_model_generated as skid
import loader_model_generated.compact_wheel_loader as wl
from derive.description import MACHINES_DIR
from loader_model.machine_packages import derive_command
from loader_model.machines import generated_folder, list_machines, machine, resolve_machine_name
from loader_model.parameters.machine_files import (
    default_machine_parameters,
    load_machine_parameters,
)
from loader_model.vehicle.dynamics import LoaderDynamics
from loader_model.vehicle.statics import resolve_machine_values

DATA = Path(__file__).resolve().parents[2] / "loader_model" / "data" / "machines"
SHIPPED = (DATA / "compact_wheel_loader.toml").read_text(encoding="utf-8")


def test_every_generated_machine_is_listed_with_its_metadata() -> None:
    assert list_machines() == ("compact_wheel_loader", "skid_steer", "tractor_front_loader")
    info = machine("compact_wheel_loader")
    assert info.package == "loader_model_generated.compact_wheel_loader"
    assert info.coordinate_names == wl.COORDINATE_NAMES and info.n_coordinates == 5
    assert info.state_names == wl.STATE_NAMES and info.output_names == wl.OUTPUT_NAMES
    assert info.axles == ("A", "B") and info.seat_point == "S"
    assert (info.driven_cylinder.base, info.driven_cylinder.rod) == ("C", "E")
    assert [c.name for c in info.locked_cylinders] == ["tilt"]
    assert info.static_names == ("F_Ay0", "F_By0", "F_tilt0")
    assert info.description_hash == wl.DESCRIPTION_HASH
    default = machine()
    assert default.package == "loader_model_generated" and default.n_coordinates == 4
    assert default.parameter_names == skid.PARAMETER_NAMES


@pytest.mark.parametrize("name", ["skid_steer", "compact_wheel_loader"])
def test_shipped_descriptions_are_the_derivation_inputs(name: str) -> None:
    shipped = (DATA / f"{name}.machine.toml").read_bytes()
    assert shipped == (MACHINES_DIR / f"{name}.toml").read_bytes(), "run `make regenerate`"
    assert resolve_machine_name(MACHINES_DIR / f"{name}.toml") == name


def test_shipped_values_repeat_the_derivation_values() -> None:
    derive_values = tomllib.loads(
        (MACHINES_DIR / "values" / "compact_wheel_loader.toml").read_text()
    )
    shipped = tomllib.loads(SHIPPED)
    for name, entry in (shipped["model"] | shipped["tyres"]).items():
        assert (entry["value"], entry["unit"]) == (
            derive_values[name]["value"],
            derive_values[name]["unit"],
        ), name


def test_registry_errors(tmp_path: Path) -> None:
    with pytest.raises(
        ValueError, match="unknown machine 'tractor'; allowed: compact_wheel_loader"
    ):
        machine("tractor")
    other = tmp_path / "tractor.toml"
    other.write_text('[machine]\nname = "tractor"\n')
    folder = generated_folder(other)
    assert not folder.is_relative_to(tmp_path)  # the runtime's cache, never beside the file
    with pytest.raises(
        ValueError,
        match=rf"'tractor' has no generated package for this version of the file \(none in "
        rf"{folder}/\); derive it with `{re.escape(derive_command(other))}`",
    ):
        machine(other)
    changed = tmp_path / "wl.toml"
    changed.write_text((MACHINES_DIR / "compact_wheel_loader.toml").read_text() + "\n# edit\n")
    with pytest.raises(ValueError, match="differs from the one its generated code"):
        machine(changed)
    broken = tmp_path / "broken.toml"
    broken.write_text("this is not toml")
    with pytest.raises(ValueError, match="not a machine description"):
        machine(broken)


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (
            'm_1 = { value = 4200.0, unit = "kg"',
            'm_1 = { value = 4200.0, unit = "t"',
            "m_1: unit 't'",
        ),
        ("m_1 = { value = 4200.0,", "m_1 = { value = 1e6,", r"m_1 = 1000000.0 kg is out of range"),
        ("m_1 = {", "m_9 = {", "missing m_1"),
        ("count = { value = 2,", "count = { value = 9,", r"count = 9 - is out of range"),
        ("k_tilt = { value = 30000000.0", "k_tilt = { value = 1.0", "k_tilt = 1.0 N/m is out"),
        # each axle's tyres: the description's range (R in [0.2, 1] m, c_e in [1.5, 2])
        (
            "R_A = { value = 0.42,",
            "R_A = { value = 0.0,",
            r"R_A = 0\.0 m is out of range; allowed: \[0\.2, 1\]",
        ),
        (
            "R_A = { value = 0.42,",
            "R_A = { value = nan,",
            r"\[tyres\]: R_A = nan m is out of range",
        ),
        (
            "R_B = { value = 0.42,",
            "R_B = { value = 2.5,",
            r"R_B = 2\.5 m is out of range; allowed: \[0\.2, 1\]",
        ),
        (
            "ce_A = { value = 1.8,",
            "ce_A = { value = 1.0,",
            r"ce_A = 1\.0 - is out of range; allowed: \[1\.5, 2\]",
        ),
        ("R_B = {", "R_Z = {", r"\[tyres\]: missing R_B"),
        ('R_A = { value = 0.42, unit = "m"', 'R_A = { value = 0.42, unit = "mm"', "R_A: unit 'mm'"),
    ],
)
def test_parameter_file_errors_name_the_entry(
    tmp_path: Path, old: str, new: str, message: str
) -> None:
    assert old in SHIPPED
    path = tmp_path / "wl.toml"
    path.write_text(SHIPPED.replace(old, new, 1))
    with pytest.raises(ValueError, match=message) as error:
        load_machine_parameters(path, machine("compact_wheel_loader"))
    assert str(path) in str(error.value)


def test_unknown_parameter_and_load_case(tmp_path: Path) -> None:
    path = tmp_path / "wl.toml"
    path.write_text(
        SHIPPED.replace("[model]\n", '[model]\nZ_x = { value = 1.0, unit = "m", source = "x" }\n')
    )
    with pytest.raises(ValueError, match=r"\[model\]: unknown Z_x; allowed: A_x"):
        load_machine_parameters(path, machine("compact_wheel_loader"))
    with pytest.raises(ValueError, match="unknown load case 'heavy'; allowed: empty, full"):
        resolve_machine_values(machine("compact_wheel_loader"), None, "heavy")


def test_wheel_loader_dynamics_from_its_metadata() -> None:
    model = LoaderDynamics.from_parameters(None, "full", machine="compact_wheel_loader")
    linear = model.linearise()
    assert linear.A.shape == (10, 10) and linear.state_names == wl.STATE_NAMES
    params = default_machine_parameters(machine("compact_wheel_loader"))
    raw = np.array([params.model[n] for n in wl.PARAMETER_NAMES])
    completed, force = wl.function("complete_parameters")(raw)
    np.testing.assert_array_equal(model.parameters, np.asarray(completed).ravel())
    assert model.static_cylinder_force_N == float(force) > 0
    assert model.parameter("F_tilt0") == float(completed[wl.PARAMETER_NAMES.index("F_tilt0")])
    assert set(model.point_positions(np.zeros(5))) >= {"K", "Q", "T", "U"}
    with pytest.raises(ValueError, match=r"\|theta_3\| <= pi rad"):
        model.mass_matrix([0, 0, 0, 0, 4.0])
    with pytest.raises(ValueError, match="model parameter m_3 = 1e-06 is out of range"):
        LoaderDynamics({**params.model, "m_3": 1e-6}, machine="compact_wheel_loader")


def test_coordinate_units_come_from_the_joints() -> None:
    """The chassis' x_H, y_H are lengths, pinned bodies' coordinates angles; an unknown
    coordinate is refused naming it."""
    from loader_model.machines import machine

    info = machine("compact_wheel_loader")
    units = [info.coordinate_unit(name) for name in info.coordinate_names]
    assert units == ["m", "m", "rad", "rad", "rad"]
    with pytest.raises(ValueError, match="coordinate 'theta_9': allowed"):
        info.coordinate_unit("theta_9")


def test_the_tractor_examples_files_are_the_shipped_machines() -> None:
    """docs/examples/tractor_front_loader/ holds the shipped tractor's description and values
    as a user keeps them: byte for byte the same, so the example's commands run the shipped
    generated package (a description of a shipped name resolves to it by its hash)."""
    root = DATA.parents[2]
    example = root / "docs" / "examples" / "tractor_front_loader"
    pairs = (
        (example / "tractor_front_loader.toml", root / "derive" / "machines"),
        (example / "tractor_front_loader_values.toml", DATA),
    )
    for copy, folder in pairs:
        assert copy.read_bytes() == (folder / "tractor_front_loader.toml").read_bytes(), copy
    assert resolve_machine_name(example / "tractor_front_loader.toml") == "tractor_front_loader"
