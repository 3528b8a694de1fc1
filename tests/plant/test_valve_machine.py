"""A machine with the valve-controlled lift circuit through the runtime: the example of
docs/examples/valve_wheel_loader/ (the compact wheel loader's mechanics, ``[circuit] kind =
"valve"``), derived into the session's temporary cache, rests at its static equilibrium with the
load-holding valve open and closed, and runs the paper's course at 9 km/h with the baseline and
the skyhook controller (the spool driven through the pressure loop) to finite results; a bad
``[valve]`` value is refused by the command in one line with exit code 2.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loader_model.cli import main

#: Deriving with SymPy about 8-12 s, each simulated course about 3 s (2-core machine).
pytestmark = pytest.mark.slow

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "valve_wheel_loader"
DESCRIPTION = EXAMPLE / "valve_wheel_loader.toml"
VALUES = EXAMPLE / "valve_wheel_loader_values.toml"


@pytest.fixture(scope="module")
def machine_args() -> list[str]:
    """``--machine``/``--params`` of the example, derived into the session's temporary cache."""
    from derive.__main__ import main as derive_main
    from loader_model.machines import generated_folder

    assert derive_main([str(DESCRIPTION)]) == 0
    assert (generated_folder(DESCRIPTION) / "__init__.py").is_file()
    return ["--machine", str(DESCRIPTION), "--params", str(VALUES)]


@pytest.mark.parametrize("controller", ["baseline", "skyhook"])
def test_the_valve_machine_rests_at_its_equilibrium(
    machine_args: list[str], controller: str
) -> None:
    """Open load-holding valve (skyhook): the hold spool feeds the spool's leakage, every rate
    zero; closed (baseline): the seal leakage's quasi-static drift only (a few hundred Pa/s)."""
    from loader_model.plant.plant import plant_function
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.plant.scenario import resolve_plant

    plant = resolve_plant(
        VALUES, "full", PlantOptions.for_controller(controller), machine=str(DESCRIPTION)
    )
    assert plant.layout.circuit == "valve" and plant.layout.input_names == ("x_s_ref",)
    names = plant.layout.state_names
    f = plant_function(str(DESCRIPTION))
    rate = np.asarray(f(plant.x0, plant.u0, np.zeros(f.size1_in(2)), plant.params)[0]).ravel()
    assert plant.x0[names.index("p_B")] == plant.parameter("p_tank")
    mechanical = rate[: names.index("p_A")]
    assert np.max(np.abs(mechanical)) < 1e-9
    pressures = np.abs(rate[names.index("p_A") : names.index("p_A") + 2])
    if controller == "skyhook":
        assert 0 < plant.u0 < 0.01 * plant.command_limit()  # a few um of the 5 mm stroke
        assert np.max(pressures) < 1e-6 * plant.x0[names.index("p_A")]
    else:
        assert plant.u0 == 0.0
        assert np.max(pressures) < 1e3  # Pa/s: the seals' drift


@pytest.mark.parametrize("controller", ["baseline", "skyhook"])
def test_the_valve_machine_runs_the_paper_course(
    machine_args: list[str], controller: str, tmp_path: Path
) -> None:
    output = tmp_path / f"{controller}.npz"
    argv = ["simulate", *machine_args, "--load", "full", "--controller", controller]
    assert main([*argv, "--speed", "9", "--output", str(output)]) == 0
    with np.load(output) as data:
        columns = {name: data[name] for name in data.files if data[name].dtype.kind == "f"}
    assert {"x_s", "xd_s", "x_s_ref", "Q_supply", "p_A", "f_Sy"} <= set(columns)
    assert "V_p_ref" not in columns and "V_p" not in columns
    for name, values in columns.items():
        assert np.all(np.isfinite(values)), name
    assert columns["time"][-1] > 10.0  # the whole course, not a run stopped by validity
    spool = columns["x_s"]
    if controller == "baseline":  # the spool stays centred, the cylinder sealed
        assert np.max(np.abs(spool)) == 0.0
    else:  # the pressure loop moves the spool, within its stroke
        assert 1e-5 < np.max(np.abs(spool)) <= 0.005 * 1.01


def test_a_bad_valve_value_exits_with_one_line(
    machine_args: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "values.toml"
    text = VALUES.read_text(encoding="utf-8")
    bad.write_text(text.replace("damping_ratio = { value = 0.7,", "damping_ratio = { value = 9.0,"))
    argv = ["simulate", "--machine", str(DESCRIPTION), "--params", str(bad), "--duration", "1"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert "[valve]: damping_ratio = 9.0 - is out of range; allowed: [0.05, 5]" in err, err


@pytest.mark.parametrize("controller", [None, "skyhook"])
def test_the_valve_machines_fmu_reproduces_the_simulators_plant_and_loop(
    machine_args: list[str], tmp_path: Path, controller: str | None
) -> None:
    """The FMU of a valve circuit: the spool command x_s_ref is its input (the plant) or its
    held output (the closed loop), and FMPy's run over the bump of the cross-check follows the
    reference of the plant Function and the sampled controller to 1e-4 of each signal's
    excursion (measured at most 1.6e-5; the skid-steer's acceptance is 1e-3)."""
    import numpy as np

    fmpy = pytest.importorskip("fmpy")
    validate_fmu = pytest.importorskip("fmpy.validation").validate_fmu
    from loader_model.fmu.build import export_plant_fmu, find_compiler
    from loader_model.fmu.crosscheck import cross_check
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.scenario import ride_scenario

    try:
        find_compiler()
    except ValueError:
        pytest.skip("no C compiler")
    options = PlantOptions.for_controller(controller or "baseline") if controller else None
    plant = resolve_plant(VALUES, "full", options, machine=str(DESCRIPTION))
    settings = None if controller is None else ride_scenario(plant, controller).settings
    path = export_plant_fmu(
        tmp_path / "valve.fmu",
        plant.params,
        controller=controller,
        settings=settings,
        include_sources=False,
        machine=str(DESCRIPTION),
    )
    assert validate_fmu(str(path)) == []
    command = next(v for v in fmpy.read_model_description(str(path)).modelVariables
                   if v.name == "x_s_ref")  # fmt: skip
    assert command.causality == ("input" if controller is None else "output")
    assert command.unit == "m"
    check = cross_check(
        path, plant.params, controller=controller, settings=settings, machine=str(DESCRIPTION)
    )
    for name, error in check.relative_error.items():
        assert error < 1e-4, (name, check.relative_error)
    if controller is not None:  # the loop acts: the spool leaves its holding position
        assert np.ptp(check.reference["x_s_ref"]) > 100.0 * abs(plant.u0)


def test_the_gain_gradient_runs_on_the_valve_and_names_its_spool(machine_args) -> None:
    """The machine design's runs on a valve circuit: the spool command and velocity are the
    columns the pump limits are judged on (x_s_ref, xd_s), with or without the ride control
    off below a speed."""
    import dataclasses

    import numpy as np

    from loader_model.control.settings import default_settings
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.gain_sensitivity import gain_gradient
    from loader_model.simulation.scenario import resolve_scenario
    from loader_model.simulation.settling import limit_duty
    from loader_model.simulation.simulator import course_input

    for gate_kmh, moving in ((0.0, True), (9.5, False)):
        settings = dataclasses.replace(default_settings(), ride_control_min_speed=gate_kmh / 3.6)
        scenario = resolve_scenario(
            VALUES, "full", controller="skyhook", settings=settings, machine=str(DESCRIPTION)
        )
        run = gain_gradient(scenario, course_input(paper_course(9.0), scenario))
        assert {"x_s_ref", "xd_s"} <= set(run.columns) and "V_p_ref" not in run.columns
        assert bool(np.any(run.gradient != 0.0)) is moving
        plant = scenario.plant
        duty = limit_duty(run.columns, plant.command_limit(), plant.rate_limit())
        assert 0.0 <= duty.command <= 1.0 and 0.0 <= duty.rate <= 1.0
