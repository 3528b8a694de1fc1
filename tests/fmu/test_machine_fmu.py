"""The plant FMU of another described machine (issue 23): the compact wheel loader's."""

from __future__ import annotations

import ctypes
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

fmpy = pytest.importorskip("fmpy")
fmi2 = pytest.importorskip("fmpy.fmi2")

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
    names = fmu_parameter_names(MACHINE)
    assert not set(names) & set(layout.machine.static_names)
    for name, value in zip(names, fmu_parameter_values(params, MACHINE), strict=True):
        assert float(by_name[name].start) == pytest.approx(value, rel=1e-15), name

    unzipped = fmpy.extract(str(target))
    fmu = fmi2.FMU2Model(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.modelExchange.modelIdentifier,
        instanceName="wheel_loader",
    )
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    n = len(layout.state_names)
    states, derivatives = np.zeros(n), np.zeros(n)
    fmu.getContinuousStates(states.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), n)
    fmu.getDerivatives(derivatives.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), n)
    outputs = np.asarray(fmu.getReal([by_name[n].valueReference for n in layout.output_names]))
    nominals = np.array([float(by_name[f"x.{n}"].nominal) for n in layout.state_names])
    moved = x0 + 0.01 * nominals * np.cos(np.arange(n))  # off the equilibrium: xdot != 0
    moved_xdot = np.asarray(plant_function(MACHINE)(moved, u0, w, params)[0]).ravel()
    fmu.setContinuousStates(moved.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), n)
    moved_derivatives = np.zeros(n)
    fmu.getDerivatives(moved_derivatives.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), n)
    fmu.terminate()
    fmu.freeInstance()
    np.testing.assert_allclose(states, x0, rtol=1e-12, atol=1e-12 * nominals.max())
    assert np.all(np.abs(derivatives - xdot) <= RTOL * (np.abs(xdot) + nominals))
    np.testing.assert_allclose(outputs, y, rtol=1e-9, atol=1e-9)
    scale = np.abs(moved_xdot) + nominals
    assert np.max(np.abs(moved_xdot)) > 1e-3
    assert np.all(np.abs(moved_derivatives - moved_xdot) <= RTOL * scale)
    assert time.perf_counter() - started < 60.0


def test_wheel_loader_fmu_refuses_a_controller(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    argv = ["export-fmu", "--machine", MACHINE, "--controller", "skyhook", str(tmp_path / "c.fmu")]
    assert cli.main(argv) == 2
    assert "skid-steer only" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_wheel_loader_fmu_reproduces_cvodes_on_its_plant_function(tmp_path: Path) -> None:
    from loader_model.fmu.build import export_plant_fmu
    from loader_model.fmu.crosscheck import cross_check

    params = resolve_plant(None, "full", machine=MACHINE).params
    path = export_plant_fmu(tmp_path / "wl.fmu", params, include_sources=False, machine=MACHINE)
    result = cross_check(path, params, machine=MACHINE)
    # the skid-steer's acceptance (issue 15): 1e-3 of each signal's excursion (measured ~6e-6)
    assert max(result.relative_error.values()) < 1e-3, result.relative_error
