"""The plant FMU (issue 15): model description, FMPy validation, cross-check, command errors."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

from loader_model import cli
from loader_model.fmu import build
from loader_model.fmu.crosscheck import cross_check
from loader_model.fmu.model_description import MODEL_IDENTIFIER, model_description_xml
from loader_model.fmu.variables import FMU_PARAMETER_NAMES, fmu_parameter_values, fmu_variables
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import EXOGENOUS_NAMES, OUTPUT_NAMES, STATE_NAMES
from loader_model.plant.plant_parameters import (
    PLANT_PARAMETER_NAMES,
    PLANT_PARAMETER_UNITS,
    plant_parameter_vector,
)

fmpy = pytest.importorskip("fmpy")
validate_fmu = pytest.importorskip("fmpy.validation").validate_fmu

#: Acceptance tolerance of the cross-check (issue 15): relative to each signal's excursion.
CROSS_CHECK_RTOL = 1e-3


@pytest.fixture(scope="module")
def params() -> np.ndarray:
    return plant_parameter_vector(None, "empty")


@pytest.fixture(scope="module")
def plant_fmu(params: np.ndarray, tmp_path_factory: pytest.TempPathFactory) -> Path:
    return build.export_plant_fmu(tmp_path_factory.mktemp("fmu") / "plant.fmu", params)


def test_model_description_names_units_causality_and_start_values(
    params: np.ndarray, tmp_path: Path
) -> None:
    x0, u0 = static_state(params)
    xml = model_description_xml(fmu_variables(params, x0, u0), "{guid}", "test", "test")
    (tmp_path / "modelDescription.xml").write_bytes(xml)
    md = fmpy.read_model_description(str(tmp_path / "modelDescription.xml"), validate=True)
    assert md.fmiVersion == "2.0"
    assert md.modelExchange.modelIdentifier == MODEL_IDENTIFIER
    by_name = {v.name: v for v in md.modelVariables}
    assert len(by_name) == len(md.modelVariables)  # names unique
    assert not [name for name in by_name if "__" in name]
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    assert inputs == ["V_p_ref", *EXOGENOUS_NAMES]
    assert [v.name for v in md.modelVariables if v.causality == "output"] == list(OUTPUT_NAMES)
    assert [d.variable.name for d in md.derivatives] == [f"der(x.{n})" for n in STATE_NAMES]
    assert [d.variable.derivative.name for d in md.derivatives] == [f"x.{n}" for n in STATE_NAMES]
    for name, value in zip(FMU_PARAMETER_NAMES, fmu_parameter_values(params), strict=True):
        variable = by_name[name]
        assert variable.causality == "parameter" and variable.variability == "fixed"
        assert float(variable.start) == pytest.approx(value, rel=1e-15)
        unit = PLANT_PARAMETER_UNITS[name]
        assert variable.unit == (None if unit == "-" else unit), name
        assert variable.description
    for name, value in zip(STATE_NAMES, x0, strict=True):
        assert float(by_name[f"x.{name}"].start) == pytest.approx(value, rel=1e-15, abs=0.0)
    assert float(by_name["V_p_ref"].start) == pytest.approx(u0, rel=1e-15)
    assert by_name["f_Sy"].unit == "m/s^2" and by_name["p_A"].unit == "Pa"
    assert set(FMU_PARAMETER_NAMES) == set(PLANT_PARAMETER_NAMES) - {"F_Ay0", "F_By0"}


def test_fmu_validates_and_holds_its_equilibrium(plant_fmu: Path) -> None:
    assert validate_fmu(str(plant_fmu)) == []
    with zipfile.ZipFile(plant_fmu) as archive:
        assert f"binaries/linux64/{MODEL_IDENTIFIER}.so" in archive.namelist()
    result = fmpy.simulate_fmu(str(plant_fmu), stop_time=0.2, output=["f_Sy", "p_A", "phi"])
    assert np.ptp(result["p_A"]) < 1e-6 * result["p_A"][0]  # at rest: no drift
    assert np.max(np.abs(result["phi"])) < 1e-12


def test_fmu_recomputes_the_equilibrium_for_changed_parameters(
    plant_fmu: Path, params: np.ndarray
) -> None:
    changed = params.copy()
    changed[PLANT_PARAMETER_NAMES.index("m_2")] *= 1.2
    x0, u0 = static_state(changed)
    result = fmpy.simulate_fmu(
        str(plant_fmu),
        stop_time=0.1,
        start_values={"m_2": float(changed[PLANT_PARAMETER_NAMES.index("m_2")]), "V_p_ref": u0},
        output=["p_A", "phi"],
    )
    assert result["p_A"][0] == pytest.approx(x0[STATE_NAMES.index("p_A")], rel=1e-12)
    assert result["p_A"][-1] == pytest.approx(x0[STATE_NAMES.index("p_A")], rel=1e-6)


def test_fmu_reproduces_cvodes_on_the_plant_function(plant_fmu: Path, params: np.ndarray) -> None:
    check = cross_check(plant_fmu, params)
    assert np.ptp(check.reference["f_Sy"]) > 1.0  # the bump does excite the seat [m/s²]
    for name in ("f_Sx", "f_Sy", "p_A", "p_B"):
        assert check.relative_error[name] < CROSS_CHECK_RTOL, (name, check.relative_error)


@pytest.mark.parametrize(
    "controller",
    [
        "skyhook",  # the most involved: four filter states, all five sensors
        pytest.param("virtual_accumulator", marks=pytest.mark.slow),
        pytest.param("baseline", marks=pytest.mark.slow),
    ],
)
def test_closed_loop_fmu_reproduces_the_sampled_loop(
    controller: str, params: np.ndarray, tmp_path: Path
) -> None:
    """The controller sampled by time events in the FMU against the project's discrete loop."""
    from loader_model.control.settings import default_settings, settings_vector_for_plant
    from loader_model.parameters.sets import bucket_load

    settings = settings_vector_for_plant(
        default_settings(), params, bucket_load("empty").pressure_normalisation
    )
    path = build.export_plant_fmu(
        tmp_path / "loop.fmu", params, controller=controller, settings=settings
    )
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    command = next(v for v in md.modelVariables if v.name == "V_p_ref")
    assert (command.causality, command.variability) == ("output", "discrete")
    assert [v.name for v in md.modelVariables if v.causality == "input"] == list(EXOGENOUS_NAMES)
    check = cross_check(path, params, controller=controller, settings=settings)
    for name in ("f_Sx", "f_Sy", "p_A", "p_B", "V_p_ref"):
        assert check.relative_error[name] < CROSS_CHECK_RTOL, (name, check.relative_error)


def _no_partial(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_export_fmu_command_writes_an_fmu(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    target = tmp_path / "full.fmu"
    assert cli.main(["export-fmu", "--load", "full", "--no-sources", str(target)]) == 0
    assert "FMI 2.0 Model Exchange" in capsys.readouterr().out
    assert _no_partial(tmp_path) == ["full.fmu"]
    with zipfile.ZipFile(target) as archive:
        assert not [n for n in archive.namelist() if n.startswith("sources/")]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--load", "heavy"], "neither a load case"),
        (["--params", "missing.toml"], "missing.toml"),
    ],
)
def test_export_fmu_bad_arguments(
    tmp_path: Path, capsys: pytest.CaptureFixture, argv: list[str], message: str
) -> None:
    assert cli.main(["export-fmu", *argv, str(tmp_path / "x.fmu")]) == 2
    assert message in capsys.readouterr().err
    assert _no_partial(tmp_path) == []


def test_export_fmu_unknown_controller_exits_2(tmp_path: Path) -> None:
    with pytest.raises(SystemExit) as raised:
        cli.main(["export-fmu", "--controller", "lqr", str(tmp_path / "x.fmu")])
    assert raised.value.code == 2
    assert _no_partial(tmp_path) == []


@pytest.mark.parametrize("output", ["missing/x.fmu", "x.zip", "."])
def test_export_fmu_bad_output(tmp_path: Path, capsys: pytest.CaptureFixture, output: str) -> None:
    assert cli.main(["export-fmu", str(tmp_path / output)]) == 2
    assert "FMU" in capsys.readouterr().err
    assert _no_partial(tmp_path) == []


def test_export_fmu_without_compiler(
    tmp_path: Path, capsys: pytest.CaptureFixture, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("CC", raising=False)
    monkeypatch.setattr(build.shutil, "which", lambda name: None)
    assert cli.main(["export-fmu", str(tmp_path / "x.fmu")]) == 2
    assert "no C compiler found" in capsys.readouterr().err
    assert _no_partial(tmp_path) == []


def test_failed_compilation_leaves_no_file(
    tmp_path: Path, capsys: pytest.CaptureFixture, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("CC", "false")  # a "compiler" that always fails
    (tmp_path / "keep.fmu").write_bytes(b"old")
    assert cli.main(["export-fmu", str(tmp_path / "keep.fmu")]) == 2
    assert "failed" in capsys.readouterr().err
    assert _no_partial(tmp_path) == ["keep.fmu"]
    assert (tmp_path / "keep.fmu").read_bytes() == b"old"
