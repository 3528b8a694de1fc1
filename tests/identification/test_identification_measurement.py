"""The identification CSV format: round trip, unit conversion, and errors that name the cell."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loader_model.identification.measurement import (
    MIN_ROWS,
    MeasurementRecord,
    read_measurement_csv,
    write_measurement_csv,
)

HEADER = "time [s],x_cyl [m],p_A [Pa],p_B [Pa],Q_A [m^3/s],m_load [kg]"


def _rows(n: int = 60) -> list[list[str]]:
    return [
        [f"{i * 0.002:.3f}", f"{0.1 + 1e-4 * i:.6g}", "8.0e6", "2.0e6", "1.0e-4", "340"]
        for i in range(n)
    ]


def _write(tmp_path: Path, header: str, rows: list[list[str]]) -> Path:
    path = tmp_path / "data.csv"
    path.write_text("# a comment\n" + header + "\n" + "\n".join(",".join(r) for r in rows) + "\n")
    return path


def test_round_trip_is_exact(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    t = np.arange(100) / 500.0
    record = MeasurementRecord(
        time_s=t,
        position_m=rng.uniform(0, 0.4, 100),
        p_a_pa=rng.uniform(1e6, 2e7, 100),
        p_b_pa=rng.uniform(1e6, 3e6, 100),
        load_mass_kg=np.full(100, 340.0),
        flow_m3_s=rng.normal(0, 1e-3, 100),
    )
    path = write_measurement_csv(tmp_path / "r.csv", record.columns(), ("comment",))
    back = read_measurement_csv(path)
    for name in ("time_s", "position_m", "p_a_pa", "p_b_pa", "load_mass_kg", "flow_m3_s"):
        np.testing.assert_array_equal(getattr(back, name), getattr(record, name))
    assert back.sample_rate_hz == pytest.approx(500.0, rel=1e-12)


def test_bar_litre_and_displacement_columns_are_converted(tmp_path: Path) -> None:
    header = "time [s],x_cyl [m],p_A [bar],p_B [bar],V_p [cm^3/rev],m_load [kg],other [V]"
    rows = [[f"{i * 0.01:.2f}", "0.1", "80", "20", "23", "0", "abc"] for i in range(60)]
    record = read_measurement_csv(_write(tmp_path, header, rows))
    assert record.p_a_pa[0] == pytest.approx(8.0e6, rel=1e-15)
    assert record.p_b_pa[0] == pytest.approx(2.0e6, rel=1e-15)
    assert record.flow(40.0)[0] == pytest.approx(23e-6 * 40.0, rel=1e-15)
    header = HEADER.replace("Q_A [m^3/s]", "Q_A [L/min]")
    rows = _rows()
    rows[0][4] = "60"
    record = read_measurement_csv(_write(tmp_path, header, rows))
    assert record.flow(40.0)[0] == pytest.approx(1e-3, rel=1e-15)


@pytest.mark.parametrize(
    ("header", "edit", "pattern"),
    [
        (HEADER.replace(",p_B [Pa]", ""), None, r"missing column\(s\) \['p_B'\]"),
        (HEADER.replace(",m_load [kg]", ""), None, r"missing column\(s\) \['m_load'\]"),
        (HEADER.replace("Q_A [m^3/s]", "flow [m^3/s]"), None, r"missing.*Q_A \(or V_p\)"),
        (HEADER.replace("x_cyl [m]", "angle [rad]"), None, r"\['x_cyl \(or phi\)'\]"),
        (HEADER + ",phi [deg]", None, r"either column 'x_cyl' or 'phi'"),
        (HEADER.replace("p_A [Pa]", "p_A"), None, r"column 'p_A' has no unit"),
        (HEADER.replace("p_A [Pa]", "p_A [psi]"), None, r"'p_A' has unit 'psi'; allowed"),
        (HEADER.replace("x_cyl [m]", "x_cyl [mm]"), None, r"'x_cyl' has unit 'mm'"),
        (HEADER + ",V_p [m^3/rev]", None, r"either column 'Q_A' or 'V_p'"),
        (HEADER, (10, 2, "abc"), r"column 'p_A', line 13: 'abc' is not a number"),
        (HEADER, (20, 4, ""), r"column 'Q_A', line 23: '' is not a number"),
        (HEADER, (5, 1, "nan"), r"column 'x_cyl', line 8: 'nan' is not finite"),
        (HEADER, (7, 3, "inf"), r"column 'p_B', line 10: 'inf' is not finite"),
        (HEADER, (30, 0, "0.058"), r"column 'time', line 33: 0.058 s is not after 0.058 s"),
        (
            HEADER,
            (30, 0, "0.0605"),
            r"column 'time', line 33: 0.0605 s is 0.0025 s after 0.058 s.*non-uniform",
        ),
    ],
)
def test_bad_input_names_column_line_and_value(
    tmp_path: Path, header: str, edit: tuple[int, int, str] | None, pattern: str
) -> None:
    rows = _rows()
    if edit is not None:
        row, column, value = edit
        rows[row][column] = value
    path = _write(tmp_path, header, rows)
    with pytest.raises(ValueError, match=pattern):
        read_measurement_csv(path)


def test_too_few_rows_and_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=f"{MIN_ROWS - 1} data rows; at least {MIN_ROWS}"):
        read_measurement_csv(_write(tmp_path, HEADER, _rows(MIN_ROWS - 1)))
    with pytest.raises(ValueError, match="does not exist"):
        read_measurement_csv(tmp_path / "nothing.csv")
    empty = tmp_path / "empty.csv"
    empty.write_text("# only a comment\n")
    with pytest.raises(ValueError, match="no header row"):
        read_measurement_csv(empty)


def test_failed_write_leaves_no_file(tmp_path: Path) -> None:
    columns = {"time [s]": np.arange(3.0), "x_cyl [m]": np.zeros(2)}  # unequal lengths
    with pytest.raises(ValueError):
        write_measurement_csv(tmp_path / "out.csv", columns)
    assert list(tmp_path.iterdir()) == []


def test_chassis_columns_round_trip_and_convert(tmp_path: Path) -> None:
    rng = np.random.default_rng(1)
    t = np.arange(80) / 500.0
    record = MeasurementRecord(
        time_s=t,
        position_m=rng.uniform(0, 0.4, 80),
        p_a_pa=rng.uniform(1e6, 2e7, 80),
        p_b_pa=rng.uniform(1e6, 3e6, 80),
        load_mass_kg=np.full(80, 340.0),
        flow_m3_s=rng.normal(0, 1e-3, 80),
        pitch_rad=rng.normal(0, 0.01, 80),
        specific_force_m_s2=rng.normal([0, 9.8, 9.8], 0.1, (80, 3)),
    )
    back = read_measurement_csv(write_measurement_csv(tmp_path / "r.csv", record.columns()))
    assert back.has_chassis
    np.testing.assert_array_equal(back.pitch_rad, record.pitch_rad)
    np.testing.assert_array_equal(back.specific_force_m_s2, record.specific_force_m_s2)
    header = HEADER + ",theta_1 [deg],f_Hx [g],f_Hy [g],f_Ny [m/s^2]"
    rows = [[*row, "1.0", "0.5", "1.0", "9.0"] for row in _rows()]
    converted = read_measurement_csv(_write(tmp_path, header, rows))
    assert converted.pitch_rad[0] == pytest.approx(np.pi / 180.0, rel=1e-15)
    assert converted.specific_force_m_s2[0] == pytest.approx([4.903325, 9.80665, 9.0], rel=1e-15)


def test_chassis_columns_come_all_or_none(tmp_path: Path) -> None:
    header = HEADER + ",theta_1 [rad],f_Hx [m/s^2]"
    rows = [[*row, "0.0", "0.0"] for row in _rows()]
    with pytest.raises(ValueError, match=r"chassis columns \['theta_1', 'f_Hx'\] given without"):
        read_measurement_csv(_write(tmp_path, header, rows))
    header = HEADER + ",theta_1 [rad],f_Hx [m/s2],f_Hy [m/s^2],f_Ny [m/s^2]"
    rows = [[*row, "0", "0", "9.8", "9.8"] for row in _rows()]
    with pytest.raises(
        ValueError, match=r"column 'f_Hx' has unit 'm/s2'; allowed: \['m/s\^2', 'g'\]"
    ):
        read_measurement_csv(_write(tmp_path, header, rows))
    assert not read_measurement_csv(_write(tmp_path, HEADER, _rows())).has_chassis
