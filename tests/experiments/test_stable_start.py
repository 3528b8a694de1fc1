"""The nearest gains that keep the loop's margin on every plant: the start of the design on the
machine (loader_model.experiments.stable_start)."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.experiments.stable_start import loop_margin, nearest_stable_gain

#: The gains refined on the paper course (loader_model/data/controller_refined.toml): unstable
#: on 1 of the 16 plants the design check draws (margin −3.48 rad/s, measured).
REFINED = np.array(
    [37.992734723997316, -99.69001078329339, -18.531397286347172, 0.6830662188945267]
)


@pytest.fixture(scope="module")
def nominal():
    from loader_model.control.comfort_design import comfort_plants

    return comfort_plants(("empty", "full"))


def test_a_gain_that_keeps_the_margin_is_returned_as_it_is(nominal) -> None:
    assert loop_margin(nominal, REFINED) > 0.1  # measured 0.388 rad/s
    np.testing.assert_array_equal(nearest_stable_gain(REFINED, nominal, 0.1), REFINED.reshape(1, 4))


def test_bad_arguments_are_clear_errors(nominal) -> None:
    with pytest.raises(ValueError, match=r"margin_rad_s = -1.0; allowed: a number >= 0"):
        nearest_stable_gain(REFINED, nominal, -1.0)
    with pytest.raises(ValueError, match=r"gain = \[1.0, 2.0\]; allowed: 4 finite gains"):
        nearest_stable_gain([1.0, 2.0], nominal, 0.1)


# slow: the 16 sampled plants take about 10 s to build, each solve about 10 s
@pytest.mark.slow
def test_the_refined_gains_are_moved_the_least_onto_the_sampled_plants_margin(nominal) -> None:
    from loader_model.control.settings import default_settings
    from loader_model.experiments.design_check import Design
    from loader_model.experiments.design_check.margins import sampled_plants

    sampled = sampled_plants(Design(default_settings()), 16)
    plants = [*nominal, *sampled]
    assert loop_margin(plants, REFINED) < 0.0
    found = nearest_stable_gain(REFINED, plants, 0.1).ravel()
    # on the constraint, to the solver's feasibility tolerance (1e-6 rad/s accepted)
    assert loop_margin(plants, found) == pytest.approx(0.1, abs=1e-6)
    # the least move: every gain part-way back to the start breaks the margin, and the
    # uniform shrink of the gains that reaches it (by bisection) moves them further
    scale = np.maximum(np.abs(REFINED), 1.0)
    for fraction in (0.05, 0.2):
        assert loop_margin(plants, found + fraction * (REFINED - found)) < 0.1
    low, high = 0.0, 1.0
    for _ in range(30):
        middle = 0.5 * (low + high)
        low, high = (
            (middle, high) if loop_margin(plants, middle * REFINED) >= 0.1 else (low, middle)
        )
    uniform = low * REFINED
    assert np.linalg.norm((found - REFINED) / scale) < np.linalg.norm((uniform - REFINED) / scale)
    # a margin no gain reaches: the loop's margin is bounded by poles the gain does not move
    # (0.388 rad/s on the empty bucket's nominal plant)
    with pytest.raises(ValueError, match=r"keeps the loop margin 5 rad/s on all 18 plants"):
        nearest_stable_gain(REFINED, plants, 5.0)
