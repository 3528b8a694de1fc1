"""The Table 6 calibration: its targets, its cost, its search box and the held-out cells."""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import pytest

from loader_model.experiments import calibration_table6 as calibration
from loader_model.experiments import table6
from loader_model.experiments.agreement import paper_scatter
from loader_model.experiments.table6 import PAPER_TABLE_6


def _outcome(load: str, controller: str, a_total: float) -> SimpleNamespace:
    return SimpleNamespace(
        spec=SimpleNamespace(load=load, controller=controller), a_total_m_s2=a_total
    )


def test_targets_are_the_fitted_speeds_cells_only() -> None:
    nine = calibration.paper_targets(9.0)
    assert nine[("empty", "skyhook")] == -33.6 and nine[("full", "virtual-accumulator")] == 6.0
    assert len(nine) == 6 and len(calibration.paper_targets(18.0)) == 6
    assert calibration.paper_targets(18.0)[("full", "passive")] == -10.7
    with pytest.raises(ValueError, match="speed_kmh 12"):
        calibration.paper_targets(12)


def test_mean_changes_and_cost_against_a_hand_computation() -> None:
    outcomes = [
        _outcome("empty", "baseline", 4.0),
        _outcome("empty", "baseline", 6.0),
        _outcome("empty", "skyhook", 4.0),
        _outcome("empty", "passive", 6.0),
    ]
    changes = calibration.mean_changes(outcomes)
    assert changes == {
        ("empty", "skyhook"): pytest.approx(-20.0),
        ("empty", "passive"): pytest.approx(20.0),
    }
    targets = {("empty", "skyhook"): -30.0, ("empty", "passive"): 0.0}
    assert calibration.table6_cost(changes, targets) == pytest.approx(1.0**2 + 2.0**2)
    with pytest.raises(ValueError, match="no model cells"):
        calibration.table6_cost(changes, {("full", "skyhook"): 1.0})


def test_the_search_box_maps_the_shipped_values_and_the_bounds() -> None:
    for path, distribution in calibration.estimated_parameters():
        value = calibration.shipped_value(path)
        u = calibration._to_unit(distribution, value, path)
        assert 0.0 < u < 1.0, path
        assert calibration._to_value(distribution, u) == pytest.approx(value, rel=1e-12)
        assert calibration._to_value(distribution, 0.0) == pytest.approx(distribution.low)
        assert calibration._to_value(distribution, 1.0) == pytest.approx(distribution.high)
        assert distribution.source.startswith("estimate")


@pytest.mark.slow  # 9.7 s on a cold cache: two small fits of 128 three-second trials
def test_the_fit_never_reads_the_held_out_cells(monkeypatch) -> None:
    """Garbage in the 18 km/h cells of the paper's table changes nothing, and no 18 km/h trial
    runs, when fitting the 9 km/h cells (a small budget on a short drive)."""
    speeds: set[float] = set()
    run_trial = table6.run_trial

    def spy(spec):
        speeds.add(spec.speed_kmh)
        return run_trial(spec)

    monkeypatch.setattr(table6, "run_trial", spy)
    options = {"evaluations": 4, "design_points": 2, "trials": 2, "jobs": 1, "duration_s": 3.0}
    honest = calibration.calibrate_table6(9.0, progress=False, **options)
    poisoned = {key: dict(cells) for key, cells in PAPER_TABLE_6.items()}
    for key in (("High", "Low"), ("High", "High")):
        poisoned[key] = {c: (math.nan, math.nan) for c in poisoned[key]}
    monkeypatch.setattr(table6, "PAPER_TABLE_6", poisoned)
    blind = calibration.calibrate_table6(9.0, progress=False, **options)
    assert speeds == {9.0}
    assert blind == honest and math.isfinite(blind.cost)
    assert blind.cost <= blind.start_cost


def test_bad_budgets_are_named() -> None:
    with pytest.raises(ValueError, match="design_points 3: allowed: a power of 2"):
        calibration.calibrate_table6(9.0, design_points=3, progress=False)
    with pytest.raises(ValueError, match="evaluations 5: allowed: at least"):
        calibration.calibrate_table6(9.0, evaluations=5, design_points=4, progress=False)


def _speed_outcomes(groups: dict[tuple[str, str], list[float]]) -> list[SimpleNamespace]:
    return [_outcome(load, c, a) for (load, c), values in groups.items() for a in values]


def test_cell_statistics_give_the_change_and_the_pooled_scatter() -> None:
    # baseline 4, 6, 4, 6 (mean 5, SD √(4/3)); skyhook 3, 5, 3, 5 (mean 4, the same SD): change
    # -20 %, pooled SD √(4/3) / 5 of the baseline mean; one stopped trial (NaN) of 9 left out
    groups = {("empty", "baseline"): [4.0, 6.0] * 2, ("empty", "skyhook"): [3.0, 5.0] * 2}
    groups[("empty", "skyhook")].append(math.nan)
    changes, scatters = calibration.cell_statistics(_speed_outcomes(groups))
    assert changes == {("empty", "skyhook"): pytest.approx(-20.0, rel=1e-12)}
    sd = 100 * math.sqrt(4 / 3) / 5
    assert scatters == {("empty", "skyhook"): pytest.approx(sd, rel=1e-12)}
    groups[("empty", "baseline")].append(math.nan)  # 2 of 10: more than one in eight
    with pytest.raises(ValueError, match="2 of 10 trials stopped by the validity checks"):
        calibration.cell_statistics(_speed_outcomes(groups))


def test_the_cost_adds_the_scatter_in_factors_of_two() -> None:
    targets = {("empty", "passive"): -26.4, ("empty", "skyhook"): -33.6}
    paper = {key: paper_scatter(9.0, *key) for key in targets}
    changes = {("empty", "passive"): -16.4, ("empty", "skyhook"): -33.6}
    # passive: 10 pp off (1) and twice the paper's scatter (1); skyhook: on the mean, below
    # its upper bound (0)
    scatters = {("empty", "passive"): 2 * paper[("empty", "passive")].sd_percent}
    scatters[("empty", "skyhook")] = 0.5 * paper[("empty", "skyhook")].sd_percent
    cost = calibration.table6_cost(changes, targets, scatters, paper, weight=3.0)
    assert cost == pytest.approx(1.0 + 3.0 * 1.0, rel=1e-12)
    assert calibration.table6_cost(changes, targets) == pytest.approx(1.0, rel=1e-12)
    assert calibration.table6_cost(changes, targets, scatters, paper, 0.0) == pytest.approx(1.0)
    with pytest.raises(ValueError, match=re.escape("weight must be >= 0 and finite; got -1.0")):
        calibration.table6_cost(changes, targets, scatters, paper, weight=-1.0)
    with pytest.raises(ValueError, match="scatters need paper_scatters"):
        calibration.table6_cost(changes, targets, scatters)


def test_the_scatter_targets_are_the_fitted_speeds_cells_only() -> None:
    eighteen = calibration.scatter_targets(18.0)
    assert set(eighteen) == set(calibration.paper_targets(18.0))
    assert eighteen[("full", "passive")] == paper_scatter(18.0, "full", "passive")


def test_bad_trials_and_weights_are_named() -> None:
    with pytest.raises(ValueError, match=re.escape("trials 1: allowed: an integer >= 2")):
        calibration.calibrate_table6(9.0, trials=1, progress=False)
    with pytest.raises(
        ValueError, match=re.escape("scatter_weight -0.5: allowed: a finite number >= 0")
    ):
        calibration.calibrate_table6(9.0, scatter_weight=-0.5, progress=False)
