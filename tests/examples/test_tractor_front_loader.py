"""The worked example of docs/examples/tractor_front_loader.md: a machine described as a user
describes their own, here under a name of its own outside the package (a tractor with a front
loader: boom and bucket on their own pins, the tilt cylinders held, a cab on a sliding mount),
derived into a temporary cache, and what the page claims of it: its static axle loads equal the
hand calculation of its values file, the rear axle lifts off at the boards with the full bucket,
the linear comfort design is refused by the design check (full bucket: worse than the baseline,
the pump at its limits, a persistent oscillation) while the empty bucket's condition passes, and
Table 3's gains pass the full bucket's boards."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import pytest

from loader_model.cli import main
from loader_model.commands.check_design_command import EXIT_CHECK_FAILED

#: Deriving with SymPy about 10 s, the reduced design check about 15 s (2-core machine).
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
#: The example's files: the package ships them as the machine ``tractor_front_loader``.
DESCRIPTION = ROOT / "derive" / "machines" / "tractor_front_loader.toml"
VALUES = ROOT / "loader_model" / "data" / "machines" / "tractor_front_loader.toml"
G = 9.80665  # the values file's g
#: The centre of gravity of each body (x in the chassis frame at p = 0) and its mass.
BODIES = (("H", "m_1"), ("Z", "m_cab"), ("G", "m_2"), ("Q", "m_3"))


#: The name the example's copy takes outside the package: the package ships the example as
#: ``tractor_front_loader``, and a description of a shipped name resolves to the shipped machine.
EXTERNAL_NAME = "my_tractor"


@pytest.fixture(scope="module")
def machine_args(tmp_path_factory: pytest.TempPathFactory) -> list[str]:
    """``--machine``/``--params`` of the example as a user's own machine: its description under
    another name in a folder of its own, derived into the session's temporary cache."""
    from derive.__main__ import main as derive_main
    from loader_model.machines import generated_folder

    # one folder per session (and worker): a second module's copy would be another machine of
    # the same name, which a process refuses
    folder = tmp_path_factory.getbasetemp() / "my_machine"
    folder.mkdir(exist_ok=True)
    text = DESCRIPTION.read_text(encoding="utf-8")
    renamed = text.replace('name = "tractor_front_loader"', f'name = "{EXTERNAL_NAME}"', 1)
    assert renamed != text
    description, values = folder / f"{EXTERNAL_NAME}.toml", folder / f"{EXTERNAL_NAME}_values.toml"
    description.write_text(renamed, encoding="utf-8")
    values.write_text(VALUES.read_text(encoding="utf-8"), encoding="utf-8")
    assert derive_main([str(description)]) == 0
    assert (generated_folder(description) / "__init__.py").is_file()
    return ["--machine", str(description), "--params", str(values)]


def _values(load: str) -> dict[str, float]:
    data = tomllib.loads(VALUES.read_text(encoding="utf-8"))
    values = {name: entry["value"] for name, entry in data["model"].items()}
    values |= {name: entry["value"] for name, entry in data["loads"][load].items()}
    return values | {"H_x": 0.0}


@pytest.mark.parametrize(
    "load, front_kn, rear_kn", [("empty", 30.13, 24.79), ("full", 45.05, 17.71)]
)
def test_static_axle_loads_equal_the_hand_calculation(
    machine_args: list[str], load: str, front_kn: float, rear_kn: float
) -> None:
    """Moments about the rear axle of every body's weight on the level chassis; the loads the
    values file's header states (rounded to 10 N) and the derived static equilibrium's."""
    from loader_model.plant.scenario import resolve_plant

    v = _values(load)
    wheelbase = v["A_x"] - v["B_x"]
    weight = G * sum(v[m] for _, m in BODIES)
    front = G * sum(v[m] * (v[f"{p}_x"] - v["B_x"]) for p, m in BODIES) / wheelbase
    rear = weight - front
    assert (front / 1e3, rear / 1e3) == pytest.approx((front_kn, rear_kn), abs=0.006)
    assert rear > 0.25 * weight  # the rear axle keeps a quarter of the weight, full bucket too
    plant = resolve_plant(VALUES, load, machine=str(DESCRIPTION))
    derived = (plant.output("F_Ay"), plant.output("F_By"))  # at the static state
    # the derivation solves the same balance: equal to round-off of the ~50 kN loads
    assert derived == pytest.approx((front, rear), rel=1e-9)


@pytest.mark.parametrize("load, bar", [("empty", 50.88), ("full", 113.64)])
def test_static_piston_pressure_equals_the_hand_calculation(
    machine_args: list[str], load: str, bar: float
) -> None:
    """Moments about the loader pivot D of the boom's and the bucket's weight (the tilt
    cylinders are internal to the two) held by the lift cylinder pair along C -> E, its rod side
    at the charge pressure: p_A = (F / n + p_c A_B) / A_A."""
    from loader_model.plant.scenario import resolve_plant

    v = _values(load)
    data = tomllib.loads(VALUES.read_text(encoding="utf-8"))
    cyl = {name: entry["value"] for name, entry in data["cylinders"].items()}
    moment = G * (v["m_2"] * (v["G_x"] - v["D_x"]) + v["m_3"] * (v["Q_x"] - v["D_x"]))
    line = (v["E_x"] - v["C_x"], v["E_y"] - v["C_y"])
    arm = (v["E_x"] - v["D_x"], v["E_y"] - v["D_y"])
    lever = (arm[0] * line[1] - arm[1] * line[0]) / math.hypot(*line)  # dx_cyl/dφ, Eq. 35
    area_a = math.pi * cyl["piston_diameter"] ** 2 / 4
    area_b = area_a - math.pi * cyl["rod_diameter"] ** 2 / 4
    charge = data["hydraulics"]["charge_pressure"]["value"]
    p_a = (moment / lever / cyl["count"] + charge * area_b) / area_a
    assert p_a / 1e5 == pytest.approx(bar, abs=0.006)  # the values' sources state 51 and 114 bar
    plant = resolve_plant(VALUES, load, machine=str(DESCRIPTION))
    assert plant.output("p_A") == pytest.approx(p_a, rel=1e-9)


def test_full_bucket_lifts_the_rear_axle_at_the_first_board(machine_args, capsys) -> None:
    """4 s of the paper course at 9 km/h, baseline: the rear tyres leave the ground once, as
    they ride over the first board (they meet it at 2.90 s; measured off the ground from 3.055
    to 3.286 s)."""
    argv = ["simulate", *machine_args, "--load", "full", "--duration", "4"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "events: 1 (1 tyre_off_ground)" in out
    assert re.search(r"tyre_off_ground: F_By from 3\.0\d\d s", out)


def test_linear_design_is_refused_naming_the_full_bucket(
    machine_args: list[str], tmp_path: Path, capsys
) -> None:
    """The default design (ISO 2631 optimum on the linear plant, both loads) checked on the
    boards at 9 km/h: the empty bucket passes (measured −9.4 %), the full bucket fails
    (measured +77.7 %, the command at V_p,max 20.0 % and the rate 40.5 % of the run, a 5.3 Hz
    pitch oscillation of 9.1 rad/s² r.m.s. left in the last second against the baseline's
    0.84; at rest with the sensors' noise alone the pump reaches its limits too); nothing is
    written."""
    conditions = tmp_path / "conditions.toml"
    conditions.write_text(
        '[envelope]\nloads = ["empty", "full"]\nboard_speeds_kmh = [9.0]\nroad_classes = []\n'
        "[criteria]\nsampled_plants = 0\n",
        encoding="utf-8",
    )
    target = tmp_path / "tractor_gains.toml"
    argv = ["design", *machine_args, "--output", str(target), "--conditions", str(conditions)]
    assert main([*argv, "--jobs", "1", "--no-progress"]) == EXIT_CHECK_FAILED
    out = capsys.readouterr().out
    assert not target.exists()
    rows = {
        line.split("  ")[0]: line.split()
        for line in out.splitlines()
        if line.startswith(("empty, boards", "full, boards"))
    }
    empty, full = rows["empty, boards 9 km/h"], rows["full, boards 9 km/h"]
    assert empty[-1] == "pass" and float(empty[7]) < -3.0  # change [%], measured −9.4
    assert full[-1] == "FAIL" and float(full[7]) > 30.0  # measured +77.7
    assert float(full[9]) > 10.0 and float(full[10]) > 20.0  # duty [%], measured 20.0, 40.5
    assert float(full[12]) > 5.0 * float(full[14])  # residual pitch, measured 9.120 / 0.840
    failures = [line for line in out.splitlines() if line.startswith("  - ")]
    # at rest on flat ground, the sensors' noise alone sets the pump at its limits (measured:
    # command 0.3 %, rate 1.3 % of the run), so the oscillation after the boards is judged
    # against the fixed floor and is persistent
    assert failures[0].startswith("  - full, at rest with the sensors' noise alone: the pump")
    assert all(line.startswith("  - full, boards 9 km/h: ") for line in failures[1:])
    reasons = " ".join(failures)
    for reason in (
        "against the baseline",
        "pump command at V_p,max",
        "rate at its limit",
        "persistent oscillation after the road",
    ):
        assert reason in reasons
    assert "finding(s) over 2 judged conditions" in out


def test_table3_gains_pass_the_full_bucket_boards(machine_args, tmp_path: Path, capsys) -> None:
    """Table 3's gains on the full bucket's boards at 9 km/h, on the tractor's own tyres
    (0.63 m front, 0.825 m rear): slightly better than the baseline (measured −1.0 %: 2.728
    against 2.755 m/s²), the pump never at its limits, no finding."""
    conditions = tmp_path / "conditions.toml"
    conditions.write_text(
        '[envelope]\nloads = ["full"]\nboard_speeds_kmh = [9.0]\nroad_classes = []\n'
        "[criteria]\nsampled_plants = 0\n",
        encoding="utf-8",
    )
    argv = ["check-design", "default", *machine_args, "--conditions", str(conditions)]
    assert main([*argv, "--jobs", "1", "--no-progress"]) == 0
    out = capsys.readouterr().out
    row = next(line.split() for line in out.splitlines() if line.startswith("full, boards"))
    # change [%], measured −1.0: the 2 % allowance is far, the sign within a tenth of a percent
    assert row[-1] == "pass" and -3.0 < float(row[7]) < -0.1
    assert float(row[9]) == 0.0 and float(row[10]) == 0.0  # the pump never at its limits
    assert "PASSED: 1 conditions judged" in out
