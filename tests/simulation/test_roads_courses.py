"""The paper's course (section 5.3), the Fig. 10 single obstacle, and the course plot."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from loader_model.simulation import (
    BOARD_WIDTH_M,
    Course,
    TandemCam,
    iso8608_course,
    paper_course,
    plot_course,
    single_obstacle_course,
)


@pytest.mark.parametrize(("speed_kmh", "spacing_m"), [(9, 6.0), (18, 9.0)])
def test_paper_course_is_five_40_mm_boards(speed_kmh, spacing_m):
    course = paper_course(speed_kmh)
    assert course.speed_m_s == pytest.approx(speed_kmh / 3.6, rel=1e-15)
    leading_m = course.profile.distance_m[::4]
    np.testing.assert_allclose(leading_m, spacing_m * np.arange(5), rtol=0, atol=1e-12)
    assert set(course.profile.height_m.tolist()) == {0.0, 0.04}
    widths_m = course.profile.distance_m[2::4] - leading_m
    np.testing.assert_allclose(widths_m, BOARD_WIDTH_M, rtol=0, atol=1e-12)
    assert BOARD_WIDTH_M == 0.14  # a 2x6 plank laid flat (courses module notes)
    drive = course.road_input(1.2)
    # Each axle climbs five boards: count the rising edges of w_Ay and w_By.
    for column in (1, 3):
        on_board = drive.road_m[:, column] > 0.02
        assert np.count_nonzero(np.diff(on_board.astype(int)) == 1) == 5
    # The drive ends settle_s after the rear axle leaves the last board's envelope.
    rear_end_m = drive.axle_distance(drive.duration_s)[1]
    assert rear_end_m == pytest.approx(
        4 * spacing_m + 0.14 + 0.42 + 3.0 * course.speed_m_s, abs=1e-3
    )


def test_paper_course_jitter_is_seeded():
    one = paper_course(18, position_jitter_m=0.05, seed=2)
    assert np.array_equal(
        one.profile.distance_m, paper_course(18, position_jitter_m=0.05, seed=2).profile.distance_m
    )
    assert not np.array_equal(one.profile.distance_m, paper_course(18).profile.distance_m)


def test_single_obstacle_is_fig10_drive():
    course = single_obstacle_course()
    assert course.speed_m_s == pytest.approx(17 / 3.6, rel=1e-15)
    assert course.profile.height_m.max() == 0.04
    assert course.settle_s >= 5.0  # a free response long enough for the Fig. 10 spectra
    faster = dataclasses.replace(course, speed_m_s=5.0)
    assert isinstance(faster, Course) and faster.road_input(1.2).speed_m_s == 5.0


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: paper_course(10),
            r"speed_kmh must be one of the paper's speeds \(9.0, 18.0\) km/h; got 10",
        ),
        (lambda: paper_course(True), "speed_kmh must be one of the paper's speeds"),
        (lambda: paper_course(9, settle_s=-1), r"settle_s must be a finite number in \[0, 60\] s"),
        (
            lambda: single_obstacle_course(0.0),
            r"speed_kmh must be a finite number in \(0, 100\] km/h",
        ),
        (lambda: iso8608_course("C", 10, length_m=0.0), r"length_m must be a finite number"),
        (
            lambda: paper_course(9).road_input(-1.0),
            r"wheelbase_m must be a finite number in \[0, 10\] m",
        ),
    ],
)
def test_course_errors_name_argument(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_plot_course_writes_png(tmp_path):
    path = plot_course(tmp_path / "course.png", paper_course(9), wheelbase_m=1.2)
    cams = (TandemCam.from_deflection(0.42, 0.0073), TandemCam.from_deflection(0.42, 0.0099))
    cam_path = plot_course(
        tmp_path / "cams.png", paper_course(9), wheelbase_m=1.2, cams=cams, distance_range_m=(-1, 1)
    )
    assert cam_path.stat().st_size > 10_000
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match=r"must end in \.png, \.pdf or \.svg"):
        plot_course(tmp_path / "course.jpg", paper_course(9), wheelbase_m=1.2)
    with pytest.raises(ValueError, match="distance_range_m must be"):
        plot_course(tmp_path / "c.png", paper_course(9), wheelbase_m=1.2, distance_range_m=(2, 1))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cams.png", "course.png"]
