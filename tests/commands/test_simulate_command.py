"""``loader-model simulate``: evaluation printed, files written whole, clear errors, no partial files."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.cli import main


def test_simulate_writes_series_and_plot(tmp_path, capsys) -> None:
    """Single board, passive, 3 s (the weighting filters need 2.6 s): table, CSV, PNG."""
    output = tmp_path / "run.csv"
    code = main(
        ["simulate", "--controller", "passive", "--course", "single", "--speed", "17",
         "--duration", "3", "--output", str(output)]
    )  # fmt: skip
    assert code == 0
    text = capsys.readouterr().out
    assert "vibration total value a_total (paper Eq. 50)" in text and "pitch" in text
    assert "events:" in text
    header = output.read_text().splitlines()[0]
    assert header.startswith("time [s],x_H [m]") and "f_Sy [m/s^2]" in header
    table = np.loadtxt(output, delimiter=",", skiprows=1)
    assert table.shape[0] == 3000 and np.all(np.isfinite(table))
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (
            ["--course", "paper", "--speed", "12"],
            "--speed 12: allowed with --course paper: 9 or 18",
        ),
        (["--course", "moon"], "--course must be"),
        (["--course", "iso8608:Z"], "--course must be paper, single or iso8608:A to iso8608:H"),
        (["--duration", "0"], "--duration"),
        (["--output", "run.txt"], "allowed"),
        (["--load", "no-such-file"], "neither a load case"),
    ],
)
def test_simulate_errors_are_clear(tmp_path, capsys, monkeypatch, arguments, message) -> None:
    """Bad arguments: exit code 2, one line naming the problem, no traceback, no files."""
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", "--output", "out.csv", *arguments]) == 2
    error = capsys.readouterr().err
    assert message in error and "Traceback" not in error
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("controller", ["virtual-accumulator", "skyhook"])
def test_ride_controllers_run_from_their_fixed_point(controller: str, capsys) -> None:
    """The controllers of loader_model.control close the loop in the simulator; started at their
    fixed point they leave a resting loader at rest (no start transient from the static p_A)."""
    from loader_model.parameters.sets import bucket_load
    from loader_model.plant.plant_parameters import plant_parameter_vector
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.ride_control import controller_setup, plant_controller
    from loader_model.simulation.simulator import course_input, simulate

    params = plant_parameter_vector(None, "empty")
    settings, state = controller_setup(
        controller, params, bucket_load("empty").pressure_normalisation
    )
    course = paper_course(9)
    result = simulate(
        course_input(course, params),
        params,
        plant_controller(controller),
        settings=settings,
        controller_state=state,
        duration_s=1.0,  # the first board comes later: the loader rests
    )
    # at rest: the piston pressure holds within 1 Pa of 89 bar, the chassis does not move
    assert np.ptp(result["p_A"]) < 1.0
    assert np.abs(result["y_H"]).max() < 1e-9
    assert (
        main(["simulate", "--controller", controller, "--course", "single", "--duration", "4"]) == 0
    )
    assert "a_total" in capsys.readouterr().out
