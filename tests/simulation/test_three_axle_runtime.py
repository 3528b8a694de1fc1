"""A three-axle machine from a description file outside the package, through the runtime (issue 23).

The fixture of ``tests/derive/three_axle_cab.py`` (axles A, B, R 1.5 m apart, a cab on a sliding
mount) is derived by ``python -m derive <file>`` into the runtime's machine cache and
loaded by ``--machine <file>``; its flat parameter file is written here from the fixture's values
(one 80 mm lift cylinder, the skid-steer's oil). Checked: it rests at its static equilibrium on
a level road, each axle's contact force answers the board its own distance behind the front axle
later (d_i / v), the simulator agrees with the CVODES reference, the ``simulate`` command runs it,
and a missing or stale generated package and a bad description are refused naming the file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.derive.three_axle_cab import DESCRIPTION, POINTS, VALUES

#: Deriving the machine with SymPy takes about 5 s, the CVODES reference about 2 s.
pytestmark = pytest.mark.slow

_CYLINDER = {  # value, unit
    "count": (1, "-"),
    "piston_diameter": (0.08, "m"),
    "rod_diameter": (0.045, "m"),
    "stroke": (0.5, "m"),
    "retracted_length": (0.9, "m"),
    "dead_volume_a": (6e-4, "m^3"),
    "dead_volume_b": (4e-4, "m^3"),
    "end_stop_stiffness": (1e8, "N/m"),
    "end_stop_damping": (1e5, "N s/m"),
}

#: Each axle's tyres (as the shipped machines': 0.42 m and the tandem cam's estimates).
_TYRE = (("R", 0.42, "m"), ("ae", 1.03, "-"), ("be", 1.0, "-"), ("ce", 1.8, "-"), ("ls", 0.8, "-"))


def _parameter_text(units: dict[str, str], computed: set[str]) -> str:
    values = VALUES | {f"{k}_{a}": v[i] for k, v in POINTS.items() for i, a in enumerate("xy")}
    lines = ["[model]"]
    lines += [
        f'{name} = {{ value = {values[name]!r}, unit = "{unit}", source = "test" }}'
        for name, unit in units.items()
        if name not in computed
    ]
    lines += ["", "[cylinders]"]
    lines += [
        f'{k} = {{ value = {v!r}, unit = "{u}", source = "test" }}'
        for k, (v, u) in _CYLINDER.items()
    ]
    lines += [
        "",
        "[hydraulics]",
        'bulk_modulus = { value = 1.64e9, unit = "Pa", source = "test" }',
        'charge_pressure = { value = 2.0e6, unit = "Pa", source = "test" }',
        "",
        "[tyres]",
        *(
            f'{name}_{axle} = {{ value = {value!r}, unit = "{unit}", source = "test" }}'
            for axle in "ABR"
            for name, value, unit in _TYRE
        ),
        "",
        "[loads.empty]",
        'm_2 = { value = 900.0, unit = "kg", source = "test" }',
        "",
        "[loads.full]",
        'm_2 = { value = 1200.0, unit = "kg", source = "test" }',
    ]
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """The description (derived into the cache by ``python -m derive``) and its parameter file."""
    from derive.__main__ import main as derive_main
    from loader_model.machines import generated_folder, machine

    root = tmp_path_factory.mktemp("machine")
    description = root / "three_axle_cab.toml"
    description.write_text(DESCRIPTION, encoding="utf-8")
    assert derive_main([str(description)]) == 0
    assert (generated_folder(description) / "__init__.py").is_file()
    assert [path.name for path in root.iterdir()] == ["three_axle_cab.toml"]  # nothing beside it
    info = machine(description)
    params = root / "three_axle_cab_parameters.toml"
    params.write_text(_parameter_text(info.parameter_units, set(info.static_names)), "utf-8")
    return description, params


@pytest.fixture(scope="module")
def plant(files: tuple[Path, Path]):
    from loader_model.plant.scenario import resolve_plant

    description, params = files
    return resolve_plant(params, "empty", machine=str(description))


@pytest.fixture(scope="module")
def board_run(plant):
    """One 4 cm board at 9 km/h, the front axle 1 m before it (2.3 s of road)."""
    from loader_model.simulation.courses import Course, single_obstacle_course
    from loader_model.simulation.simulator import course_input, simulate

    single = single_obstacle_course(9.0)
    road = course_input(Course(single.profile, single.speed_m_s, -1.0, 0.5, "board"), plant)
    return road, simulate(road, plant)


def test_machine_from_file_has_three_axles_and_their_inputs(plant) -> None:
    info = plant.layout.machine
    assert info.axles == ("A", "B", "R")
    assert info.package.startswith("loader_model_machine_three_axle_cab_")
    names = [f"w{d}_{a}{e}" for d in ("", "d") for a in "ABR" for e in "xy"]
    assert plant.layout.exogenous_names == (*names, "F_dx", "F_dy", "M_d")
    assert {"F_Ay", "F_By", "F_Ry", "phi"} <= set(plant.layout.output_names)


def test_rests_at_static_equilibrium_on_a_level_road(plant) -> None:
    """Accelerations at the static state 6e-17 g measured; over 1 s of level road the tyre
    loads stay within 1e-10 N of 28 kN and the coordinates within 4e-17 m or rad."""
    from loader_model.plant.plant import plant_function
    from loader_model.simulation.courses import Course
    from loader_model.simulation.roads import flat_road
    from loader_model.simulation.simulator import course_input, simulate

    info, layout = plant.layout.machine, plant.layout
    n_p, g = info.n_coordinates, plant.parameter("g")
    w0 = np.zeros(len(layout.exogenous_names))
    xdot = np.asarray(plant_function(info.name)(plant.x0, plant.u0, w0, plant.params)[0]).ravel()
    assert np.abs(xdot[n_p : 2 * n_p]).max() < 1e-12 * g
    loads = np.array([plant.output(f"F_{a}y") for a in info.axles])
    weight = g * sum(plant.parameter(m) for m in ("m_1", "m_2", "m_cab"))
    assert loads.sum() == pytest.approx(weight, rel=1e-12)
    assert np.all(loads > 0.2 * weight)  # each axle carries its share (28.2, 27.5, 26.7 kN)
    level = Course(flat_road(100.0), 2.5, 0.0, 1.0, "level")
    result = simulate(course_input(level, plant), plant, duration_s=1.0)
    for axle, load in zip(info.axles, loads, strict=True):
        assert np.abs(result.columns[f"F_{axle}y"] - load).max() < 1e-9 * load
    for name in info.coordinate_names:
        assert np.abs(result.columns[name] - result.columns[name][0]).max() < 1e-12


def test_each_axle_meets_the_board_delayed_by_its_distance(board_run) -> None:
    """The steep rise of each axle's contact force (its force rate first above 30 % of its own
    peak; the chassis' pitch moves the other axles' forces far more slowly) comes d_i / v after
    the front axle's: measured 0.601 s and 1.201 s for 0.6 s and 1.2 s, one 1 ms period late."""
    road, result = board_run
    assert road.axle_offsets_m == pytest.approx((0.0, 1.5, 3.0), abs=1e-12)
    onsets = []
    for axle in road.axle_names:
        force = result.columns[f"F_{axle}y"]
        rate = np.abs(np.gradient(force, result.time_s))
        onsets.append(result.time_s[np.argmax(rate > 0.3 * rate.max())])
    delays = np.array(onsets) - onsets[0]
    expected = np.array(road.axle_offsets_m) / road.speed_m_s
    np.testing.assert_allclose(delays, expected, atol=3e-3)  # three controller periods


def test_simulator_agrees_with_the_cvodes_reference(plant, board_run) -> None:
    """Largest difference over the board run, relative to each signal's range: measured
    2.3e-4 (f_Sx), 2.2e-4 (F_Ry, p_A), 1.7e-4 (F_Ay), 7.9e-5 (f_Sy), 4.4e-5 (F_By)."""
    from loader_model.simulation.reference import reference_simulation

    road, result = board_run
    name = plant.layout.machine.name
    reference = reference_simulation(road, plant.params, machine=name)
    for signal in ("F_Ay", "F_By", "F_Ry", "f_Sx", "f_Sy", "p_A"):
        expected = reference["y"][:, plant.layout.output_names.index(signal)]
        actual = result.columns[signal][: expected.size]
        assert np.abs(actual - expected).max() < 2e-3 * np.ptp(expected), signal


def test_simulate_command_takes_the_description_file(
    files: tuple[Path, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from loader_model.cli import main

    description, params = files
    output = tmp_path / "run.csv"
    argv = ["simulate", "--machine", str(description), "--params", str(params)]
    assert main([*argv, "--course", "single", "--duration", "4", "--output", str(output)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("three_axle_cab: single obstacle") and "a_w" in out
    header = output.read_text(encoding="utf-8").splitlines()[0].split(",")
    assert {"F_Ry [N]", "xi_R [m]", "w_Ry [m]", "wd_Ry [m/s]"} <= set(header)


def test_missing_or_stale_generated_package_is_refused_naming_the_command(
    files: tuple[Path, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from loader_model.cli import main

    _, params = files
    elsewhere = tmp_path / "three_axle_cab.toml"
    elsewhere.write_text(DESCRIPTION + "# another version\n", encoding="utf-8")
    argv = ["simulate", "--params", str(params), "--duration", "4", "--machine", str(elsewhere)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"{elsewhere}: machine 'three_axle_cab' has no generated package for this " in err
    assert f"-m derive {elsewhere}`" in err and "Traceback" not in err
    stale = files[0].with_name("three_axle_cab.toml")
    original = stale.read_text(encoding="utf-8")
    try:
        stale.write_text(original.replace("k_cab = { unit", "k_cab = {  unit"), "utf-8")
        assert main([*argv[:-1], str(stale)]) == 2
    finally:
        stale.write_text(original, encoding="utf-8")
    err = capsys.readouterr().err
    assert "has no generated package for this version of the file" in err
    assert f"-m derive {stale}`" in err and "Traceback" not in err


def test_bad_description_entry_is_refused_by_derive_naming_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from derive.__main__ import main as derive_main

    bad = tmp_path / "bad.toml"
    bad.write_text(
        DESCRIPTION.replace('parent = "chassis"\nat = "D"', 'parent = "frame"\nat = "D"')
    )
    assert derive_main([str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.toml" in err and "frame" in err and "Traceback" not in err
    assert not (tmp_path / "bad_generated").exists()
    assert derive_main([str(tmp_path / "missing.toml")]) == 2
    assert "missing.toml: no such description file" in capsys.readouterr().err


def test_lift_off_events_and_airborne_check_cover_every_axle(plant, board_run) -> None:
    """Synthetic rows from the board run: the rear axle R alone off the ground for 0.2 s is a
    lift-off event of F_Ry and no flight (the others carry the machine); all three off for
    longer than the bound stops the run, naming all three."""
    from loader_model.simulation.events import find_events
    from loader_model.simulation.validity import validity_bounds
    from loader_model.simulation.validity_check import ValidityMonitor

    _, result = board_run
    layout = plant.layout
    outputs = np.column_stack([result.columns[n] for n in layout.output_names])
    states = np.column_stack([result.columns[n] for n in layout.state_names])
    rear_off = outputs.copy()
    rear_off[1000:1200, layout.output_names.index("F_Ry")] = 0.0
    bounds = validity_bounds(plant.params, layout=layout)
    assert ValidityMonitor(bounds, 1e-3, layout).check(0, states, rear_off) is None
    columns = dict(result.columns) | {"F_Ry": rear_off[:, layout.output_names.index("F_Ry")]}
    events = find_events(
        result.time_s, columns, stroke_m=0.5, max_displacement=1.0, axles=("A", "B", "R")
    )
    assert [(e.kind, e.signal, e.start_s) for e in events] == [("tyre_off_ground", "F_Ry", 1.0)]
    airborne = outputs.copy()
    rows = slice(1000, 1000 + round(bounds.airborne_s / 1e-3) + 5)
    airborne[rows, [layout.output_names.index(f"F_{a}y") for a in "ABR"]] = 0.0
    violation = ValidityMonitor(bounds, 1e-3, layout).check(0, states, airborne)
    assert violation is not None and violation.bound == "airborne_s"
    assert violation.signal == "F_Ay, F_By, F_Ry"
    assert "all 3 tyres off the ground (F_Ay = F_By = F_Ry = 0)" in violation.describe()


def test_export_fmu_carries_every_axle(files: tuple[Path, Path], tmp_path: Path) -> None:
    """`export-fmu --machine FILE`: the plant FMU of the three-axle machine has the third
    axle's road inputs and tyre output, starts at the static equilibrium, and its derivatives
    off the equilibrium equal the plant Function's (to 1e-9 of each derivative plus its
    state's nominal, the wheel loader's FMU tolerance)."""
    fmpy = pytest.importorskip("fmpy")
    from loader_model.cli import main
    from loader_model.plant.plant import plant_function
    from tests.fmu.model_exchange import continuous_time_instance, pointer

    description, params = files
    target = tmp_path / "three_axle.fmu"
    argv = ["export-fmu", "--machine", str(description), "--params", str(params)]
    assert main([*argv, "--controller", "none", str(target)]) == 0
    model = fmpy.read_model_description(str(target), validate=True)
    by_name = {v.name: v for v in model.modelVariables}
    assert {"w_Ry", "wd_Ry", "F_Ry"} <= set(by_name)
    assert by_name["w_Ry"].description == "road under the axle R, vertical"
    plant = _plant_of(files)
    layout, n = plant.layout, len(plant.layout.state_names)
    nominals = np.array([float(by_name[f"x.{name}"].nominal) for name in layout.state_names])
    moved = plant.x0 + 0.01 * nominals * np.cos(np.arange(n))
    states, derivatives = np.zeros(n), np.zeros(n)
    with continuous_time_instance(target, model, "three_axle") as fmu:
        fmu.getContinuousStates(pointer(states), n)
        fmu.setContinuousStates(pointer(moved), n)
        fmu.getDerivatives(pointer(derivatives), n)
    w = np.zeros(len(layout.exogenous_names))
    expected = np.asarray(
        plant_function(layout.machine.name)(moved, plant.u0, w, plant.params)[0]
    ).ravel()
    np.testing.assert_allclose(states, plant.x0, rtol=1e-12, atol=1e-12 * nominals.max())
    assert np.max(np.abs(expected)) > 1e-3  # off the equilibrium
    assert np.all(np.abs(derivatives - expected) <= 1e-9 * (np.abs(expected) + nominals))


def _plant_of(files: tuple[Path, Path]):
    from loader_model.plant.scenario import resolve_plant

    description, params = files
    return resolve_plant(params, "empty", machine=str(description))


def test_comfort_design_drives_every_axle(files: tuple[Path, Path], tmp_path: Path) -> None:
    """The comfort plant's road model has one independent ISO 8608 track per axle (the
    ``road_filter`` limit the two-axle design uses): the third axle's road enters the design's
    plant, and ``loader-model design --machine FILE --method lqr`` writes its gains."""
    from loader_model.cli import main
    from loader_model.control.comfort_plant import PERFORMANCE, comfort_case, comfort_system
    from loader_model.plant.scenario import resolve_plant

    description, params = files
    plant = resolve_plant(params, "empty", machine=str(description))
    system = comfort_system(comfort_case("empty", plant), "C", 2.5)
    noise = [n for n in system.input_labels if n.startswith("nu_")]
    assert noise == ["nu_road", "nu_rear", "nu_rear_R"]
    # each axle's track reaches the weighted seat: |G(j 2π 2 Hz)| from each noise input
    response = system(2j * np.pi * 2.0)
    rows = [system.output_labels.index(name) for name in PERFORMANCE]
    gains = [np.linalg.norm(response[rows, system.input_labels.index(n)]) for n in noise]
    print("seat response per axle track at 2 Hz:", gains)
    assert min(gains) > 0.05 * max(gains)
    output = tmp_path / "gains.toml"
    argv = ["design", "--machine", str(description), "--params", str(params), "--method", "lqr"]
    # the gains, not their nonlinear check (tests/experiments/test_design_check.py), are tested
    assert main([*argv, "--output", str(output), "--no-check", "--force"]) == 0
    assert "k_fb" in output.read_text(encoding="utf-8")


def test_modes_command_labels_the_sliding_mount_in_metres(
    files: tuple[Path, Path], capsys: pytest.CaptureFixture[str]
) -> None:
    """`loader-model modes --machine FILE`: the cab's travel is a length (m), the pinned bodies'
    coordinates angles (rad), from the description's joints, not from the coordinate names."""
    from loader_model.cli import main

    description, params = files
    assert main(["modes", "--machine", str(description), "--params", str(params)]) == 0
    out = capsys.readouterr().out
    assert "s_cab [m]" in out and "s_cab [rad]" not in out
    assert "theta_2 [rad]" in out and "x_H [m]" in out


def test_robustness_study_of_the_description_file_in_worker_processes(
    files: tuple[Path, Path], tmp_path: Path
) -> None:
    """`[study] machine` = the description file and `[study] params` = its flat file: two
    worker processes (each resolves the file again) run the baseline, the Table 3 skyhook and
    gains designed on the machine's own comfort plants; without `params` the study is refused
    naming the key."""
    from loader_model.robustness.engine import run_study
    from loader_model.robustness.study import parse_study

    description, params = files
    text = f"""
[study]
machine = "{description}"
params = "{params}"
seed = 3
samples = 2
duration_s = 3.0
batch_size = 1
[conditions]
speeds_kmh = [9.0]
loads = ["empty"]
[controllers]
compare = ["skyhook"]
gains = {{ lqr = "lqr" }}
[parameters]
"hydraulics.bulk_modulus" = {{ distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }}
"""
    study = parse_study(text)
    assert study.machine == str(description.resolve()) and study.params == str(params.resolve())
    rows = run_study(study, tmp_path / "study", workers=2, progress=False).to_pylist()
    assert len(rows) == 2 * 3  # 2 samples x (baseline, skyhook, lqr)
    assert not [r["reason"] for r in rows if r["failed"]]
    assert all(r["a_total"] > 0 for r in rows)
    with pytest.raises(
        ValueError, match=r"study\.params: missing key; machine .* description file"
    ):
        parse_study(text.replace(f'params = "{params}"\n', ""))
    with pytest.raises(ValueError, match=r"study\.params = 'nowhere\.toml': allowed: the path"):
        parse_study(text.replace(f'params = "{params}"', 'params = "nowhere.toml"'))
