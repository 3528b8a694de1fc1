"""The design check on the nonlinear skid-steer: a limit cycle at the pump's limit is flagged, a
decaying design passes, a condition made worse than the baseline is named."""

from __future__ import annotations

import math

import pytest

from loader_model.control.settings import default_settings, with_gains
from loader_model.experiments.design_check import (
    Design,
    Envelope,
    check_design,
    load_envelope,
)
from loader_model.experiments.design_check.report import check_csv, check_markdown, check_text

#: The skyhook with the pitch gain's sign reversed (k_θ = +80): it drives the pump to V_p,max and
#: keeps the chassis pitching at about 3 rad/s² after the course (measured, empty bucket).
LIMIT_CYCLE_GAIN = (2.75, 5.10, 80.0, 0.22)
#: The shipped course-refined gains (data/controller_refined.toml), which decay after the road.
REFINED_GAIN = (37.99273472, -99.69001078, -18.53139729, 0.68306622)

BOARDS_9_KMH = Envelope(loads=("empty",), board_speeds_kmh=(9.0,), road_classes=())


@pytest.fixture(scope="module")
def limit_cycle():
    design = Design(with_gains(default_settings(), LIMIT_CYCLE_GAIN, "test"))
    return check_design(design, BOARDS_9_KMH, progress=False, sampled_plants=0)


@pytest.fixture(scope="module")
def decaying():
    design = Design(with_gains(default_settings(), REFINED_GAIN, "test"))
    return check_design(design, BOARDS_9_KMH, progress=False, sampled_plants=0)


def test_a_limit_cycle_at_the_pumps_limit_is_flagged(limit_cycle) -> None:
    (condition,) = limit_cycle.conditions
    run = condition.runs["design"]
    assert run.persistent
    assert run.command_duty > 0.0  # the command reached V_p,max (≥, not >)
    assert run.decay_ratio > 0.8 and run.tail_rms > 1.0
    assert not limit_cycle.passed
    assert any("persistent oscillation after the road" in f for f in limit_cycle.failures)
    assert all(f.startswith("empty") for f in limit_cycle.failures)
    # the linearised loop says so too: k_θ > 0 is positive pitch-rate feedback
    assert limit_cycle.margins["empty"].margin_rad_s < 0.0


def test_a_decaying_design_passes(decaying) -> None:
    (condition,) = decaying.conditions
    run, baseline = condition.runs["design"], condition.runs["baseline"]
    assert not run.persistent and run.decay_ratio < 0.8
    assert run.tail_rms < baseline.tail_rms
    assert run.a_total < baseline.a_total
    assert decaying.passed, decaying.failures
    assert "PASSED" in check_text(decaying)


def test_a_condition_worse_than_baseline_is_named(decaying) -> None:
    """The same runs judged with a criterion the design misses: the condition is named."""
    from loader_model.experiments.design_check import judge_condition

    (condition,) = decaying.conditions
    strict = Envelope(loads=("empty",), board_speeds_kmh=(9.0,), road_classes=(), tail_factor=1.0)
    baseline = condition.runs["baseline"]
    worse = dict(condition.runs)
    worse["design"] = type(baseline)(**{**baseline.__dict__, "a_total": baseline.a_total * 1.1})
    judged = judge_condition(condition.condition, worse, strict)
    assert judged.failures == (
        f"a_total {1.1 * baseline.a_total:.3f} m/s² is +10.0% against the baseline's "
        f"{baseline.a_total:.3f} (allowed +2%)",
    )
    assert judged.change == pytest.approx(0.1, rel=1e-12)


@pytest.mark.parametrize(
    ("circuit", "command", "rate"),
    [
        (
            "pump",
            "pump command at V_p,max for 6.0%",
            "pump displacement rate at its limit for 20.0%",
        ),
        (
            "valve",
            "spool command at its stroke x_s,max for 6.0%",
            "spool velocity at its limit for 20.0%",
        ),
    ],
)
def test_the_actuators_limits_are_named_for_the_machines_circuit(
    decaying, circuit, command, rate
) -> None:
    from loader_model.experiments.design_check import judge_condition

    (condition,) = decaying.conditions
    runs = dict(condition.runs)
    baseline = runs["baseline"]
    runs["design"] = type(baseline)(**{**baseline.__dict__, "command_duty": 0.06, "rate_duty": 0.2})
    envelope = Envelope(loads=("empty",), board_speeds_kmh=(9.0,), road_classes=())
    failures = judge_condition(condition.condition, runs, envelope, circuit=circuit).failures
    assert failures == (f"{command} of the run (allowed 5%)", f"{rate} of the run (allowed 10%)")


def test_motion_at_the_level_of_the_sensors_noise_is_not_an_oscillation(limit_cycle) -> None:
    """A run that keeps its level after the road counts as persistent only above twice what
    the design keeps at rest with its sensors' noise alone (rest_level, measured per load)."""
    from loader_model.experiments.design_check import judge_condition
    from loader_model.simulation.settling import REST_FLOOR_RAD_S2

    (condition,) = limit_cycle.conditions
    cycling = condition.runs["design"]
    assert set(limit_cycle.rest_rms) == {"empty"} and limit_cycle.rest_rms["empty"] > 0.0
    runs = dict(condition.runs)
    # the same run at 1.5 times a rest level of 0.06 rad/s²: the noise's, not the road's
    noisy = {"tail_rms": 0.09, "command_duty": 0.0, "a_total": condition.runs["baseline"].a_total}
    runs["design"] = type(cycling)(**{**cycling.__dict__, **noisy})
    assert runs["design"].persistent and 0.09 > REST_FLOOR_RAD_S2
    assert judge_condition(condition.condition, runs, BOARDS_9_KMH, 0.06).failures == ()
    (failure,) = judge_condition(condition.condition, runs, BOARDS_9_KMH, 0.04).failures
    assert failure.startswith("persistent oscillation after the road: pitch acceleration 0.090")


def test_reports_render(limit_cycle) -> None:
    markdown = check_markdown(limit_cycle)
    table = [line for line in markdown.splitlines() if line.startswith("|")]
    assert len(table) == 3 and all(line.count("|") == 12 for line in table)
    rows = check_csv(limit_cycle).splitlines()
    assert len(rows) == 1 + 3 and rows[1].split(",")[4] == "design"
    assert math.isfinite(limit_cycle.conditions[0].change)


def test_envelope_conditions_and_errors(tmp_path) -> None:
    assert len(Envelope().conditions()) == 2 * (4 + 3 * 3)
    path = tmp_path / "envelope.toml"
    path.write_text('[envelope]\nloads = ["full"]\nroad_classes = ["C"]\n[criteria]\n')
    envelope = load_envelope(path)
    assert [c.label for c in envelope.conditions()][:5] == [
        "full, boards 5 km/h",
        "full, boards 9 km/h",
        "full, boards 13.5 km/h",
        "full, boards 18 km/h",
        "full, ISO C 5 km/h",
    ]
    cases = {
        "[envelope]\nroad_classes = ['Z']\n": r"road_classes = \('Z',\); allowed: ISO 8608",
        "[envelope]\nsettle_s = 0.5\n": "settle_s = 0.5; allowed: a number from 2 to 30",
        "[criteria]\nworse = 1\n": r"unknown key\(s\) \['worse'\]",
        "[other]\n": r"unknown section\(s\) \['other'\]",
        "[envelope]\nseeds = 3\n": "seeds = 3; allowed: a list",
        "[envelope]\nboard_speeds_kmh = [nan]\n": "board_speeds_kmh = \\(nan,\\)",
        "[envelope\n": "envelope file .*envelope.toml",
    }
    for text, message in cases.items():
        path.write_text(text)
        with pytest.raises(ValueError, match=message):
            load_envelope(path)


def test_a_margin_met_to_the_designs_tolerance_passes(decaying) -> None:
    """The gain design puts its optimum on σ itself: a margin 0.05 % of σ short passes, 0.2 %
    short fails and is named with the margin."""
    import dataclasses

    from loader_model.experiments.design_check import LinearMargin

    sigma = decaying.envelope.margin_rad_s
    for margin, fails in ((sigma * (1 - 5e-4), False), (sigma * (1 - 2e-3), True)):
        check = dataclasses.replace(decaying, margins={"empty": LinearMargin("empty", margin, 0.1)})
        assert (not check.passed) is fails
        assert (
            any("linearised loop margin 0.0998 rad/s below 0.1" in f for f in check.failures)
            is fails
        )


def test_a_design_that_does_not_hold_still_at_rest_fails(decaying) -> None:
    """Noise alone can set off a limit cycle (a tractor with a front loader, full bucket: 6.2
    rad/s² at rest with the pump at its limits): the run at rest then fails the design."""
    import dataclasses

    from loader_model.experiments.design_check.runs import holds_still

    rest = decaying.rest["empty"]
    assert holds_still(rest) and decaying.passed  # the refined gains hold still (measured)
    cycling = dataclasses.replace(rest, tail_rms=6.2, command_duty=0.12, rate_duty=0.3)
    assert not holds_still(cycling)
    check = dataclasses.replace(decaying, rest={"empty": cycling})
    assert check.failures == (
        "empty, at rest with the sensors' noise alone: the pump at its limits (command 12.0%, "
        "rate 30.0% of the run), pitch acceleration 6.200 rad/s² r.m.s.: the loop does not "
        "hold still",
    )
