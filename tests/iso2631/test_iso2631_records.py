"""Labelled multi-axis records, CSV input and the whole-record evaluation (paper Eq. 49, 50)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from loader_model.iso2631 import (
    COMFORT_K_FACTORS,
    DEFAULT_AXIS_WEIGHTINGS,
    VibrationRecord,
    evaluate_record,
    format_evaluation,
    health_assessment,
    read_vibration_csv,
    vibration_dose_value,
    weight_acceleration,
    weighted_rms,
)
from tests.iso2631.test_iso2631_annex_a import annex_a_response

RATE_HZ = 200.0
#: axis: (amplitude m/s² or rad/s², frequency Hz) of the synthetic seat record.
SINES = {"x": (0.4, 1.0), "y": (0.25, 2.0), "z": (0.9, 5.0), "pitch": (0.6, 2.5)}


def synthetic_record(duration_s: float = 60.0) -> VibrationRecord:
    time_s = np.arange(round(duration_s * RATE_HZ)) / RATE_HZ
    axes = {a: amp * np.sin(2 * np.pi * f * time_s) for a, (amp, f) in SINES.items()}
    axes["z"] = axes["z"] + 9.81  # gravity offset, removed by the band-limiting high-pass
    return VibrationRecord(time_s=time_s, axes=axes)


def write_csv(path: Path, header: str, rows: list[str]) -> Path:
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return path


def test_record_properties_and_read_only_storage() -> None:
    record = synthetic_record(10.0)
    assert record.sample_rate_hz == pytest.approx(RATE_HZ, rel=1e-12)
    assert record.duration_s == pytest.approx(10.0, rel=1e-12)
    assert record.axis_names == ("x", "y", "z", "pitch")
    with pytest.raises(ValueError, match="read-only"):
        record.axes["x"][0] = 1.0
    with pytest.raises(TypeError):
        record.axes["roll"] = np.zeros(3)  # type: ignore[index]


def test_csv_round_trip(tmp_path: Path) -> None:
    record = synthetic_record(5.0)
    table = np.column_stack([record.time_s, *record.axes.values()])
    path = tmp_path / "seat.csv"
    np.savetxt(path, table, delimiter=",", header="time,x,y,z,pitch", comments="", fmt="%.9g")
    loaded = VibrationRecord.from_csv(path)
    assert loaded.axis_names == record.axis_names
    for axis in record.axis_names:
        np.testing.assert_allclose(loaded.axes[axis], record.axes[axis], rtol=1e-8, atol=1e-9)
    assert loaded.sample_rate_hz == pytest.approx(RATE_HZ, rel=1e-8)


def test_evaluation_of_sines_matches_the_exact_weightings() -> None:
    """Per axis a_w = A |W(f)| / sqrt(2); a_v by Eq. 50 with k = 1, 1, 1, 0.4 (the paper).
    The start transient of the filters (< 3 s of 60 s) is allowed for by rtol = 1 %."""
    evaluation = evaluate_record(synthetic_record())
    by_axis = {item.axis: item for item in evaluation.axes}
    for axis, (amplitude, frequency_hz) in SINES.items():
        weighting = DEFAULT_AXIS_WEIGHTINGS[axis]
        assert by_axis[axis].weighting == weighting
        expected = amplitude * abs(annex_a_response(weighting, frequency_hz)) / math.sqrt(2)
        assert by_axis[axis].weighted_rms == pytest.approx(expected, rel=1e-2)
        assert by_axis[axis].crest_factor >= math.sqrt(2) * (1 - 1e-2)
        # MTVV >= a_w; it also sees the start transient, so no closed form here.
        assert by_axis[axis].mtvv >= by_axis[axis].weighted_rms
    assert by_axis["pitch"].unit == "rad/s²"
    assert by_axis["pitch"].k_factor == 0.4
    expected_total = math.sqrt(
        sum((COMFORT_K_FACTORS[a] * item.weighted_rms) ** 2 for a, item in by_axis.items())
    )
    assert evaluation.total_m_s2 == pytest.approx(expected_total, rel=1e-12)


def test_evaluation_uses_the_filters_and_metrics_consistently() -> None:
    record = synthetic_record(8.0)
    evaluation = evaluate_record(
        record, weightings={"x": "Wc"}, k_factors={"x": 0.8}, running_rms_method="exponential"
    )
    x = evaluation.axes[0]
    weighted = weight_acceleration(record.axes["x"], RATE_HZ, "Wc")
    assert (x.weighting, x.k_factor) == ("Wc", 0.8)
    assert x.weighted_rms == pytest.approx(weighted_rms(weighted), rel=1e-12)
    assert x.vdv == pytest.approx(vibration_dose_value(weighted, RATE_HZ), rel=1e-12)
    assert x.estimated_vdv == pytest.approx(1.4 * x.weighted_rms * 8.0**0.25, rel=1e-12)


def test_health_assessment_uses_the_worst_axis_with_health_k_factors() -> None:
    evaluation = evaluate_record(synthetic_record(20.0))
    by_axis = {item.axis: item for item in evaluation.axes}
    assessment = health_assessment(evaluation, 4 * 3600.0)
    assert assessment is not None
    expected_a8 = max(
        1.4 * by_axis["x"].weighted_rms, 1.4 * by_axis["y"].weighted_rms, by_axis["z"].weighted_rms
    ) * math.sqrt(0.5)
    assert assessment.a8_m_s2 == pytest.approx(expected_a8, rel=1e-12)
    expected_vdv = (
        max(1.4 * by_axis["x"].vdv, 1.4 * by_axis["y"].vdv, by_axis["z"].vdv)
        * (4 * 3600.0 / 20.0) ** 0.25
    )
    assert assessment.vdv_m_s175 == pytest.approx(expected_vdv, rel=1e-12)
    pitch = np.sin(2 * np.pi * 2.0 * np.arange(1000) / RATE_HZ)
    only_pitch = VibrationRecord(time_s=np.arange(1000) / RATE_HZ, axes={"pitch": pitch})
    assert health_assessment(evaluate_record(only_pitch)) is None


def test_table_lists_axes_total_and_directive_values() -> None:
    evaluation = evaluate_record(synthetic_record(10.0))
    text = format_evaluation(evaluation, health_assessment(evaluation), title="seat.csv:")
    lines = text.splitlines()
    assert lines[0] == "seat.csv:"
    assert [line.split()[0] for line in lines[3:7]] == ["x", "y", "z", "pitch"]
    assert f"a_total (paper Eq. 50) = {evaluation.total_m_s2:.4g} m/s²" in text
    assert "A(8) = " in text and "Directive 2002/44/EC" in text


def test_bad_records_are_refused() -> None:
    time_s = np.arange(10) / 100.0
    ones = np.ones(10)
    with pytest.raises(
        ValueError, match=r"time_s must be uniformly sampled \(intervals within 1% of"
    ):
        VibrationRecord(time_s=np.r_[time_s[:5], time_s[5:] + 0.003], axes={"z": ones})
    with pytest.raises(
        ValueError, match=r"time_s must be strictly increasing; got 0.03 then 0.03 at"
    ):
        VibrationRecord(time_s=np.r_[time_s[:4], time_s[3:9]], axes={"z": ones})
    with pytest.raises(ValueError, match=r"time_s must have at least 2 samples; got 1"):
        VibrationRecord(time_s=[0.0], axes={"z": [1.0]})
    with pytest.raises(ValueError, match=r"time_s must not be empty; got 0 samples"):
        VibrationRecord(time_s=[], axes={"z": []})
    with pytest.raises(ValueError, match=r"axis 'z' must be finite; got inf at index 2"):
        VibrationRecord(time_s=time_s, axes={"z": np.where(np.arange(10) == 2, np.inf, ones)})
    with pytest.raises(ValueError, match=r"axis name must be one of \('x', .*'yaw'\); got 'heave'"):
        VibrationRecord(time_s=time_s, axes={"heave": ones})
    with pytest.raises(
        ValueError, match=r"axis 'x' must have as many samples as time_s \(10\); got 9"
    ):
        VibrationRecord(time_s=time_s, axes={"x": ones[:9]})
    with pytest.raises(
        ValueError, match=r"axes must map at least one of \('x', .*\) to samples; got \{\}"
    ):
        VibrationRecord(time_s=time_s, axes={})


def test_bad_evaluation_options_are_refused() -> None:
    record = synthetic_record(5.0)
    with pytest.raises(ValueError, match=r"weighting must be one of \('Wk', .*\); got 'Wb'"):
        evaluate_record(record, weightings={"z": "Wb"})
    with pytest.raises(
        ValueError, match=r"weightings axis must be one of \('x', .*\); got 'heave'"
    ):
        evaluate_record(record, weightings={"heave": "Wk"})
    with pytest.raises(
        ValueError, match=r"k_factors\['pitch'\] must be a number in \[0, 2\] .*; got -0.4"
    ):
        evaluate_record(record, k_factors={"pitch": -0.4})
    with pytest.raises(
        ValueError,
        match=r"sample_rate_hz must be at least 200 Hz for weighting Wk .*; got 100.0 Hz",
    ):
        evaluate_record(VibrationRecord(time_s=np.arange(1000) / 100.0, axes={"z": np.zeros(1000)}))
    with pytest.raises(
        ValueError, match=r"exposure_duration_s must be a finite number > 0 s; got 0"
    ):
        health_assessment(evaluate_record(record), 0)


@pytest.mark.parametrize(
    ("header", "rows", "message"),
    [
        ("t,z", ["0,1", "0.01,1"], r"header must contain a 'time' column \(s\); got \['t', 'z'\]"),
        ("time,z,heave", ["0,1,1"], r"column name must be one of \('x', .*\); got 'heave'"),
        ("time,z,z", ["0,1,1"], r"duplicate column\(s\) \['z'\] in header"),
        (
            "time",
            ["0", "1"],
            r"header needs at least one axis column of \('x', .*\); got \['time'\]",
        ),
        ("time,z", [], r"no data rows below the header \['time', 'z'\]"),
        (
            "time,z",
            ["0,1", "0.01,nan", "0.02,1"],
            r"column 'z' must be finite; got nan on line 3",
        ),
        ("time,z", ["0,1", "0.01,abc"], r"line 3, column 'z': 'abc' is not a number"),
        ("time,x,z", ["0,1", "0.01,1"], r"line 2 has 2 values but the header has 3 columns"),
        ("time,z", ["0,1", "0.01,1", "0.05,1"], r"time_s must be uniformly sampled"),
    ],
)
def test_bad_csv_files_are_refused(
    tmp_path: Path, header: str, rows: list[str], message: str
) -> None:
    path = write_csv(tmp_path / "bad.csv", header, rows)
    with pytest.raises(ValueError, match=message):
        read_vibration_csv(path)


def test_csv_comments_and_blank_lines_are_skipped(tmp_path: Path) -> None:
    path = write_csv(tmp_path / "c.csv", "# seat, 2009\ntime, z ", ["", "0,1", "# note", "0.5,2"])
    record = read_vibration_csv(path)
    np.testing.assert_array_equal(record.axes["z"], [1.0, 2.0])
    assert record.sample_rate_hz == pytest.approx(2.0, rel=1e-12)
    with pytest.raises(ValueError, match=r"no header row; expected columns 'time' and some of"):
        read_vibration_csv(write_csv(tmp_path / "e.csv", "# only a comment", []))


@pytest.mark.parametrize(
    ("axes", "message"),
    [
        ({"z": ["1"] * 10}, r"axis 'z' must be a 1-D array of real numbers; got \['1', '1'"),
        ({"z": [True] * 10}, r"axis 'z' must be a 1-D array of real numbers, not booleans"),
        ({"z": np.ones(10) + 1j}, r"axis 'z' must be a 1-D array of real numbers; got complex"),
        ({"z": np.full(10, 1e200)}, r"axis 'z' = 1e\+200 m/s² at index 0 is implausible"),
    ],
)
def test_record_api_refuses_what_the_csv_reader_refuses(axes: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        VibrationRecord(time_s=np.arange(10) / 100.0, axes=axes)


@pytest.mark.parametrize("rate", [True, "200", 10**400])
def test_sample_rate_must_be_a_real_number(rate: object) -> None:
    from loader_model.iso2631 import weight_acceleration

    with pytest.raises(ValueError, match=r"sample_rate_hz must be a positive number in Hz"):
        weight_acceleration(np.zeros(4000), rate, "Wk")  # type: ignore[arg-type]
