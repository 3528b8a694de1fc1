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
        (
            ["--course", "iso8608:Z"],
            "--course must be paper, boards, single, iso8608:A to iso8608:H or a course file FILE.toml",
        ),
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


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--board-height", "0.06"], "--board-height: allowed only with --course boards"),
        (
            ["--course", "boards", "--board-height", "-0.04"],
            "--board-height must be a finite number in (0, 0.5] m; got -0.04",
        ),
        (
            ["--course", "boards", "--board-spacing", "0.1"],
            "--board-spacing must be a finite number in (0.14, 1000] m; got 0.1",
        ),
        (["--course", "boards", "--boards", "0"], "--boards must be an integer in [1, 1000]"),
        (["--course", "no_such.toml"], "course file no_such.toml: "),
    ],
)
def test_simulate_course_errors_are_clear(tmp_path, capsys, monkeypatch, arguments, message):
    """Bad board options or course file: exit code 2, one line naming it, no files."""
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", "--output", "out.csv", *arguments]) == 2
    error = capsys.readouterr().err
    assert message in error and "Traceback" not in error
    assert list(tmp_path.iterdir()) == []


def test_simulate_bad_course_file_names_every_bad_entry(tmp_path, capsys):
    path = tmp_path / "yard.toml"
    path.write_text(
        "[[obstacles]]\nposition_m = 0.0\nheight_m = -0.04\nlength_m = 0.14\n"
        '[[obstacles]]\nposition_m = 3.0\nheight_m = 0.04\nlength_m = 0\nshape = "cone"\n',
        encoding="utf-8",
    )
    assert main(["simulate", "--course", str(path)]) == 2
    error = capsys.readouterr().err
    assert "obstacles[1].height_m: -0.04 is not allowed; give a number in (0, 0.5] m" in error
    assert "obstacles[2].length_m: 0 is not allowed; give a number in (0, 20] m" in error
    assert "obstacles[2].shape: 'cone' is not allowed" in error
    assert len(error.strip().splitlines()) == 1


def test_simulate_runs_a_course_file(tmp_path, capsys):
    """A course file drives its own obstacles (3 s, the seat weighting needs 2.6 s)."""
    path = tmp_path / "yard.toml"
    path.write_text(
        'name = "yard"\n[[obstacles]]\nposition_m = 0.0\nheight_m = 0.05\nlength_m = 0.6\n'
        'shape = "bump"\n',
        encoding="utf-8",
    )
    assert main(["simulate", "--course", str(path), "--duration", "3", "--speed", "12"]) == 0
    assert "yard at 12 km/h; baseline controller" in capsys.readouterr().out


def test_board_options_shape_the_board_course():
    """--course boards with the --board-* options is board_course_at with those arguments."""
    import argparse

    from loader_model.commands.course_options import course_from_arguments
    from loader_model.commands.simulate_command import add_arguments
    from loader_model.simulation.courses import board_course_at

    parser = argparse.ArgumentParser()
    add_arguments(parser)
    args = parser.parse_args(
        ["--course", "boards", "--speed", "12", "--board-height", "0.03", "--board-spacing",
         "4", "--board-length", "0.2", "--boards", "3"]
    )  # fmt: skip
    course = course_from_arguments(args)
    expected = board_course_at(12.0, spacing_m=4.0, height_m=0.03, length_m=0.2, count=3)
    assert course.name == "3 boards 30 mm x 200 mm, 4 m apart, at 12 km/h" == expected.name
    assert course.profile.distance_m.tobytes() == expected.profile.distance_m.tobytes()
    assert course.profile.height_m.tobytes() == expected.profile.height_m.tobytes()
