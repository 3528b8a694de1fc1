"""The plausible machines' mean-and-scatter study, the budget's per-cell scatter and their tables
(fast: synthetic outcomes, no trials)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from loader_model.experiments.agreement import paper_scatter
from loader_model.experiments.agreement_report import agreement_text, machine_rows
from loader_model.experiments.calibration_table6 import estimated_parameters
from loader_model.experiments.fidelity import scatter_summary
from loader_model.experiments.machine_agreement import cell_shares, machine_values

KEY = "9/empty/passive"  # paper: Δ = -26.4 %, p = 0.0001


def test_shares_count_mean_scatter_and_both_per_cell() -> None:
    sd = paper_scatter(9.0, "empty", "passive").sd_percent
    machines = [
        {KEY: (-26.0, sd, 1.0)},  # both agree
        {KEY: (-26.0, 3 * sd, 1.0)},  # mean only
        {KEY: (0.0, sd, 3.0)},  # scatter only
        {KEY: None},  # its group kept too few trials
        None,  # refused by the parameter files
    ]
    cell = cell_shares(machines)[KEY]
    assert cell["count"] == 3 and cell["failed"] == 2
    assert cell["mean_share"] == pytest.approx(2 / 3, rel=1e-12)
    assert cell["scatter_share"] == pytest.approx(2 / 3, rel=1e-12)
    assert cell["both_share"] == pytest.approx(1 / 3, rel=1e-12)
    assert cell["se_median"] == pytest.approx(1.0, rel=1e-12)
    assert cell["paper"] == -26.4 and not cell["paper_sd_bound"]
    other = cell_shares(machines)["18/full/skyhook"]
    assert other["count"] == 0 and math.isnan(other["both_share"])
    rows = machine_rows({"cells": {KEY: cell}})
    assert rows[1][2:6] == ["67 %", "67 %", "33 %", "3 (2)"]


def test_the_machines_lie_inside_the_plausible_ranges() -> None:
    machines = machine_values(8)
    assert len(machines) == 8
    for path, distribution in estimated_parameters():
        values = [m[path] for m in machines]
        assert all(distribution.low <= v <= distribution.high for v in values), path
        # a Latin hypercube: one machine in each eighth of the range (in the sampled scale)
        scale = math.log if distribution.kind == "loguniform" else float
        low, high = scale(distribution.low), scale(distribution.high)
        bins = sorted(int(8 * (scale(v) - low) / (high - low)) for v in values)
        assert bins == list(range(8)), path
    with pytest.raises(ValueError, match="machines 1: allowed"):
        machine_values(1)


def _outcome(speed: float, load: str, controller: str, a: float) -> SimpleNamespace:
    spec = SimpleNamespace(speed_kmh=speed, load=load, controller=controller)
    return SimpleNamespace(spec=spec, a_total_m_s2=a)


def test_the_budget_cells_get_their_scatter_and_the_counts() -> None:
    # baseline 4, 6 (mean 5); passive 3, 5: Δ -20 % (6.4 pp from the paper's -26.4), pooled SD
    # √2 / 5 = 28.3 % of the mean, far above the paper's 4.1 %
    outcomes = [_outcome(9.0, "empty", "baseline", a) for a in (4.0, 6.0)]
    outcomes += [_outcome(9.0, "empty", "passive", a) for a in (3.0, 5.0)]
    cells = {KEY: {"change": -20.0, "paper": -26.4}}
    counts = scatter_summary(outcomes, 9.0, cells)
    assert cells[KEY]["sd"] == pytest.approx(100 * math.sqrt(2) / 5, rel=1e-12)
    assert not cells[KEY]["scatter_agrees"] and not cells[KEY]["agrees"]
    assert counts["scatter_within"] == 0 and counts["held_out_scatter_within"] == 0
    # a tighter passive group: SD √((0.02 + 2) / 2) / 5 = 20.1 %, still above 2 × 4.1 %
    tight = [*outcomes[:2], *(_outcome(9.0, "empty", "passive", a) for a in (3.9, 4.1))]
    assert not scatter_summary(tight, None, cells)["scatter_within"]
    assert scatter_summary(tight, None, cells)["held_out_both_within"] is None


def test_the_report_shows_the_calibrated_cells_and_the_machines() -> None:
    cell = {
        "change": -20.0, "se": 1.2, "sd": 5.0, "paper": -26.4, "paper_sd": 4.1,
        "paper_sd_bound": False, "scatter_agrees": True, "agrees": True,
    }  # fmt: skip
    step = {
        "label": "+ calibrated to 9 km/h", "held_out_kmh": 18.0, "cells": {KEY: cell},
        "within": 1, "count": 1, "held_out_within": 0, "held_out_count": 0, "largest_se": 1.2,
        "scatter_within": 1, "both_within": 1, "held_out_scatter_within": 0,
        "held_out_both_within": 0,
    }  # fmt: skip
    machines = {"machines": 2, "trials": 6, "seed": 0, "stopped": 1, "refused": 0}
    machines["cells"] = cell_shares([{KEY: (-26.0, 4.0, 1.5)}, {KEY: (-40.0, 4.0, 2.5)}])
    text, tables = agreement_text({"steps": [step], "machines": machines})
    assert tables["calibrated_cells"][1] == [KEY, "-26.4 (4.1)", "-20.0 ± 1.2 (5.0)"]
    assert tables["calibrated_cells"][2][2] == "1 / 1 / 1 of 1 (0 / 0 / 0 of 0)"
    assert "largest standard error of a mean 1.2 pp" in text
    assert "2 plausible machines" in text and "6 trials per group" in text
    assert "(trials stopped by the validity checks: 1; machines the parameter" in text
    row = tables["machine_agreement"][[r[0] for r in tables["machine_agreement"]].index(KEY)]
    assert row[2:] == ["50 %", "100 %", "50 %", "2 (0)", "2.0"]
