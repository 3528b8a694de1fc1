"""Road CSV files: round trip, units, and an error naming file, row, column and value."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.simulation import (
    RoadFileError,
    RoadProfile,
    iso8608_profile,
    read_road_csv,
    single_board,
    write_road_csv,
)


def test_round_trip_is_exact(tmp_path):
    profile = iso8608_profile("C", 20.0, seed=4)
    path = write_road_csv(profile, tmp_path / "road.csv")
    back = read_road_csv(path)
    np.testing.assert_array_equal(back.distance_m, profile.distance_m)
    np.testing.assert_array_equal(back.height_m, profile.height_m)
    assert back.name == "road.csv"


def test_units_comments_and_blank_lines(tmp_path):
    path = tmp_path / "ramp.csv"
    path.write_text("# measured ramp\n\ndistance [cm], height [mm]\n0, 0\n50,10\n\n100 ,20\n")
    profile = read_road_csv(path, name="ramp")
    np.testing.assert_allclose(profile.distance_m, [0.0, 0.5, 1.0], rtol=1e-15)
    np.testing.assert_allclose(profile.height_m, [0.0, 0.01, 0.02], rtol=1e-15)
    assert profile.name == "ramp"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "no header"),
        ("distance [m]\n0\n", r"row 1: header must have 2 columns"),
        (
            "distance [m],elevation [m]\n",
            r"row 1: header column 'height' expected; got 'elevation \[m\]'",
        ),
        ("distance,height [m]\n", r"row 1: header column 'distance' needs a unit in brackets"),
        (
            "distance [m],height [ft]\n",
            r"row 1: unit 'ft' of column 'height' must be one of \('m', 'cm', 'mm'\)",
        ),
        (
            "distance [m],height [m]\n0,0\n1,abc\n",
            r"row 3, column 'height \[m\]': 'abc' is not a number",
        ),
        (
            "distance [m],height [m]\n0,0\n1,nan\n",
            r"row 3, column 'height \[m\]': 'nan' is not finite",
        ),
        (
            "distance [m],height [m]\n0,0\ninf,0\n",
            r"row 3, column 'distance \[m\]': 'inf' is not finite",
        ),
        (
            "distance [m],height [m]\n0,0\n2,0\n2,1\n",
            r"row 4, column 'distance \[m\]': distance must increase; got '2' after 2",
        ),
        ("distance [m],height [m]\n0,0\n-1,0\n", r"row 3, .*got '-1' after 0"),
        (
            "distance [m],height [m]\n0,0,0\n",
            r"row 2: expected 2 values \(distance \[m\], height \[m\]\)",
        ),
        ("distance [m],height [m]\n0,0\n", r"at least 2 data rows needed; got 1"),
    ],
)
def test_bad_files_name_row_column_and_value(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(
        RoadFileError, match=r"bad\.csv.*" + message if "row" in message else message
    ):
        read_road_csv(path)


def test_missing_and_unreadable_files(tmp_path):
    with pytest.raises(RoadFileError, match=r"road file not found: .*nope\.csv"):
        read_road_csv(tmp_path / "nope.csv")
    (tmp_path / "binary.csv").write_bytes(b"\xff\xfe\x00\x81")
    with pytest.raises(RoadFileError, match="cannot read road file"):
        read_road_csv(tmp_path / "binary.csv")
    assert issubclass(RoadFileError, ValueError)


def test_writer_refuses_vertical_edges_and_missing_folder(tmp_path):
    with pytest.raises(ValueError, match="vertical edge"):
        write_road_csv(single_board(height_m=0.04, width_m=0.14), tmp_path / "board.csv")
    with pytest.raises(ValueError, match="road file folder does not exist"):
        write_road_csv(RoadProfile([0, 1], [0, 0]), tmp_path / "no" / "road.csv")
