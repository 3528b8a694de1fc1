"""Error-controlled ROS2 substeps (module notes of :mod:`loader_model.simulation.adaptive`).

The mechanism is driven by its tolerance: at zero every period climbs to the largest count and
stays there, close to the run with that many fixed substeps; at infinity every period takes
one substep, which must equal the run with one. Both in CasADi's virtual machine (no
compilation), over 0.3 s of the passive machine meeting a 40 mm board.
"""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.experiments.trials import plant_for
from loader_model.plant.plant import STATE_NAMES
from loader_model.simulation import adaptive, stepper
from loader_model.simulation.courses import Course
from loader_model.simulation.roads import board_course, flat_road
from loader_model.simulation.simulator import course_input, simulate


@pytest.fixture(scope="module")
def passive():
    """The passive machine, full bucket, over one 40 mm board met by the front axle at 0.12 s."""
    params = plant_for("passive", "full")
    course = Course(board_course(1, height_m=0.04, width_m=0.14, spacing_m=0.0), 2.5, -0.3, 2.0, "")
    return params, course_input(course, params)


def _states(result) -> np.ndarray:
    return np.column_stack([result[name] for name in STATE_NAMES])


def _with_tolerance(monkeypatch, tolerance: float) -> None:
    """Build the adaptive period afresh with ``tolerance`` (not the process's cached one)."""
    monkeypatch.setattr(adaptive, "STEP_TOLERANCE", tolerance)
    monkeypatch.setattr(stepper, "_COMPILED", {})


@pytest.mark.parametrize(("tolerance", "fixed", "within"), [(0.0, 8, 5e-3), (np.inf, 1, 1e-9)])
def test_the_tolerance_at_its_limits_is_the_fixed_count(
    passive, monkeypatch, tolerance, fixed, within
):
    """Infinite tolerance: every period takes one substep, the fixed one-substep run to 1e-9 of
    each state's range (measured: identical). Zero: every period takes the largest count (8),
    whose substeps share the Jacobian of the period's start, against the fixed 8 substeps
    with a Jacobian each: within 5e-3 of each state's range (measured 8.7e-4 over the board)."""
    params, road = passive
    _with_tolerance(monkeypatch, tolerance)
    chosen = simulate(road, params, duration_s=0.3, substeps=None, jit=False)
    plain = simulate(road, params, duration_s=0.3, substeps=fixed, jit=False)
    assert chosen.metadata["substep_periods"] == {str(fixed): chosen.time_s.size}
    assert chosen.metadata["mean_substeps"] == fixed
    ours, theirs = _states(chosen), _states(plain)
    scale = np.ptp(theirs, axis=0) + 1e-12
    assert np.max(np.abs(ours - theirs) / scale) <= within


# slow: 9 s (the opt-in error-controlled stepping compiled and run twice)
@pytest.mark.slow
def test_smooth_stretches_take_one_substep_and_a_board_more(passive) -> None:
    """At rest on a flat road every period takes one substep; over the board (first 0.6 s,
    the front and rear axles over it) some periods take more, most still one."""
    params, road = passive
    flat = course_input(Course(flat_road(5.0), 2.5, -0.3, 1.0, ""), params)
    rest = simulate(road=flat, params=params, duration_s=0.5, substeps=None)
    assert rest.metadata["substep_periods"] == {"1": rest.time_s.size}
    board = simulate(road, params, duration_s=0.6, substeps=None)
    counts = {int(n): k for n, k in board.metadata["substep_periods"].items()}
    assert sum(counts.values()) == board.time_s.size
    assert max(counts) >= 4
    assert counts.get(1, 0) >= 20
    assert board.metadata["substeps"] == "adaptive"


def test_the_level_starts_at_one_substep_and_the_carry_keeps_the_command_last() -> None:
    """The adaptive period's carry is (x, z, level, u): one entry more than the fixed period's,
    the command still last (the refinement of a failed period reads it there)."""
    from loader_model.simulation.controllers import hold_command_controller

    fixed = stepper.period_function(hold_command_controller(), 1e-3, 4)
    chosen = adaptive.adaptive_period_function(hold_command_controller())
    assert chosen.size1_in(0) == fixed.size1_in(0) + 1
    assert chosen.name_out()[:4] == fixed.name_out()
    assert adaptive.SUBSTEP_COUNTS == tuple(
        2**level for level in range(len(adaptive.SUBSTEP_COUNTS))
    )
