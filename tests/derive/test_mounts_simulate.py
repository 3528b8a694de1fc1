"""The tractor of docs/examples/tractor_front_loader with its cab on two mounts (bounce and pitch,
end stops) and a suspension seat (a slider with end stops) under the seat point S, described
outside the package, derived into the test session's cache and run through ``simulate`` on the
paper's board course: the run ends with finite, plausible results, and the static loads still
equal the hand calculation of the example's values file (the cab's and the seat's weights now go
through their mounts)."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import pytest

from loader_model.cli import main

#: Deriving with SymPy about 40 s, the 4 s board run a few seconds (2-core machine).
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
G = 9.80665

#: The example's sliding cab replaced by a cab on two mounts and a suspension seat.
CAB = """[bodies.cab]
joint = "two_mounts"
label = "cab"
parent = "chassis"
at = "M"
direction = [0.0, 1.0]
coordinates = ["s_cab", "theta_cab"]
mounts = ["F", "R"]
end_stops = true
mass = "m_cab"
inertia = "J_cab"
centre_of_gravity = "Z"
points = { F = "front cab mount", R = "rear cab mount", Z = "centre of gravity of the cab", W = "seat base" }

[bodies.seat]
joint = "slider"
label = "suspension seat"
parent = "cab"
at = "W"
direction = [0.0, 1.0]
coordinate = "s_seat"
end_stops = true
mass = "m_seat"
inertia = "J_seat"
centre_of_gravity = "Y"
points = { Y = "centre of gravity of the seat top and occupant", S = "seat reference point" }
"""

#: (name, unit, value, source) of the new parameters.
NEW = [
    ("m_seat", "kg", 100.0, "seat top 20 kg and an 80 kg occupant on the suspension"),
    ("J_seat", "kg*m^2", 8.0, "100 kg over about 0.5 m x 0.6 m"),
    ("k_cab_F", "N/m", 89000.0, "half of the example's 178 kN/m cab mount"),
    ("c_cab_F", "N*s/m", 2350.0, "half of the example's cab damping"),
    ("k_cab_R", "N/m", 89000.0, "half of the example's 178 kN/m cab mount"),
    ("c_cab_R", "N*s/m", 2350.0, "half of the example's cab damping"),
    *(
        (f"{name}_{mount}", unit, value, source)
        for mount in ("cab_F", "cab_R")
        for name, unit, value, source in (
            ("s_min", "m", -0.025, "25 mm travel to the rubber bump stop"),
            ("s_max", "m", 0.025, "25 mm travel to the rebound stop"),
            ("k_stop", "N/m", 2.0e6, "rubber bump stop"),
            ("c_stop", "N*s/m", 5.0e3, "rubber bump stop"),
        )
    ),
    ("k_seat", "N/m", 11800.0, "100 kg at 1.73 Hz: m (2 pi f)^2"),
    ("c_seat", "N*s/m", 1090.0, "damping ratio 0.5: 2 zeta sqrt(k m)"),
    ("s_min_seat", "m", -0.045, "half of a 90 mm scissor-seat stroke"),
    ("s_max_seat", "m", 0.045, "half of a 90 mm scissor-seat stroke"),
    ("k_stop_seat", "N/m", 3.0e5, "rubber end stop of the seat's scissor"),
    ("c_stop_seat", "N*s/m", 1.0e3, "rubber end stop of the seat's scissor"),
]
#: New points (x, y) [m] relative to H: mounts 0.55 m either side of M, the seat on the floor.
POINTS = {"F": (-0.15, 0.2), "R": (-1.25, 0.2), "W": (-0.6, 0.25), "Y": (-0.6, 0.55)}


def _variant(folder: Path) -> tuple[Path, Path]:
    description = (ROOT / "derive" / "machines" / "tractor_front_loader.toml").read_text(
        encoding="utf-8"
    )
    start = description.index("[bodies.cab]")
    end = description.index("[[axles]]")
    cab = description[start:end]
    description = description.replace(cab, CAB + "\n")
    description = description.replace('name = "tractor_front_loader"', 'name = "tractor_mounts"')
    lines = [
        line
        for line in description.splitlines()
        if not line.startswith(("k_cab =", "c_cab =", "F_cab0 ="))
    ]
    at = lines.index("[parameters]") + 1  # the new parameters in [parameters], not a later table
    lines[at:at] = [
        f'{name} = {{ unit = "{unit}", description = "{source}", source = "test" }}'
        for name, unit, _, source in NEW
    ]
    values = (ROOT / "loader_model" / "data" / "machines" / "tractor_front_loader.toml").read_text(
        encoding="utf-8"
    )
    values = "\n".join(
        line for line in values.splitlines() if not line.startswith(("k_cab =", "c_cab ="))
    )
    added = [
        f'{name} = {{ value = {value!r}, unit = "{unit}", source = "{source}" }}'
        for name, unit, value, source in NEW
    ]
    added += [
        f'{point}_{axis} = {{ value = {xy[i]!r}, unit = "m", source = "test" }}'
        for point, xy in POINTS.items()
        for i, axis in enumerate("xy")
    ]
    values = values.replace("[model]\n", "[model]\n" + "\n".join(added) + "\n", 1)
    paths = folder / "tractor_mounts.toml", folder / "tractor_mounts_values.toml"
    paths[0].write_text("\n".join(lines) + "\n", encoding="utf-8")
    paths[1].write_text(values + "\n", encoding="utf-8")
    return paths


@pytest.fixture(scope="module")
def machine_args(tmp_path_factory: pytest.TempPathFactory) -> list[str]:
    """``--machine``/``--params`` of the variant, derived into the session's temporary cache."""
    from derive.__main__ import main as derive_main

    description, values = _variant(tmp_path_factory.mktemp("tractor_mounts"))
    assert derive_main([str(description)]) == 0
    return ["--machine", str(description), "--params", str(values)]


def test_static_loads_with_the_cab_on_two_mounts(machine_args: list[str]) -> None:
    """Moments about the rear axle of every body's weight (the seat's 100 kg added at its x):
    the derived static axle loads equal the hand calculation."""
    from loader_model.plant.scenario import resolve_plant

    data = tomllib.loads(Path(machine_args[3]).read_text(encoding="utf-8"))["model"]
    v = {name: entry["value"] for name, entry in data.items()} | {"H_x": 0.0}
    bodies = (("H", "m_1"), ("Z", "m_cab"), ("Y", "m_seat"), ("G", "m_2"), ("Q", "m_3"))
    weight = G * sum(v[m] for _, m in bodies)
    front = G * sum(v[m] * (v[f"{p}_x"] - v["B_x"]) for p, m in bodies) / (v["A_x"] - v["B_x"])
    plant = resolve_plant(Path(machine_args[3]), "full", machine=machine_args[1])
    derived = (plant.output("F_Ay"), plant.output("F_By"))
    print(
        f"two-mount tractor, full bucket: {front / 1e3:.2f} kN front, "
        f"{(weight - front) / 1e3:.2f} kN rear"
    )
    # the derivation solves the same balance: equal to round-off of the ~50 kN loads
    assert derived == pytest.approx((front, weight - front), rel=1e-9)


def test_board_course_runs_with_finite_results(machine_args: list[str], capsys) -> None:
    argv = ["simulate", *machine_args, "--load", "full", "--duration", "4"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    print(out)
    found = re.search(r"a_total \(paper Eq\. 50\) = ([0-9.eE+-]+) m/s", out)
    assert found is not None, out
    a_total = float(found.group(1))
    assert math.isfinite(a_total) and 0.05 < a_total < 20.0
    assert "nan" not in out.lower()


def test_modes_and_fmu_of_the_mounted_cab(machine_args: list[str], tmp_path: Path, capsys) -> None:
    """The linear modes list the cab's bounce and pitch and the seat's travel, and the plant
    exports as an FMU (the two-point mount's coordinates in the runtime's machine structure)."""
    assert main(["modes", *machine_args, "--load", "full"]) == 0
    out = capsys.readouterr().out
    for row in ("s_cab [m]", "theta_cab [rad]", "s_seat [m]"):
        assert row in out
    fmu = tmp_path / "tractor_mounts.fmu"
    assert main(["export-fmu", *machine_args, str(fmu)]) == 0
    assert fmu.stat().st_size > 10_000


def test_travel_limits_that_miss_the_static_position_are_refused(
    machine_args: list[str], tmp_path: Path, capsys
) -> None:
    """A values file whose seat stops do not hold p = 0: one line naming both limits, exit 2."""
    values = Path(machine_args[3]).read_text(encoding="utf-8")
    old = "s_min_seat = { value = -0.045,"
    assert old in values
    bad = tmp_path / "bad_values.toml"
    bad.write_text(values.replace(old, "s_min_seat = { value = 0.01,"), encoding="utf-8")
    assert main(["modes", "--machine", machine_args[1], "--params", str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert err.endswith(
        "bad_values.toml [model]: s_min_seat = 0.01 m and s_max_seat = 0.045 m: the end stops' "
        "travel limits must hold the static position inside (s_min < 0 < s_max, travel from "
        "p = 0)"
    )
