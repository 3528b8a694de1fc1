"""Course files of the user's own as conditions of the design check's envelope."""

from __future__ import annotations

from pathlib import Path

import pytest

from loader_model.control.settings import default_settings
from loader_model.experiments.design_check import Design, Envelope, check_design, load_envelope
from loader_model.experiments.design_check.envelope import COURSE_PREFIX, DEFAULT_ENVELOPE
from loader_model.experiments.design_check.runs import condition_course

ONE_BOARD = "[[obstacles]]\nposition_m = 0.0\nheight_m = 0.04\nlength_m = 0.14\n"


def test_default_envelope_has_no_course_files():
    assert DEFAULT_ENVELOPE.courses == ()
    roads = [c.road for c in DEFAULT_ENVELOPE.conditions()]
    assert len(roads) == 2 * (4 + 3 * 3)
    assert set(roads) == {"boards", "B", "C", "D"}


def test_course_files_are_conditions_relative_to_the_envelope_file(tmp_path):
    (tmp_path / "courses").mkdir()
    (tmp_path / "courses" / "my_yard.toml").write_text(ONE_BOARD, encoding="utf-8")
    path = tmp_path / "envelope.toml"
    path.write_text(
        '[envelope]\nloads = ["full"]\nboard_speeds_kmh = [9.0]\nroad_classes = []\n'
        'courses = ["courses/my_yard.toml"]\ncourse_speeds_kmh = [6.0, 12.0]\n',
        encoding="utf-8",
    )
    envelope = load_envelope(path)
    conditions = envelope.conditions()
    assert [c.label for c in conditions] == [
        "full, boards 9 km/h",
        "full, my_yard 6 km/h",
        "full, my_yard 12 km/h",
    ]
    road = conditions[1].road
    assert road.startswith(COURSE_PREFIX)
    assert Path(road[len(COURSE_PREFIX) :]) == tmp_path / "courses" / "my_yard.toml"
    course = condition_course(conditions[2], envelope)
    assert course.name == "my_yard at 12 km/h"
    assert course.speed_m_s == pytest.approx(12.0 / 3.6, rel=1e-15)
    assert course.settle_s == envelope.settle_s


@pytest.mark.parametrize(
    ("entries", "message"),
    [
        ('courses = ["no_such.toml"]', r"courses = '.*no_such.toml'; allowed: a valid course"),
        ('courses = ["bad.toml"]', r"obstacles\[1\].height_m: -0.04 is not allowed"),
        ('courses = "bad.toml"', r"courses = 'bad.toml'; allowed: a list"),
        ('courses = ["yard.csv"]', r"allowed: a list of course files FILE.toml"),
        (
            'courses = ["good.toml"]\ncourse_speeds_kmh = []',
            r"course_speeds_kmh = \(\); allowed: at least one speed",
        ),
        ('courses = ["good.toml"]\ncourse_speeds_kmh = [90.0]', "speeds from 1 to 60 km/h"),
    ],
)
def test_bad_course_entries_are_named(tmp_path, entries, message):
    (tmp_path / "good.toml").write_text(ONE_BOARD, encoding="utf-8")
    (tmp_path / "bad.toml").write_text(ONE_BOARD.replace("0.04", "-0.04"), encoding="utf-8")
    path = tmp_path / "envelope.toml"
    path.write_text(f"[envelope]\n{entries}\n", encoding="utf-8")
    with pytest.raises(ValueError, match=message):
        load_envelope(path)


@pytest.mark.slow  # 26 s on a shared 2-core machine, most of it the compile and the margins
def test_a_course_file_is_checked_like_the_boards(tmp_path):
    """The shipped skyhook over one board of a course file: three runs judged (design, baseline,
    passive), the condition labelled by the file."""
    course = tmp_path / "one_board.toml"
    course.write_text(ONE_BOARD, encoding="utf-8")
    envelope = Envelope(
        loads=("empty",),
        board_speeds_kmh=(),
        road_classes=(),
        courses=(str(course),),
        course_speeds_kmh=(9.0,),
        sampled_plants=0,
    )
    check = check_design(Design(default_settings()), envelope, progress=False)
    (row,) = check.conditions
    assert row.condition.label == "empty, one_board 9 km/h"
    assert set(row.runs) == {"design", "baseline", "passive"}
    assert all(run.a_total > 0.0 for run in row.runs.values())
