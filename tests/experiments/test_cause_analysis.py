"""The linear cause analysis of the Table 6 sign reversal (issue 13): what the report states holds."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.experiments.cause_analysis import board_changes, plant_modes


def _coupled_boom_mode(modes: list[tuple[float, float]]) -> tuple[float, float]:
    """The baseline mode between 4 and 5 Hz (the boom bouncing on the oil columns)."""
    (mode,) = [m for m in modes if 4.0 <= m[0] <= 5.0]
    return mode


def test_table5_leakage_is_what_damps_the_pump_held_boom() -> None:
    frequency, damping = _coupled_boom_mode(plant_modes("empty"))
    assert 4.5 < frequency < 4.8
    assert damping > 0.2
    _, undamped = _coupled_boom_mode(plant_modes("empty", {"k_Lp": 0.0}))
    assert undamped < 0.1


def test_linear_changes_reverse_sign_with_the_leakage_slope_only() -> None:
    model = board_changes("empty", 9.0)
    assert model["baseline"] == 0.0
    assert all(model[c] > 0.0 for c in ("passive", "virtual_accumulator", "skyhook"))
    without = board_changes("empty", 9.0, {"k_Lp": 0.0})
    assert without["virtual_accumulator"] < 0.0 and without["skyhook"] < 0.0


def test_overrides_scale_or_replace_and_gains_reach_the_skyhook() -> None:
    doubled = board_changes("empty", 9.0, {"c_Ay": "x2", "c_By": "x2"})
    assert doubled["baseline a_total"] < board_changes("empty", 9.0)["baseline a_total"]
    zero = board_changes("empty", 9.0, gains=(0.0, 0.0, 0.0, 0.0))
    assert zero["skyhook"] == pytest.approx(zero["virtual_accumulator"], abs=1e-9)
    table3 = board_changes("empty", 9.0)
    assert np.isfinite(table3["skyhook"]) and table3["skyhook"] != zero["skyhook"]
