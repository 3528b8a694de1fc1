"""Bad circuit entries are refused with one line naming the entry, the value and what is allowed.

In a description (``[circuit]``: checked before anything is derived, ``python -m derive`` exits
with code 2 and one line) and in a machine parameter file (``[valve]``: required for a valve
circuit, refused for a pump's, each value checked against its unit and range).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from derive.__main__ import main as derive_main
from derive.description import MACHINES_DIR
from loader_model.machines import machine
from loader_model.parameters.machine_files import parse_machine_parameters

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "valve_wheel_loader"
VALVE_DESCRIPTION = (EXAMPLE / "valve_wheel_loader.toml").read_text(encoding="utf-8")
VALVE_VALUES = (EXAMPLE / "valve_wheel_loader_values.toml").read_text(encoding="utf-8")
PUMP_VALUES = (
    (Path(__file__).resolve().parents[2] / "loader_model" / "data" / "machines")
    .joinpath("compact_wheel_loader.toml")
    .read_text(encoding="utf-8")
)


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


DESCRIPTION_CASES = [
    (
        "kind",
        _edit(VALVE_DESCRIPTION, 'kind = "valve"', 'kind = "servo"'),
        r"circuit\.kind: 'servo' is not allowed; allowed: 'pump', 'valve'$",
    ),
    (
        "supply",
        _edit(VALVE_DESCRIPTION, 'supply = "load_sensing"', 'supply = "open_centre"'),
        r"circuit\.supply: 'open_centre' is not allowed; allowed: 'load_sensing', "
        r"'constant_pressure'$",
    ),
    (
        "pump_supply",
        _edit(VALVE_DESCRIPTION, 'kind = "valve"', 'kind = "pump"'),
        r"circuit\.supply: 'load_sensing' is not allowed; a supply is given for kind 'valve' "
        r"only$",
    ),
    (
        "misspelt",
        _edit(VALVE_DESCRIPTION, 'supply = "load_sensing"', 'suply = "load_sensing"'),
        r"circuit: unknown key 'suply' \(did you mean 'supply'\?\); allowed: kind, supply$",
    ),
    (
        "no_kind",
        _edit(VALVE_DESCRIPTION, 'kind = "valve"', ""),
        r"circuit\.kind: None is not allowed; allowed: 'pump', 'valve'$",
    ),
]


@pytest.mark.parametrize(
    ("label", "text", "message"), DESCRIPTION_CASES, ids=[c[0] for c in DESCRIPTION_CASES]
)
def test_a_bad_circuit_entry_is_refused_before_deriving(
    label: str, text: str, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    description = tmp_path / f"{label}.toml"
    description.write_text(text, encoding="utf-8")
    output = tmp_path / "out"
    assert derive_main([str(description), "--output", str(output)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith(f"python -m derive: {label}.toml: "), err
    assert re.search(message, err.rstrip("\n")), err
    assert not output.exists()


def test_the_shipped_descriptions_have_the_pump_circuit() -> None:
    for name in ("skid_steer", "compact_wheel_loader"):
        assert "[circuit]" not in (MACHINES_DIR / f"{name}.toml").read_text(encoding="utf-8")
        assert machine(name).circuit == "pump"


@pytest.fixture(scope="module")
def valve_info():  # type: ignore[no-untyped-def]
    """The compact wheel loader's registry entry with the valve circuit (the parameter file's
    checks need no generated package of its own)."""
    import dataclasses

    return dataclasses.replace(machine("compact_wheel_loader"), circuit="valve")


VALUE_CASES = [
    (
        _edit(VALVE_VALUES, "spool_stroke = { value = 0.005,", "spool_stroke = { value = 0.05,"),
        r"\[valve\]: spool_stroke = 0\.05 m is out of range; allowed: \[0\.0005, 0\.02\] "
        r"\(spool strokes of 0\.5-20 mm\)$",
    ),
    (
        _edit(VALVE_VALUES, "compensated = { value = 1,", "compensated = { value = 2,"),
        r"\[valve\]: compensated = 2 - is out of range; allowed: \[0, 1\]",
    ),
    (
        _edit(
            VALVE_VALUES,
            'tank_pressure = { value = 300000.0, unit = "Pa"',
            'tank_pressure = { value = 3.0, unit = "bar"',
        ),
        r"\[valve\]: tank_pressure: unit 'bar'; expected 'Pa'$",
    ),
    (
        VALVE_VALUES[: VALVE_VALUES.index("\n[valve]\n")]
        + VALVE_VALUES[VALVE_VALUES.index("# Bucket load cases") :],
        r"missing table \[valve\] \(machine 'compact_wheel_loader' has \[circuit\] kind = "
        r"\"valve\"",
    ),
    (
        _edit(VALVE_VALUES, "overlap = {", "overlapp = {"),
        r"\[valve\]: missing overlap$",
    ),
]


@pytest.mark.parametrize(("text", "message"), VALUE_CASES, ids=range(len(VALUE_CASES)))
def test_a_bad_valve_value_is_refused(valve_info, text: str, message: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=message) as raised:
        parse_machine_parameters(text, valve_info, "values.toml")
    assert "\n" not in str(raised.value)


def test_a_valve_table_for_a_pump_circuit_is_refused() -> None:
    table = VALVE_VALUES[VALVE_VALUES.index("\n[valve]\n") : VALVE_VALUES.index("# Bucket load")]
    with pytest.raises(
        ValueError,
        match=r"\[valve\] is given, but machine "
        r"'compact_wheel_loader' has the circuit kind 'pump'",
    ):
        parse_machine_parameters(PUMP_VALUES + "\n" + table, machine("compact_wheel_loader"), "f")


def test_the_example_values_are_read(valve_info) -> None:  # type: ignore[no-untyped-def]
    values = parse_machine_parameters(VALVE_VALUES, valve_info, "values.toml")
    assert values.valve is not None and values.valve.spool_stroke == 0.005
    assert values.rod_side_pressure == values.valve.tank_pressure == 3e5
    assert "charge_pressure" not in values.hydraulics
