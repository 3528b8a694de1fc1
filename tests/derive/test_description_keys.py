"""A misspelt key of a description is named as found, with the key it was probably meant to be,
the keys still missing and those allowed; the static loads are listed by the derivation.

Each bad case exits ``python -m derive`` with code 2 and one line, before anything is derived.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from derive.__main__ import main as derive_main
from derive.description import (
    MACHINES_DIR,
    DescriptionError,
    load_machine,
    static_load_parameters,
)
from derive.description_values import check_values

WHEEL_LOADER = (MACHINES_DIR / "compact_wheel_loader.toml").read_text(encoding="utf-8")
#: A declaration of a static load, F_<axle>y0 or F_<element>0, one line in [parameters].
STATIC_LOADS = re.compile(r"\nF_\w+0 = [^\n]*")


def _edit(old: str, new: str) -> str:
    assert old in WHEEL_LOADER, old
    return WHEEL_LOADER.replace(old, new, 1)


CASES = [
    (
        "axle_point",
        _edit('point = "A"', 'pont = "A"'),
        r"axles\[0\]: unknown key 'pont' \(did you mean 'point'\?\); missing: point; "
        r"allowed: label, point$",
    ),
    (
        "actuator_kind",
        _edit('kind = "driven"', 'knd = "driven"'),
        r"actuators\.lift: unknown key 'knd' \(did you mean 'kind'\?\); missing: kind; "
        r"allowed: base, kind, rod$",
    ),
    (
        "actuator_rod",
        _edit('rod = "E"', 'rood = "E"'),
        r"actuators\.lift: unknown key 'rood' \(did you mean 'rod'\?\); missing: rod",
    ),
    (
        "sensor_axes",
        _edit('[sensors.H]\naxes = ["x", "y"]', '[sensors.H]\naxis = ["x", "y"]'),
        r"sensors\.H: unknown key 'axis' \(did you mean 'axes'\?\); missing: axes",
    ),
    (
        "body_joint",
        _edit('[bodies.boom]\njoint = "pin"', '[bodies.boom]\njiont = "pin"'),
        r"bodies\.boom: unknown key 'jiont' \(did you mean 'joint'\?\); missing: joint; allowed: ",
    ),
    (
        "body_parent",
        _edit('parent = "chassis"', 'parnt = "chassis"'),
        r"bodies\.boom: unknown key 'parnt' \(did you mean 'parent'\?\); missing: parent",
    ),
    (
        "machine_title",
        _edit('title = "compact wheel loader"', 'titel = "compact wheel loader"'),
        r"machine: unknown key 'titel' \(did you mean 'title'\?\); missing: title",
    ),
    (
        "parameter_unit",
        _edit('m_1 = { unit = "kg"', 'm_1 = { units = "kg"'),
        r"parameters\.m_1: unknown key 'units' \(did you mean 'unit'\?\); missing: unit",
    ),
    (
        "parameter_name",
        _edit("m_3 = {", "m3 = {"),
        r"parameters: unknown parameter 'm3' \(did you mean 'm_3'\?\); missing: m_3 \[kg\]; "
        r"allowed: m_1, J_1, m_2, J_2, m_3, .*; the static loads F_Ay0, F_By0, F_tilt0 may be "
        r"left out \(computed at rest\)$",
    ),
    (
        "static_load_name",
        _edit("F_tilt0 =", "F_tilt_0 ="),
        r"parameters: unknown parameter 'F_tilt_0' \(did you mean 'F_tilt0'\?\); allowed: .*"
        r"the static loads F_Ay0, F_By0, F_tilt0 may be left out",
    ),
    (
        "parameters_missing",
        _edit("\nm_3 = {", "\n# m_3 = {").replace("\nJ_3 = {", "\n# J_3 = {", 1),
        r"parameters: missing m_3 \[kg\], J_3 \[kg\*m\^2\]: give each as "
        r"\{ unit, description, range, source \}; the static loads F_Ay0, F_By0, F_tilt0 may",
    ),
]


@pytest.mark.parametrize(("label", "text", "message"), CASES, ids=[case[0] for case in CASES])
def test_a_misspelt_key_is_named_as_found(
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


def test_the_static_loads_are_listed_by_the_derivation(tmp_path: Path) -> None:
    """Left out of [parameters], each static load is described as the shipped description
    declares it (name, unit, description, source), only without a range; the values file may
    leave them out too."""
    shipped = load_machine("compact_wheel_loader")
    loads = static_load_parameters(shipped)
    assert list(loads) == ["F_Ay0", "F_By0", "F_tilt0"]
    text, count = STATIC_LOADS.subn("", WHEEL_LOADER)
    assert count == 3
    description = tmp_path / "without_loads.toml"
    description.write_text(text, encoding="utf-8")
    listed = load_machine(description)
    assert [p.name for p in listed.parameters] == [p.name for p in shipped.parameters]
    for declared, derived in zip(shipped.parameters, listed.parameters, strict=True):
        if declared.name in loads:
            assert (derived.unit, derived.description, derived.source, derived.range) == (
                declared.unit,
                declared.description,
                declared.source,
                None,
            )
        else:
            assert derived == declared
    values = tomllib.loads(
        (MACHINES_DIR / "values" / "compact_wheel_loader.toml").read_text(encoding="utf-8")
    )
    check_values(listed, {k: v for k, v in values.items() if k not in loads})
    with pytest.raises(DescriptionError, match=r"m_3: missing"):
        check_values(listed, {k: v for k, v in values.items() if k != "m_3"})
    typo = {("m3" if k == "m_3" else k): v for k, v in values.items()}
    with pytest.raises(
        DescriptionError,
        match=r"m3: not a parameter of the machine \(did you mean 'm_3'\?\); missing: m_3$",
    ):
        check_values(listed, typo)


def test_a_sliding_mounts_static_load_is_named_for_it(tmp_path: Path) -> None:
    """The three-axle test machine's cab on a sliding mount: F_cab0 after the axles' loads."""
    from tests.derive.three_axle_cab import DESCRIPTION

    text, count = STATIC_LOADS.subn("", DESCRIPTION)
    assert count == 4
    path = tmp_path / "three_axle_cab.toml"
    path.write_text(text, encoding="utf-8")
    loads = static_load_parameters(load_machine(path))
    assert loads["F_cab0"] == "static force of the cab sliding mount (from the static equilibrium)"
    assert list(loads)[:3] == ["F_Ay0", "F_By0", "F_Ry0"]
