"""Board courses at any speed, spacing, height and length, and obstacle lists of the user's own."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from loader_model.simulation.courses import (
    LEAD_IN_M,
    board_course_at,
    boards_at_speed,
    paper_course,
)
from loader_model.simulation.obstacles import (
    CourseFileError,
    Obstacle,
    load_course_file,
    obstacle_course,
    obstacle_profile,
)


@pytest.mark.parametrize("speed_kmh", [9, 18])
def test_board_course_defaults_are_the_paper_course(speed_kmh):
    paper, boards = paper_course(speed_kmh), board_course_at(speed_kmh)
    assert paper.profile.distance_m.tobytes() == boards.profile.distance_m.tobytes()
    assert paper.profile.height_m.tobytes() == boards.profile.height_m.tobytes()
    assert (paper.speed_m_s, paper.start_m, paper.settle_s) == (
        boards.speed_m_s,
        boards.start_m,
        boards.settle_s,
    )
    assert boards.name == boards_at_speed(speed_kmh).name


def test_board_course_takes_speed_spacing_height_length_and_count():
    course = board_course_at(12.0, spacing_m=4.0, height_m=0.06, length_m=0.2, count=3)
    np.testing.assert_allclose(
        course.profile.distance_m, [0, 0, 0.2, 0.2, 4, 4, 4.2, 4.2, 8, 8, 8.2, 8.2], atol=1e-12
    )
    np.testing.assert_array_equal(course.profile.height_m, np.tile([0, 0.06, 0.06, 0], 3))
    assert course.speed_m_s == pytest.approx(12.0 / 3.6, rel=1e-15)
    assert course.name == "3 boards 60 mm x 200 mm, 4 m apart, at 12 km/h"


@pytest.mark.parametrize(
    ("keywords", "message"),
    [
        ({"height_m": -0.04}, r"height_m must be a finite number in \(0, 0.5\] m; got -0.04"),
        ({"length_m": 6.0}, r"length_m must be a finite number in \(0, 5\] m; got 6.0"),
        ({"spacing_m": 0.1}, r"spacing_m must be a finite number in \(0.14, 1000\] m; got 0.1"),
        ({"count": 0}, r"count must be an integer in \[1, 1000\] boards; got 0"),
        ({"speed_kmh": 0.0}, r"speed_kmh must be a finite number in \(0, 100\] km/h; got 0.0"),
    ],
)
def test_board_course_errors_name_argument_value_and_range(keywords, message):
    arguments = {"speed_kmh": 9.0, **keywords}
    with pytest.raises(ValueError, match=message):
        board_course_at(**arguments)


def test_obstacle_shapes_and_order():
    profile = obstacle_profile(
        [
            Obstacle(5.0, 0.08, 0.6, "bump"),
            Obstacle(1.0, 0.04, 0.14),
            Obstacle(8.0, 0.05, 0.5, "pit"),
        ]
    )
    np.testing.assert_allclose(
        profile.distance_m, [1, 1, 1.14, 1.14, 5, 5.3, 5.6, 8, 8, 8.5, 8.5], atol=1e-12
    )
    np.testing.assert_allclose(
        profile.height_m, [0, 0.04, 0.04, 0, 0, 0.08, 0, 0, -0.05, -0.05, 0], atol=0
    )
    # the bump's flanks are linear: half height a quarter of its length in
    assert float(profile.height(5.15)) == pytest.approx(0.04, abs=1e-15)


def test_obstacle_course_starts_before_the_first_obstacle():
    course = obstacle_course([Obstacle(20.0, 0.04, 0.14)], 9.0, name="yard")
    assert course.start_m == 20.0 - LEAD_IN_M
    assert course.name == "yard at 9 km/h"
    drive = course.road_input(1.2)
    assert drive.road_m[:, 1].max() == pytest.approx(0.04, abs=1e-12)


def test_obstacles_that_touch_are_refused():
    with pytest.raises(ValueError, match=r"obstacles\[2\].position_m: 1.14 is not allowed"):
        obstacle_profile([Obstacle(1.0, 0.04, 0.14), Obstacle(1.14, 0.04, 0.14)])


YARD = """
name = "my yard"

[[obstacles]]
position_m = 0.0
height_m = 0.04
length_m = 0.14

[[obstacles]]
position_m = 6.0
height_m = 0.08
length_m = 0.6
shape = "bump"
"""


def test_course_file_is_read(tmp_path):
    path = tmp_path / "yard.toml"
    path.write_text(YARD, encoding="utf-8")
    course = load_course_file(path, 9.0, settle_s=1.0)
    assert course.name == "my yard at 9 km/h"
    np.testing.assert_allclose(
        course.profile.distance_m, [0, 0, 0.14, 0.14, 6, 6.3, 6.6], atol=1e-12
    )
    assert course.settle_s == 1.0


@pytest.mark.parametrize(
    ("text", "messages"),
    [
        (
            YARD.replace("height_m = 0.08", "height_m = -0.04"),
            [r"obstacles\[2\].height_m: -0.04 is not allowed; give a number in \(0, 0.5\] m"],
        ),
        (
            YARD.replace("height_m = 0.04", 'height_m = "4 cm"').replace(
                'shape = "bump"', 'shape = "kerb"\nwidth_m = 1.0'
            ),
            [
                r"obstacles\[1\].height_m: '4 cm' is not allowed",
                r"obstacles\[2\].width_m: unknown key; allowed: position_m, height_m, "
                "length_m, shape",
                r"obstacles\[2\].shape: 'kerb' is not allowed; give one of board, bump, pit",
            ],
        ),
        (
            YARD.replace("length_m = 0.14\n", ""),
            [r"obstacles\[1\].length_m: missing; give a number in \(0, 20\] m"],
        ),
        (
            YARD.replace("position_m = 6.0", "position_m = 0.1"),
            [r"obstacles\[2\].position_m: 0.1 is not allowed; obstacles\[1\] lies from 0 to"],
        ),
        ('name = "empty"\nspeed = 9\n', [r"speed: unknown key", r"obstacles: give 1 to 1000"]),
        ("[[obstacles]\n", [r"course file .*yard.toml: "]),
    ],
)
def test_course_file_errors_name_every_bad_entry(tmp_path, text, messages):
    path = tmp_path / "yard.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(CourseFileError) as error:
        load_course_file(path, 9.0)
    assert str(path) in str(error.value)
    assert "\n" not in str(error.value)
    for message in messages:
        assert re.search(message, str(error.value)), (message, str(error.value))


def test_missing_course_file_is_named(tmp_path):
    with pytest.raises(CourseFileError, match=r"no_such\.toml"):
        load_course_file(tmp_path / "no_such.toml", 9.0)


def test_guide_example_course_file_is_valid_and_shown_as_it_is():
    """docs/examples/my_yard.toml loads, and the guide's simulation page shows it unchanged."""
    root = Path(__file__).resolve().parents[2]
    example = root / "docs" / "examples" / "my_yard.toml"
    course = load_course_file(example, 9.0)
    assert course.name == "my yard at 9 km/h"
    assert course.profile.height_m.min() == -0.05 and course.profile.height_m.max() == 0.08
    page = (root / "docs" / "guide" / "simulation.md").read_text(encoding="utf-8")
    assert f"```toml\n{example.read_text(encoding='utf-8')}```" in page
