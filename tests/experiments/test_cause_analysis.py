"""The linear cause analysis of the Table 6 sign reversal (issue 13): what the report states holds."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.experiments.cause_analysis import board_changes, plant_modes

#: The loader alone: the occupant's modes on the cushion (one at 4.3 Hz) are not the boom's.
LOADER = {"occupant_on": 0.0}


def _coupled_boom_mode(modes: list[tuple[float, float]]) -> tuple[float, float]:
    """The baseline mode between 4 and 5 Hz (the boom bouncing on the oil columns)."""
    (mode,) = [m for m in modes if 4.0 <= m[0] <= 5.0]
    return mode


def test_table5_flow_as_a_cylinder_leak_is_what_damped_the_baseline() -> None:
    """On closed load-holding valves (issue 21) the boom mode is lightly damped; reading Table 5's
    k_Lp as a cylinder leak (the valves open in the baseline too) damped it (measured: 4.64 Hz
    ζ 0.047 against 4.66 Hz ζ 0.275, empty bucket)."""
    frequency, damping = _coupled_boom_mode(plant_modes("empty", LOADER))
    assert 4.5 < frequency < 4.8
    assert damping < 0.1
    _, leaky = _coupled_boom_mode(plant_modes("empty", LOADER | {"holding_open": 1.0}))
    assert leaky > 0.2


def test_linear_changes_follow_the_paper_on_the_circuit_and_the_seat_pad() -> None:
    """Empty bucket, 9 km/h, one board (measured, %): circuit and seated occupant −9.1 (passive),
    −14.9 (virtual accumulator), −15.7 (skyhook); the occupant off +3.3, −5.2, −5.4; Table 5's
    flow as a cylinder leak in the baseline (valves open for all) +15.2, +7.6, +6.6."""
    model = board_changes("empty", 9.0)
    assert model["baseline"] == 0.0
    assert all(model[c] < 0.0 for c in ("passive", "virtual_accumulator", "skyhook"))
    chassis = board_changes("empty", 9.0, LOADER)
    assert chassis["passive"] > 0.0
    assert chassis["virtual_accumulator"] < 0.0 and chassis["skyhook"] < 0.0
    leaky = board_changes("empty", 9.0, {"holding_open": 1.0})
    assert all(leaky[c] > 0.0 for c in ("passive", "virtual_accumulator", "skyhook"))


@pytest.mark.slow  # 4.8 s of Table 6 trials
def test_overrides_scale_or_replace_and_gains_reach_the_skyhook() -> None:
    doubled = board_changes("empty", 9.0, {"c_Ay": "x2", "c_By": "x2"})
    assert doubled["baseline a_total"] < board_changes("empty", 9.0)["baseline a_total"]
    zero = board_changes("empty", 9.0, gains=(0.0, 0.0, 0.0, 0.0))
    assert zero["skyhook"] == pytest.approx(zero["virtual_accumulator"], abs=1e-9)
    table3 = board_changes("empty", 9.0)
    assert np.isfinite(table3["skyhook"]) and table3["skyhook"] != zero["skyhook"]
