"""``loader-model simulate`` outside the model's range of validity (issue 19, item 4).

The two runs of the issue: class H at 40 km/h (skyhook, full bucket, seed 3) rolled the machine
over (pitch 30.7 rad) and printed an ISO 2631 evaluation; class E at 40 km/h (baseline, full,
seed 1) exited with the ISO 2631 input check's "axis 'x' = -5876.6 m/s² ... is implausible" and
no time series. Now both stop where the model stops holding, name the time, the state and the
bound, print no evaluation, and write the time series up to the stop.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from loader_model.cli import main

STOPS = ("chassis pitch", "boom angle", "both tyres off the ground", "seat acceleration")


def _stop(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[float, str, str]:
    """Run ``argv``; assert the stop's guarantees; return (time, stderr, stdout)."""
    assert main(argv) == 3  # the exit code of a run stopped outside the validity
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err and "implausible" not in captured.err
    assert "ISO 2631-1:1997" not in captured.out and "vibration total value" not in captured.out
    found = re.search(r"range of validity at t = (\d+\.\d+) s: ", captured.err)
    assert found is not None, captured.err
    assert any(f" s: {stop}" in captured.err for stop in STOPS), captured.err
    assert "; state: x_H=" in captured.err and "no ISO 2631 evaluation" in captured.err
    return float(found.group(1)), captured.err, captured.out


@pytest.mark.parametrize("speed", ["40", "30"])
def test_a_machine_that_tips_over_stops_there_with_its_time_series(
    speed: str, tmp_path, capsys
) -> None:
    """Class H, skyhook, full bucket, 120 s asked: the run stops within 2.5 s (measured: 40 km/h
    at 1.649 s, the boom thrown 0.05 rad past its full stroke in the air; 30 km/h at 1.182 s,
    pitched back past the 39.1° static stability angle); CSV and figure up to the stop."""
    output = tmp_path / "h.csv"
    argv = ["simulate", "--speed", speed, "--course", "iso8608:H", "--load", "full",
            "--controller", "skyhook", "--duration", "120", "--seed", "3",
            "--output", str(output)]  # fmt: skip
    stop_s, error, out = _stop(argv, capsys)
    assert stop_s < 2.5
    assert f"wrote the run up to it: {output}, {tmp_path / 'h.png'}" in error
    assert f"wrote {output}" in out and "validity:" in out  # the events, with the stop
    time_s = np.loadtxt(output, delimiter=",", skiprows=1, usecols=0)
    assert abs(time_s[-1] - stop_s) <= 5e-4 and time_s.size == round(stop_s * 1000) + 1
    assert (tmp_path / "h.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_seat_acceleration_stop_is_named_not_the_iso_input_check(
    tmp_path, capsys, monkeypatch
) -> None:
    """The stop on the seat acceleration bound (the bound a failed fixed-step integration step
    crosses: class E at 40 km/h, full bucket, baseline, rigid discs, one ROS2 step per period
    once passed 50 g in one 1 ms period, at 13.287 s with seed 1 and at 1.306 s with seed 3)
    names the time, the state and the bound, prints no ISO 2631 evaluation and writes the run
    up to it. Which runs fail at one substep turns on the last digits of the plant's arithmetic:
    on an AMD EPYC without AVX-512 the seed-3 run passes (its seat peaks at 64 m/s²), so the
    test lowers the bound to 30 m/s² on that run. The seat then rises through it in 2 m/s² per
    millisecond at the first bump: the stop at 0.837 s (measured), 19 m/s² the largest value
    before 0.83 s and 35 m/s² the peak there."""
    from loader_model.simulation import simulator
    from loader_model.simulation.validity import resolve_bounds

    def lowered(validity, params, **machine_and_tyres):
        bounds = resolve_bounds(validity, params, **machine_and_tyres)
        return dataclasses.replace(bounds, seat_acceleration_m_s2=30.0)

    monkeypatch.setattr(simulator, "resolve_bounds", lowered)
    output = tmp_path / "x.npz"
    argv = ["simulate", "--speed", "40", "--course", "iso8608:E", "--load", "full",
            "--duration", "20", "--seed", "3", "--envelope", "rigid", "--substeps", "1",
            "--output", str(output)]  # fmt: skip
    stop_s, error, _ = _stop(argv, capsys)
    assert "seat acceleration f_S" in error and "beyond the bound 30 m/s²" in error
    assert 0.83 < stop_s < 0.85
    with np.load(output) as data:
        assert abs(data["time"][-1] - stop_s) <= 5e-4
        seat = np.maximum(
            np.abs(data["f_Sx"] - data["f_Sx"][0]), np.abs(data["f_Sy"] - data["f_Sy"][0])
        )
        assert seat[-1] > 30.0 > np.max(seat[:-1])


def test_without_output_the_error_says_no_series_was_written(capsys) -> None:
    argv = ["simulate", "--speed", "30", "--course", "iso8608:H", "--load", "full",
            "--controller", "skyhook", "--duration", "120", "--seed", "3"]  # fmt: skip
    _, error, _ = _stop(argv, capsys)
    assert "no time series written (give --output FILE.csv or FILE.npz to keep it)" in error
