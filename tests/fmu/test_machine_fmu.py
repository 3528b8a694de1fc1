"""The plant FMU of another described machine: the compact wheel loader's."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from loader_model import cli
from loader_model.fmu.variables import fmu_parameter_names, fmu_parameter_values
from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import plant_layout
from loader_model.plant.plant import plant_function
from loader_model.plant.scenario import resolve_plant
from tests.fmu.model_exchange import continuous_time_instance, pointer

fmpy = pytest.importorskip("fmpy")
fmi2 = pytest.importorskip("fmpy.fmi2")
validate_fmu = pytest.importorskip("fmpy.validation").validate_fmu

MACHINE = "compact_wheel_loader"
#: |FMU derivative − plant Function derivative| <= RTOL × (|plant's| + its state's nominal).
RTOL = 1e-9


def test_wheel_loader_fmu_derivatives_equal_the_plant_function(tmp_path: Path) -> None:
    started = time.perf_counter()
    target = tmp_path / "wheel_loader.fmu"
    argv = ["export-fmu", "--machine", MACHINE, "--controller", "none", str(target)]
    assert cli.main(argv) == 0
    layout = plant_layout(MACHINE)
    params = resolve_plant(None, "empty", machine=MACHINE).params  # the CLI default
    x0, u0 = static_state(params, MACHINE)
    w = np.zeros(len(layout.exogenous_names))
    xdot, y = (np.asarray(v).ravel() for v in plant_function(MACHINE)(x0, u0, w, params))

    md = fmpy.read_model_description(str(target), validate=True)
    by_name = {v.name: v for v in md.modelVariables}
    assert [v.name for v in md.modelVariables if v.causality == "output"] == list(
        layout.output_names
    )
    assert [d.variable.name for d in md.derivatives] == [f"der(x.{n})" for n in layout.state_names]
    names = fmu_parameter_names(plant_layout(MACHINE))
    assert not set(names) & set(layout.machine.static_names)
    for name, value in zip(names, fmu_parameter_values(params, plant_layout(MACHINE)), strict=True):
        assert float(by_name[name].start) == pytest.approx(value, rel=1e-15), name

    n = len(layout.state_names)
    states, derivatives = np.zeros(n), np.zeros(n)
    nominals = np.array([float(by_name[f"x.{n}"].nominal) for n in layout.state_names])
    moved = x0 + 0.01 * nominals * np.cos(np.arange(n))  # off the equilibrium: xdot != 0
    moved_xdot = np.asarray(plant_function(MACHINE)(moved, u0, w, params)[0]).ravel()
    moved_derivatives = np.zeros(n)
    with continuous_time_instance(target, md, "wheel_loader") as fmu:
        fmu.getContinuousStates(pointer(states), n)
        fmu.getDerivatives(pointer(derivatives), n)
        outputs = np.asarray(fmu.getReal([by_name[n].valueReference for n in layout.output_names]))
        fmu.setContinuousStates(pointer(moved), n)
        fmu.getDerivatives(pointer(moved_derivatives), n)
    np.testing.assert_allclose(states, x0, rtol=1e-12, atol=1e-12 * nominals.max())
    assert np.all(np.abs(derivatives - xdot) <= RTOL * (np.abs(xdot) + nominals))
    np.testing.assert_allclose(outputs, y, rtol=1e-9, atol=1e-9)
    scale = np.abs(moved_xdot) + nominals
    assert np.max(np.abs(moved_xdot)) > 1e-3
    assert np.all(np.abs(moved_derivatives - moved_xdot) <= RTOL * scale)
    assert time.perf_counter() - started < 60.0


@pytest.mark.parametrize(
    "controller",
    [
        "skyhook",  # four filter states, all five named sensors
        pytest.param("virtual_accumulator", marks=pytest.mark.slow),
    ],
)
def test_wheel_loader_closed_loop_fmu_reproduces_the_sampled_loop(
    controller: str, tmp_path: Path
) -> None:
    """The controller in the FMU against the simulator's settings and its discrete loop."""
    from loader_model.fmu.build import export_plant_fmu
    from loader_model.fmu.crosscheck import cross_check
    from loader_model.simulation.scenario import ride_scenario

    plant = resolve_plant(None, "full", machine=MACHINE)
    # the simulator's settings vector of this controller on this plant (its ‖p_A‖∞ and u0)
    settings = ride_scenario(plant, controller.replace("_", "-")).settings
    path = export_plant_fmu(
        tmp_path / "loop.fmu",
        plant.params,
        controller=controller,
        settings=settings,
        include_sources=False,
        machine=MACHINE,
    )
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    command = next(v for v in md.modelVariables if v.name == "V_p_ref")
    assert (command.causality, command.variability) == ("output", "discrete")
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    assert inputs == list(plant_layout(MACHINE).exogenous_names)
    check = cross_check(
        path, plant.params, controller=controller, settings=settings, machine=MACHINE
    )
    # the skid-steer's acceptance: 1e-3 of each signal's excursion
    for name in ("f_Sx", "f_Sy", "p_A", "p_B", "phi", "V_p_ref"):
        assert check.relative_error[name] < 1e-3, (name, check.relative_error)
    # the loop acts: the command leaves the holding command by more than round-off
    excursion = np.ptp(check.reference["V_p_ref"])
    assert excursion > 1e-3 * abs(plant.u0), excursion


def test_wheel_loader_closed_loop_fmu_from_the_command(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    target = tmp_path / "wl_skyhook.fmu"
    argv = ["export-fmu", "--machine", MACHINE, "--load", "full", "--controller", "skyhook"]
    assert cli.main([*argv, "--no-sources", str(target)]) == 0
    assert "compact_wheel_loader plant + skyhook controller" in capsys.readouterr().out
    md = fmpy.read_model_description(str(target), validate=True)
    names = [v.name for v in md.modelVariables]
    assert "controller.k_x" in names and "x.theta_3" in names
    states = [v.name for v in md.modelVariables if v.name.startswith("controller.z_")]
    assert states, names


def test_export_fmu_settings_without_a_reading_controller_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    settings = tmp_path / "gains.toml"
    settings.write_text("")
    argv = ["export-fmu", "--machine", MACHINE, "--settings", str(settings)]
    assert cli.main([*argv, str(tmp_path / "x.fmu")]) == 2
    assert "--controller none reads no settings" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gains.toml"]


def test_wheel_loader_fmu_reproduces_cvodes_on_its_plant_function(tmp_path: Path) -> None:
    from loader_model.fmu.build import export_plant_fmu
    from loader_model.fmu.crosscheck import cross_check

    params = resolve_plant(None, "full", machine=MACHINE).params
    path = export_plant_fmu(tmp_path / "wl.fmu", params, include_sources=False, machine=MACHINE)
    result = cross_check(path, params, machine=MACHINE)
    # the skid-steer's acceptance: 1e-3 of each signal's excursion (measured ~6e-6)
    assert max(result.relative_error.values()) < 1e-3, result.relative_error


def test_wheel_loader_closed_loop_fmu_takes_a_settings_file(tmp_path: Path) -> None:
    from loader_model.control.settings import default_settings, save_settings, with_gains

    gains = (1.5, -2.5, 3.5, 0.25)
    settings = tmp_path / "designed.toml"
    save_settings(with_gains(default_settings(), gains, "test gains"), settings)
    target = tmp_path / "designed.fmu"
    argv = ["export-fmu", "--machine", MACHINE, "--controller", "skyhook", "--no-sources"]
    assert cli.main([*argv, "--settings", str(settings), str(target)]) == 0
    md = fmpy.read_model_description(str(target))
    start = {v.name: v.start for v in md.modelVariables}
    got = [float(start[f"controller.k_{name}"]) for name in ("x", "y", "theta", "phi")]
    assert got == list(gains)
