"""Control design for a described machine other than the skid-steer (issue 23): the comfort plant of
the compact wheel loader, settings whose norms are scaled with large designed gains, and the
course refinement of ``design --method refine`` on it."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control.comfort_design import comfort_plants, evaluate_gain
from loader_model.control.controllers import controller_function
from loader_model.control.settings import (
    SETTINGS_NAMES,
    default_settings,
    settings_vector,
    with_scaled_gains,
)
from loader_model.plant.scenario import resolve_plant

MACHINE = "compact_wheel_loader"


def test_scaled_norms_give_the_same_control_law() -> None:
    gain = (10.5, -54.4, 211.4, 39.0)
    plain = default_settings()  # the raw gains are out of the file's range: compare the laws
    scaled = with_scaled_gains(plain, gain, "test")
    assert max(abs(k) for k in scaled.k_fb) <= 50.0 + 1e-12
    function = controller_function("skyhook")
    kwargs = {"pressure_norm": 6e6, "max_displacement": 4.6e-5, "hold_command": 0.0,
              "gravity": 9.80665, "accelerometer_x": 1.25}  # fmt: skip
    raw = settings_vector(plain, **kwargs)  # the shipped norms, the raw (out-of-range) gains
    raw[[SETTINGS_NAMES.index(n) for n in ("k_x", "k_y", "k_theta", "k_phi")]] = gain
    vector = settings_vector(scaled, **kwargs)
    rng = np.random.default_rng(0)
    for _ in range(5):
        y = np.array([0.3, 9.9, 10.2, 0.01, 4e6]) + rng.normal(0.0, 0.5, 5)
        z = rng.normal(0.0, 0.1, 4)
        # the filter states are semi-integrals of the normalised signals: scaled with them
        factor = (
            raw[[SETTINGS_NAMES.index(n) for n in ("a_norm", "a_norm", "alpha_norm")]]
            / (vector[[SETTINGS_NAMES.index(n) for n in ("a_norm", "a_norm", "alpha_norm")]])
        )
        z_scaled = np.r_[z[:3] * factor, z[3]]
        u_raw = float(function(z, y, raw)[1])
        u_scaled = float(function(z_scaled, y, vector)[1])
        assert u_raw != 0.0
        assert abs(u_scaled - u_raw) <= 1e-9 * abs(u_raw)


def test_scaling_leaves_the_callers_gains_as_given() -> None:
    """The scaled settings are a new object; the gains handed in (an array, as the designs and
    the course refinement hold them) keep their values."""
    gain = np.array([10.5, -54.4, 211.4, 39.0])
    kept = gain.copy()
    scaled = with_scaled_gains(default_settings(), gain, "test")
    np.testing.assert_array_equal(gain, kept)
    assert max(abs(k) for k in scaled.k_fb) <= 50.0 + 1e-12
    again = with_scaled_gains(default_settings(), gain, "test")  # the same settings twice
    assert again.k_fb == scaled.k_fb
    assert again.angular_acceleration_norm == scaled.angular_acceleration_norm


def test_wheel_loader_comfort_plant_and_table3_gain() -> None:
    params = {load: resolve_plant(None, load, machine=MACHINE) for load in ("empty", "full")}
    plants = comfort_plants(("empty", "full"), params=params)
    evaluations = evaluate_gain(plants, (2.75, 5.1, -4.0, 0.22))
    assert all(np.isfinite(e.a_total) and 0.5 < e.a_total < 10.0 for e in evaluations)


def _printed_course_totals(text: str, row: str) -> dict[str, float]:
    """The course a_total per load of one printed row of ``design --method refine``."""
    line = next(line for line in text.splitlines() if line.strip().startswith(row))
    shown = line.split("course a_total [m/s²]")[1].split()
    return {shown[i].rstrip(":"): float(shown[i + 1]) for i in range(0, len(shown), 2)}


@pytest.mark.slow  # 5 s; the library test of the wheel loader refinement stays fast
def test_design_refine_on_the_wheel_loader_writes_settings_that_drive_as_printed(
    tmp_path, capsys
) -> None:
    """``design --machine compact_wheel_loader --method refine`` from the linear optimum on both
    loads (k_θ beyond the settings file's ±100): the refinement drives the wheel loader's own
    plants and never ends above its start (a decrease within a few evaluations is tested on a
    short course in tests/experiments/test_course_refinement.py); the written file carries the
    gains with scaled norms, and driving it through ``simulate``'s path gives the printed course
    a_total per load."""
    from loader_model import cli
    from loader_model.control.settings import load_settings
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import resolve_scenario
    from loader_model.simulation.simulator import course_input, simulate

    target = tmp_path / "refined.toml"
    argv = ["design", "--machine", MACHINE, "--method", "refine", "--evaluations", "3"]
    argv += ["--no-check", "--force"]  # the refinement is tested here, the check elsewhere
    assert cli.main([*argv, "--output", str(target)]) == 0
    printed = capsys.readouterr().out
    start = _printed_course_totals(printed, "optimised (linear)")
    refined = _printed_course_totals(printed, "refined (course)")
    assert set(refined) == {"empty", "full"}
    assert sum(a**2 for a in refined.values()) <= sum(a**2 for a in start.values())
    settings = load_settings(target)
    source = settings.source("k_fb")
    assert source.startswith("loader-model design --method refine")
    assert f"--machine {MACHINE}" in source and "--evaluations 3" in source
    assert max(abs(k) for k in settings.k_fb) <= 50.0 + 1e-12
    assert settings.angular_acceleration_norm < default_settings().angular_acceleration_norm
    for load, printed_total in refined.items():
        scenario = resolve_scenario(
            None, load, controller="skyhook", settings=target, machine=MACHINE
        )
        result = simulate(course_input(paper_course(9.0), scenario), scenario)
        # printed with 4 decimals: to half a unit of the last one
        assert abs(result.seat_evaluation().total_m_s2 - printed_total) <= 0.5e-4 + 1e-9
