"""Ordinary measurement files the ISO 2631-1 evaluation accepts (issue 19, item 5).

A time column of Unix time stamps (only the spacing matters) and an axis that recorded no
vibration (a_w = 0, crest factor undefined), through the API and the ``iso2631`` command; bad
time columns are still refused with clear messages.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from loader_model import cli
from loader_model.iso2631 import (
    VibrationRecord,
    evaluate_record,
    format_evaluation,
    read_vibration_csv,
)

RATE_HZ = 1000.0
SAMPLES = 8000
#: A Unix time in s (2023-11-14 22:13:20 UTC): float64 resolves it to 2.4e-7 s.
UNIX_START_S = 1_700_000_000
METRICS = ("weighted_rms", "crest_factor", "mtvv", "vdv", "estimated_vdv")


def _axes() -> dict[str, np.ndarray]:
    k = np.arange(SAMPLES)
    rng = np.random.default_rng(19)
    return {
        "x": 0.3 * np.sin(2 * np.pi * 1.5 * k / RATE_HZ) + 0.05 * rng.standard_normal(SAMPLES),
        "z": 9.81 + 0.8 * np.sin(2 * np.pi * 4.0 * k / RATE_HZ),
        "pitch": 0.4 * np.sin(2 * np.pi * 2.5 * k / RATE_HZ),
    }


def _write(path: Path, start_s: int, axes: dict[str, np.ndarray]) -> Path:
    """CSV with times ``start_s + k / 1 kHz`` written exactly in decimal (ms resolution)."""
    lines = ["time," + ",".join(axes)]
    columns = [np.asarray(values) for values in axes.values()]
    for k in range(SAMPLES):
        stamp = f"{start_s + k // 1000}.{k % 1000:03d}"
        lines.append(stamp + "," + ",".join(repr(float(c[k])) for c in columns))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _relative_tolerance(record: VibrationRecord) -> float:
    """Bound of the difference a record with time stamps t makes against exact times.

    Each stamp is the float64 nearest its decimal text, within half the float spacing at |t|, so
    the span t_last - t_first, and with it the sample rate, is off by at most one spacing over the
    span (3e-8 here). The values move by at most 1.3 x a relative change of the sample rate
    (measured for Wd, Wk, We on these signals by perturbing it by 1e-8 to 1e-6): 4 x covers it.
    """
    spacing_s = float(np.spacing(np.max(np.abs(record.time_s))))
    return 4.0 * spacing_s / (record.time_s[-1] - record.time_s[0])


def test_unix_time_stamps_evaluate_as_times_from_the_start(tmp_path: Path) -> None:
    unix = read_vibration_csv(_write(tmp_path / "unix.csv", UNIX_START_S, _axes()))
    relative = read_vibration_csv(_write(tmp_path / "relative.csv", 0, _axes()))
    rtol = _relative_tolerance(unix)
    assert rtol < 2e-7
    assert unix.sample_rate_hz == pytest.approx(RATE_HZ, rel=rtol)
    got, want = evaluate_record(unix), evaluate_record(relative)
    for item, expected in zip(got.axes, want.axes, strict=True):
        for name in METRICS:
            assert getattr(item, name) == pytest.approx(getattr(expected, name), rel=rtol), name
    assert got.total_m_s2 == pytest.approx(want.total_m_s2, rel=rtol)
    # only the spacing is used: the same stamps less the first give identical values
    shifted = VibrationRecord(time_s=unix.time_s - unix.time_s[0], axes=unix.axes)
    assert evaluate_record(shifted) == got


def test_spacing_check_allows_for_the_resolution_of_large_times() -> None:
    k = np.arange(40_000)
    axes = {"z": np.ones(k.size)}
    # 10 kHz stamps at 1.7e9 s are rounded by up to 2.4e-7 s, 0.24 % of the interval: accepted
    fast = VibrationRecord(time_s=UNIX_START_S + k / 10_000.0, axes=axes)
    assert fast.sample_rate_hz == pytest.approx(10_000.0, rel=1e-6)
    # a genuine 2 % step in the interval is still refused at that magnitude
    jittered = UNIX_START_S + k / 1000.0
    jittered[20_000:] += 2e-5
    with pytest.raises(
        ValueError,
        match=r"time_s must be uniformly sampled \(intervals within 1% of the mean 0.001 s\); "
        r"got an interval of 0.001019\d* s at index 20000",
    ):
        VibrationRecord(time_s=jittered, axes=axes)
    # 100 kHz at 1.7e9 s: the float64 resolution is 2.4 % of the interval, nothing to check
    with pytest.raises(
        ValueError,
        match=r"time_s cannot resolve its sampling interval: times of 1.7\d*e\+09 s are stored "
        r"to 2.38e-07 s \(float64\), more than 1% of the mean interval 1e-05 s; .*relative to "
        r"the start",
    ):
        VibrationRecord(time_s=UNIX_START_S + k / 100_000.0, axes=axes)


@pytest.mark.parametrize(
    ("stamps", "message"),
    [
        (
            ["1700000000.000", "1700000000.001", "1700000000.001", "1700000000.002"],
            r"time_s must be strictly increasing; got 1700000000.001 then 1700000000.001 at "
            r"index 2",
        ),
        (
            ["1700000000.002", "1700000000.001", "1700000000.000", "1699999999.999"],
            r"time_s must be strictly increasing; got 1700000000.002 then 1700000000.001 at "
            r"index 1",
        ),
        (
            ["1700000000.000", "nan", "1700000000.002", "1700000000.003"],
            r"column 'time' must be finite; got nan on line 3",
        ),
        (
            ["1700000000.000", "inf", "1700000000.002", "1700000000.003"],
            r"column 'time' must be finite; got inf on line 3",
        ),
        (
            ["-1.7e308", "-1e308", "1.7e308", "1.79e308"],
            r"time_s must span a finite time; got -1.7e\+308 s to 1.79e\+308 s",
        ),
    ],
)
def test_bad_time_columns_are_still_refused(
    tmp_path: Path, stamps: list[str], message: str
) -> None:
    path = tmp_path / "bad.csv"
    path.write_text("time,z\n" + "".join(f"{t},1\n" for t in stamps), encoding="utf-8")
    with pytest.raises(ValueError, match=message):
        read_vibration_csv(path)


def test_nan_values_are_still_refused(tmp_path: Path) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(
        "time,z\n1700000000.000,0\n1700000000.001,nan\n1700000000.002,0\n", encoding="utf-8"
    )
    with pytest.raises(ValueError, match=r"bad.csv: column 'z' must be finite; got nan on line 3"):
        read_vibration_csv(path)


@pytest.mark.parametrize("level", [0.0, 9.81])
def test_axis_without_vibration_is_evaluated_as_zero(level: float) -> None:
    """An all-zero (dead sensor) or constant (gravity only) channel: a_w, MTVV, VDV, eVDV 0 and
    the crest factor undefined; the other axes and the total are as without it."""
    axes = _axes()
    time_s = np.arange(SAMPLES) / RATE_HZ
    with_dead = evaluate_record(
        VibrationRecord(time_s=time_s, axes={**axes, "y": np.full(SAMPLES, level)})
    )
    without = evaluate_record(VibrationRecord(time_s=time_s, axes=axes))
    dead = with_dead.axes[-1]
    assert dead.axis == "y" and not dead.has_vibration
    assert (dead.weighted_rms, dead.mtvv, dead.vdv, dead.estimated_vdv) == (0.0, 0.0, 0.0, 0.0)
    assert math.isnan(dead.crest_factor)
    assert with_dead.axes[:-1] == without.axes
    assert all(item.has_vibration for item in without.axes)
    assert with_dead.total_m_s2 == without.total_m_s2
    text = format_evaluation(with_dead)
    row = next(line for line in text.splitlines() if line.startswith("y "))
    assert row.split()[:7] == ["y", "Wd", "1.00", "0", "—", "0", "0"]
    assert (
        "y: no vibration (an all-zero or constant channel: a_w = 0); crest factor undefined" in text
    )
    assert "nan" not in text


def test_command_round_trip_with_unix_times_and_a_dead_axis(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(cli, "COMMANDS", {"iso2631": "loader_model.commands.iso2631_command"})
    axes = {**_axes(), "y": np.zeros(SAMPLES)}
    unix = _write(tmp_path / "unix.csv", UNIX_START_S, axes)
    relative = _write(tmp_path / "relative.csv", 0, axes)
    assert cli.main(["iso2631", str(unix)]) == 0
    unix_out, unix_err = capsys.readouterr()
    assert cli.main(["iso2631", str(relative)]) == 0
    relative_out, _ = capsys.readouterr()
    assert unix_err == ""
    # the printed values (4 significant digits) agree; only the title (file name) differs
    assert unix_out.splitlines()[1:] == relative_out.splitlines()[1:]
    lines = unix_out.splitlines()
    assert lines[0] == f"{unix}:"
    assert "ISO 2631-1:1997 evaluation: T = 8 s at 1000 Hz" in lines[1]
    y_row = next(line for line in lines if line.startswith("y "))
    assert y_row.split()[3:5] == ["0", "—"]
    assert "y: no vibration" in unix_out and "nan" not in unix_out
    assert "daily exposure A(8)" in unix_out
