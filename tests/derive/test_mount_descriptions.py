"""Bad entries of two-point mounts, end stops and a slider's extension are refused with one line
naming the entry, the value and what is allowed (no derivation: fast)."""

from __future__ import annotations

from pathlib import Path

import pytest

from derive.description import DescriptionError, load_machine, structural_parameters
from derive.description_values import check_values
from tests.derive.mounted_cab import DESCRIPTION, POINTS, VALUES

#: (replaced text, replacement, expected message): one mistake each in the fixture.
MISTAKES = {
    "one mount": (
        'mounts = ["F", "R"]',
        'mounts = ["F"]',
        r"bodies\.cab\.mounts: \['F'\] is not allowed; give the 2 mount points",
    ),
    "mount not on the body": (
        'mounts = ["F", "R"]',
        'mounts = ["F", "Q"]',
        r"bodies\.cab\.mounts\[1\]: 'Q' is not a point of the body \(points: F, R, Z, W\)",
    ),
    "same mount twice": (
        'mounts = ["F", "R"]',
        'mounts = ["F", "F"]',
        r"bodies\.cab\.mounts: \['F', 'F'\] is not allowed; give two different points",
    ),
    "end stops as text": (
        'end_stops = true\nmass = "m_cab"',
        'end_stops = "yes"\nmass = "m_cab"',
        r"bodies\.cab\.end_stops: 'yes' is not allowed; give true or false",
    ),
    "one coordinate": (
        'coordinates = ["s_cab", "theta_cab"]',
        'coordinates = ["s_cab"]',
        r"bodies\.cab\.coordinates: \['s_cab'\] is not allowed; give a list of 2 names",
    ),
    "unknown joint": (
        'joint = "two_mounts"',
        'joint = "mounted"',
        r"bodies\.cab\.joint: 'mounted' is not allowed; allowed: free, pin, slider, two_mounts",
    ),
    "extension on two mounts": (
        'mounts = ["F", "R"]',
        'mounts = ["F", "R"]\nextension = "l_tele"',
        r"bodies\.cab: unknown key 'extension'; allowed: at, centre_of_gravity, ",
    ),
    "extension as a number": (
        'extension = "l_tele"',
        "extension = 0.8",
        r"bodies\.tele\.extension: 0\.8 is not allowed; give a name",
    ),
    "stop parameter missing": (
        "s_max_seat = ",
        "s_max_sea = ",
        r"parameters: unknown parameter 's_max_sea' \(did you mean 's_max_seat'\?\); "
        r"missing: s_max_seat \[m\]",
    ),
    "no direction": (
        "direction = [0.0, 1.0]\ncoordinates",
        "coordinates",
        r"bodies\.cab\.direction: missing",
    ),
}


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "mounted_cab.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_the_fixture_loads(tmp_path: Path) -> None:
    machine = load_machine(_write(tmp_path, DESCRIPTION))
    assert machine.elements == ("tele", "cab_F", "cab_R", "seat")
    assert machine.stops == ("cab_F", "cab_R", "seat")
    names = [name for name, _ in structural_parameters(machine)]
    assert names[-7:] == ["l_tele", "F_Ay0", "F_By0", "F_tele0", "F_cab_F0", "F_cab_R0", "F_seat0"]


@pytest.mark.parametrize("mistake", sorted(MISTAKES))
def test_bad_mount_entries_are_named(mistake: str, tmp_path: Path) -> None:
    old, new, message = MISTAKES[mistake]
    assert old in DESCRIPTION
    path = _write(tmp_path, DESCRIPTION.replace(old, new, 1))
    with pytest.raises(DescriptionError, match=r"^mounted_cab\.toml: " + message):
        load_machine(path)


def _values(tmp_path: Path, **changes: float) -> tuple[object, dict[str, dict[str, object]]]:
    machine = load_machine(_write(tmp_path, DESCRIPTION))
    points = {f"{k}_{a}": v[i] for k, v in POINTS.items() for i, a in enumerate("xy")}
    tyres = {item.name: item.range[0] if item.range else 1.0 for item in machine.tyres}
    given = VALUES | points | tyres | changes
    values = {
        item.name: {"value": given[item.name], "unit": item.unit, "source": "test"}
        for item in (*machine.parameters, *machine.tyres)
        if item.name in given
    }
    return machine, values


def test_travel_limits_must_hold_the_static_position(tmp_path: Path) -> None:
    machine, values = _values(tmp_path)
    check_values(machine, values)  # type: ignore[arg-type]
    machine, values = _values(tmp_path, s_min_seat=0.01)
    with pytest.raises(
        DescriptionError,
        match=r"^values for mounted_cab: s_min_seat, s_max_seat: \[0\.01, 0\.045\]: the travel "
        r"limits must hold the static position inside, s_min < 0 < s_max",
    ):
        check_values(machine, values)  # type: ignore[arg-type]
