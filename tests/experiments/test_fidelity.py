"""The fidelity budget's steps, its per-step summary and its rendering (fast: no trials)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from loader_model.experiments.fidelity import budget_steps, step_summary
from loader_model.experiments.fidelity_report import (
    budget_section,
    comfort_rows,
    comfort_summary,
    largest_standard_error,
    trial_count,
)
from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS
from loader_model.experiments.variant import AS_BUILT, AS_IT_WAS, ModelVariant


def _cell(speed: float, load: str, controller: str, change: float, p: float = 0.01):
    paper, paper_p = PAPER_TABLE_6[(SPEED_LABELS[speed], LOAD_LABELS[load])][controller]
    model = SimpleNamespace(
        change_percent=change, low_percent=change - 3, high_percent=change + 3, p_value=p
    )
    return SimpleNamespace(
        speed_kmh=speed, load=load, controller=controller, model=model,
        paper_change_percent=paper, paper_p_value=paper_p, within=abs(change - paper),
    )  # fmt: skip


def _cells(offset: float) -> list:
    return [
        _cell(s, ld, c, PAPER_TABLE_6[(SPEED_LABELS[s], LOAD_LABELS[ld])][c][0] + offset)
        for s in (9.0, 18.0)
        for ld in ("empty", "full")
        for c in ("passive", "virtual-accumulator", "skyhook")
    ]


def test_the_steps_add_up_from_the_old_model_to_the_model_as_built() -> None:
    steps = budget_steps({9.0: {"seat.seated_mass": 70.0}})
    assert steps[0].variant == AS_IT_WAS
    assert steps[4].variant == ModelVariant(label=steps[4].label)  # as built, relabelled
    assert [s.variant.holding_valves for s in steps[:5]] == [False, True, True, True, True]
    assert [s.variant.occupant for s in steps[:5]] == [False, False, True, True, True]
    assert [s.variant.envelope for s in steps[:5]] == ["rigid"] * 3 + ["tandem-cam"] * 2
    assert steps[5].held_out_kmh == 18.0 and dict(steps[5].variant.values) == {
        "seat.seated_mass": 70.0
    }
    assert steps[5].variant.table3_gain == AS_BUILT.table3_gain


def test_summary_counts_cells_held_out_cells_and_significant_signs() -> None:
    step = budget_steps({9.0: {}})[5]
    exact = step_summary(step, _cells(0.0))
    assert exact["within"] == 12 and exact["held_out_within"] == 6 and exact["held_out_count"] == 6
    # nine paper cells have p < 0.05; two of them are positive (9 km/h full: +6.0, +2.5)
    assert exact["significant_count"] == 9 and exact["significant_in_sign"] == 9
    shifted = step_summary(step, _cells(-11.0))
    assert shifted["within"] == 0
    assert shifted["significant_in_sign"] == 7  # +6.0 and +2.5 turn negative


def test_the_budget_renders_with_its_command_and_every_step() -> None:
    step = budget_steps({9.0: {"seat.seated_mass": 70.0}})
    summaries = []
    for s in step:
        summary = step_summary(s, _cells(1.0))
        summary["baseline_a_total"] = {
            "9/empty": 3.4,
            "9/full": 3.3,
            "18/empty": 6.2,
            "18/full": 5.9,
        }
        summaries.append(summary)
    uncertainty = {
        "samples": 8,
        "cells": {"9/empty/skyhook": {"share": 0.25, "count": 4, "failed": 1, "paper": -33.6}},
    }
    budget = {"command": "loader-model fidelity --trials 4", "date": "2026-12-01", "wall_time_s": 12.0,
              "steps": summaries, "uncertainty": uncertainty}  # fmt: skip
    text, tables = budget_section(budget)
    assert "`loader-model fidelity --trials 4` on 2026-12-01" in text
    # every cell's interval is +-3 pp: the standard error is at most 3 / 1.96 pp
    assert "4 trials per group" in text and "standard error of at most 1.5 pp" in text
    assert [row[0] for row in tables["fidelity_budget"][1:]] == [s.label for s in step]
    assert tables["uncertainty"][1] == ["9/empty/skyhook", "-33.6", "25 %", "4 (1)"]
    assert (
        "70"
        in tables["calibrated_values"][
            [r[0] for r in tables["calibrated_values"]].index("seat.seated_mass")
        ][2]
    )
    assert budget_section(None)[1] == {}


def test_the_trial_count_is_the_budgets_or_its_commands() -> None:
    assert trial_count({"trials": 80, "command": "loader-model fidelity --trials 4"}) == 80
    assert trial_count({"command": "loader-model fidelity --trials 80 --seed 0"}) == 80
    assert trial_count({"command": "loader-model fidelity --seed 0"}) == 4  # the default
    cell = {"change": 1.0, "low": -2.92, "high": 4.92}  # half-width 3.92 = 2 x 1.96
    # 1.96 rounds the quantile 1.959964: 2.0000367
    assert largest_standard_error([{"cells": {"a": cell}}]) == pytest.approx(2.0, rel=1e-4)


def test_comfort_rows_give_the_level_and_the_exposure_time() -> None:
    def outcome(controller: str, a: float, a_wx: float, a_wz: float):
        return SimpleNamespace(
            spec=SimpleNamespace(speed_kmh=9.0, load="empty", controller=controller),
            a_total_m_s2=a,
            weighted_rms={"x": a_wx, "z": a_wz, "pitch": 0.1},
        )

    outcomes = [
        outcome("baseline", 3.0, 0.5, 2.0),
        outcome("baseline", 3.4, 0.5, 2.0),
        outcome("skyhook", 1.0, 0.5, 0.5),
    ]
    rows = comfort_rows(outcomes, ("baseline", "skyhook", "passive"))
    # baseline: a_wz 2.0 dominates 1.4 x 0.5 -> 480 min (0.5 / 2)^2 = 30 min;
    # skyhook: 1.4 a_wx = 0.7 dominates -> 480 (0.5 / 0.7)^2 = 244.9 min
    assert rows[1] == ["9 km/h", "empty", "3.20 (30.0 min)", "1.00 (244.9 min)", "-"]
    summary = comfort_summary(outcomes)
    assert "from 1.00 to 3.20 m/s²" in summary
    assert "1 of 2 'extremely uncomfortable'; 1 of 2 'uncomfortable'" in summary


def test_a_variant_checks_its_envelope_and_gains() -> None:
    with pytest.raises(ValueError, match="envelope 'soft'"):
        ModelVariant(envelope="soft")
    with pytest.raises(ValueError, match="4 gains"):
        ModelVariant(table3_gain=(1.0, 2.0))
    merged = AS_BUILT.with_values({"b.x": 2.0, "a.y": 1})
    assert merged.values == (("a.y", 1.0), ("b.x", 2.0))
