"""The ride control off below a travel speed (the settings' ``ride_control_min_speed``).

References: below the speed the run is the baseline's, computed on its own path
(:func:`resolve_scenario` with ``controller="baseline"``); above it, the run of the same settings
without a speed; both equal to the last bit, since the same compiled period integrates the same
numbers.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from loader_model.control.settings import default_settings, load_settings, save_settings
from loader_model.experiments.design_check.report import check_text
from loader_model.simulation.courses import board_course_at
from loader_model.simulation.gain_sensitivity import gain_gradient
from loader_model.simulation.scenario import resolve_scenario
from loader_model.simulation.simulator import course_input, simulate

GATE_KMH = 9.5


def _gated(gate_kmh: float = GATE_KMH):
    return dataclasses.replace(default_settings(), ride_control_min_speed=gate_kmh / 3.6)


def _course(speed_kmh: float):
    return board_course_at(speed_kmh, count=1, settle_s=2.0)


def _a_total(scenario, course) -> tuple[float, dict]:
    result = simulate(course_input(course, scenario), scenario)
    return result.seat_evaluation().total_m_s2, dict(result.metadata)


def test_below_its_speed_the_machine_drives_as_the_baseline() -> None:
    course = _course(5.0)
    gated = resolve_scenario(None, "full", controller="skyhook", settings=_gated())
    baseline = resolve_scenario(None, "full", controller="baseline")
    got, metadata = _a_total(gated, course)
    expected, _ = _a_total(baseline, course)
    assert got == expected  # the same plant, controller and road: bit for bit
    assert metadata["controller"] == baseline.controller.name()
    assert "off: 5 km/h is below its ride_control_min_speed of 9.5 km/h" in metadata["ride_control"]
    ungated = resolve_scenario(None, "full", controller="skyhook")
    assert _a_total(ungated, course)[0] != pytest.approx(expected, rel=1e-3)  # the gate acted


def test_at_and_above_its_speed_the_ride_control_acts_unchanged() -> None:
    gated = resolve_scenario(None, "full", controller="skyhook", settings=_gated())
    ungated = resolve_scenario(None, "full", controller="skyhook")
    for speed_kmh in (GATE_KMH, 18.0):
        course = _course(speed_kmh)
        got, metadata = _a_total(gated, course)
        assert got == _a_total(ungated, course)[0]
        assert "ride_control" not in metadata


def test_the_gain_gradient_below_the_speed_is_zero_at_the_baselines_a_total() -> None:
    course = _course(5.0)
    gated = resolve_scenario(None, "empty", controller="skyhook", settings=_gated())
    baseline = resolve_scenario(None, "empty", controller="baseline")
    run = gain_gradient(gated, course_input(course, gated))
    assert run.a_total == _a_total(baseline, course)[0]
    np.testing.assert_array_equal(run.gradient, np.zeros(4))
    assert {"V_p_ref", "Vd_p", "p_A"} <= set(run.columns)


def test_a_settings_file_without_the_speed_loads_with_the_ride_control_always_on(
    tmp_path,
) -> None:
    path = tmp_path / "gains.toml"
    save_settings(default_settings(), path)
    text = path.read_text(encoding="utf-8")
    older = "\n".join(
        line for line in text.splitlines() if not line.startswith("ride_control_min_speed")
    )
    assert older != text
    path.write_text(older + "\n", encoding="utf-8")
    assert load_settings(path).ride_control_min_speed == 0.0
    assert load_settings(path) == dataclasses.replace(
        default_settings(), sources=load_settings(path).sources
    )


@pytest.mark.parametrize(
    ("value", "unit", "message"),
    [
        ("-1.0", "m/s", "ride_control_min_speed"),
        ("20.0", "m/s", "15"),
        ("2.0", "km/h", "unit 'km/h' is not allowed"),
    ],
)
def test_a_bad_speed_is_refused_naming_it(tmp_path, value, unit, message) -> None:
    path = tmp_path / "gains.toml"
    save_settings(_gated(), path)
    text = path.read_text(encoding="utf-8").splitlines()
    text = [
        f'ride_control_min_speed = {{ value = {value}, unit = "{unit}", source = "test" }}'
        if line.startswith("ride_control_min_speed")
        else line
        for line in text
    ]
    path.write_text("\n".join(text) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match="ride_control_min_speed") as error:
        load_settings(path)
    assert message in str(error.value)


def test_the_design_checks_text_says_which_conditions_drive_without_ride_control() -> None:
    from loader_model.experiments.design_check import Design, Envelope, check_design

    envelope = Envelope(
        loads=("empty",),
        board_speeds_kmh=(5.0, 18.0),
        road_classes=(),
        road_speeds_kmh=(),
        settle_s=2.0,
    )
    check = check_design(Design(_gated()), envelope, progress=False, sampled_plants=0)
    text = check_text(check)
    assert "The ride control is off below 9.5 km/h" in text
    assert "1 of 2 conditions drive as the baseline" in text
    slow = next(c for c in check.conditions if c.condition.speed_kmh == 5.0)
    assert slow.runs["design"].a_total == slow.runs["baseline"].a_total


def test_the_rest_level_is_the_ride_controls_own_above_its_speed() -> None:
    from loader_model.experiments.design_check import Design, Envelope
    from loader_model.experiments.design_check.runs import rest_run

    envelope = Envelope(loads=("empty",), board_speeds_kmh=(18.0,), road_classes=())
    gated = rest_run(Design(_gated()), envelope, "empty")
    ungated = rest_run(Design(default_settings()), envelope, "empty")
    assert gated.tail_rms > 0.0  # the controller answers the sensors' noise, as without a gate
    # the same noise over a lead-in of another length: the last second's r.m.s. of a stationary
    # response differs by its sampling scatter (0.0182 against 0.0132 rad/s², measured)
    assert gated.tail_rms == pytest.approx(ungated.tail_rms, rel=0.5)


def test_a_design_keeps_the_starts_settings_but_its_gains(tmp_path) -> None:
    import argparse

    from loader_model.commands.design_steps import designed_settings, start_base
    from loader_model.control.settings import with_scaled_gains

    start = dataclasses.replace(
        with_scaled_gains(_gated(), [220.0, 5.1, -4.0, 0.22], "start"), k_p=0.8
    )
    path = tmp_path / "start.toml"
    save_settings(start, path)
    base = start_base(argparse.Namespace(start=str(path)))
    assert base is not None and start_base(argparse.Namespace(start=None)) is None
    written = designed_settings([1.0, 2.0, -3.0, 0.5], "compact_wheel_loader", "test", base=base)
    assert written.k_fb == (1.0, 2.0, -3.0, 0.5)
    assert (written.k_p, written.ride_control_min_speed) == (0.8, GATE_KMH / 3.6)
    shipped = default_settings()
    assert written.linear_acceleration_norm == shipped.linear_acceleration_norm  # not the start's
    assert start.linear_acceleration_norm < shipped.linear_acceleration_norm


def test_simulate_says_when_the_ride_control_is_off(tmp_path, capsys) -> None:
    from loader_model.cli import main

    path = tmp_path / "gated.toml"
    save_settings(_gated(), path)
    argv = ["simulate", "--controller", str(path), "--course", "single", "--duration", "3"]
    assert main([*argv, "--speed", "5"]) == 0
    assert (
        "ride control: skyhook off: 5 km/h is below its ride_control_min_speed of 9.5 km/h; "
        "the run is the baseline's" in capsys.readouterr().out
    )
    assert main([*argv, "--speed", "12"]) == 0
    assert "ride control:" not in capsys.readouterr().out
