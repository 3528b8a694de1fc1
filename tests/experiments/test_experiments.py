"""The Table 6 experiment: statistics against scipy, seeded trials, a short run, the report folder."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from loader_model.cli import main
from loader_model.experiments.report import write_report
from loader_model.experiments.statistics import compare_with_baseline, mean_interval
from loader_model.experiments.table6 import run_trials, table6_cells
from loader_model.experiments.trials import (
    SPEED_LIMIT_FRACTION,
    run_trial,
    trial_specs,
)

BASE = [4.1, 3.9, 4.0, 4.2]
TREATED = [3.0, 3.3, 2.9, 3.1]


def test_welch_comparison_matches_scipy() -> None:
    comparison = compare_with_baseline(BASE, TREATED)
    reference = stats.ttest_ind(TREATED, BASE, equal_var=False)
    assert comparison.p_value == pytest.approx(reference.pvalue, rel=1e-12)
    interval = reference.confidence_interval(0.95)
    scale = 100.0 / np.mean(BASE)
    assert comparison.low_percent == pytest.approx(interval.low * scale, rel=1e-10)
    assert comparison.high_percent == pytest.approx(interval.high * scale, rel=1e-10)
    assert comparison.change_percent == pytest.approx(
        100.0 * (np.mean(TREATED) / np.mean(BASE) - 1.0), rel=1e-12
    )


def test_mean_interval_matches_scipy() -> None:
    mean, low, high = mean_interval(BASE)
    reference = stats.t.interval(0.95, len(BASE) - 1, np.mean(BASE), stats.sem(BASE))
    assert mean == pytest.approx(np.mean(BASE), rel=1e-12)
    assert (low, high) == pytest.approx(reference, rel=1e-12)


def test_too_few_trials_is_a_value_error() -> None:
    with pytest.raises(ValueError, match="at least 2"):
        compare_with_baseline([4.0], TREATED)


def test_trials_are_reproducible_from_the_seed() -> None:
    first, again, other = trial_specs(3, 4), trial_specs(3, 4), trial_specs(4, 4)
    assert first == again
    assert first != other
    assert len(first) == 2 * 2 * 4 * 4
    factors = np.array([s.speed_factor for s in first])
    assert np.all(np.abs(factors - 1.0) <= SPEED_LIMIT_FRACTION + 1e-15)
    assert len({s.course_seed for s in first}) == len(first)
    # a trial's draw does not depend on which other factors are run
    subset = trial_specs(3, 4, controllers=("baseline", "skyhook"))
    assert [s for s in first if s.controller in ("baseline", "skyhook")] == subset


@pytest.mark.parametrize("bad", [-1, 1.5, True])
def test_bad_seed_is_a_value_error(bad: object) -> None:
    with pytest.raises(ValueError, match="seed"):
        trial_specs(bad, 1)  # type: ignore[arg-type]


def test_small_experiment_runs_and_is_deterministic() -> None:
    specs = trial_specs(
        0,
        2,
        speeds_kmh=(9.0,),
        loads=("empty",),
        controllers=("baseline", "passive"),
        duration_s=3.0,
    )
    outcomes = run_trials(specs, jobs=1, progress=False)
    assert [o.spec for o in outcomes] == specs
    assert all(np.isfinite(o.a_total_m_s2) and o.a_total_m_s2 > 0 for o in outcomes)
    (cell,) = table6_cells(outcomes)
    assert cell.controller == "passive"
    assert cell.paper_change_percent == pytest.approx(-26.4)
    assert run_trial(specs[0]).a_total_m_s2 == pytest.approx(outcomes[0].a_total_m_s2, rel=1e-12)


def test_report_folder_is_replaced_only_when_complete(tmp_path: Path) -> None:
    target = tmp_path / "results" / "report"

    def good(folder: Path) -> None:
        (folder / "report.md").write_text("complete\n")

    def failing(folder: Path) -> None:
        (folder / "report.md").write_text("half")
        raise RuntimeError("simulated failure")

    with pytest.raises(RuntimeError):
        write_report(target, failing)
    assert not target.exists()
    assert list(target.parent.iterdir()) == []
    write_report(target, good)
    with pytest.raises(RuntimeError):
        write_report(target, failing)
    assert (target / "report.md").read_text() == "complete\n"
    assert [p.name for p in target.parent.iterdir()] == ["report"]


def test_report_on_a_file_is_a_value_error(tmp_path: Path) -> None:
    path = tmp_path / "report"
    path.write_text("x")
    with pytest.raises(ValueError, match="not a folder"):
        write_report(path, lambda folder: None)


def test_reproduce_rejects_one_trial(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["reproduce", "--trials", "1"]) == 2
    assert "--trials" in capsys.readouterr().err


def test_designed_controllers_add_rows_without_changing_the_paper_trials() -> None:
    gains = {"skyhook-lqr": (1.0, 2.0, 3.0, 4.0), "skyhook-optimised": (5.0, -6.0, 7.0, 8.0)}
    plain, extended = trial_specs(3, 2), trial_specs(3, 2, designed=gains)
    assert [s for s in extended if s.k_fb is None] == plain
    designed = [s for s in extended if s.k_fb is not None]
    assert len(designed) == 2 * 2 * 2 * 2
    assert {s.controller: s.k_fb for s in designed} == gains
    assert len({s.course_seed for s in extended}) == len(extended)
    with pytest.raises(ValueError, match="designed controllers"):
        trial_specs(3, 2, designed={"skyhook-fancy": (1.0, 2.0, 3.0, 4.0)})


def test_a_designed_controller_runs_the_skyhook_with_its_gains() -> None:
    from loader_model.control.settings import SETTINGS_NAMES
    from loader_model.experiments.trials import controller_arguments, plant_for

    params = plant_for("skyhook-optimised", "empty")
    arguments = controller_arguments("skyhook-optimised", "empty", params, (5.0, -6.0, 7.0, 8.0))
    vector = arguments["settings"]
    gains = [vector[SETTINGS_NAMES.index(n)] for n in ("k_x", "k_y", "k_theta", "k_phi")]
    assert gains == [5.0, -6.0, 7.0, 8.0]
    assert (
        arguments["controller"].name()
        == controller_arguments("skyhook", "empty", params)["controller"].name()
    )
    with pytest.raises(ValueError, match="needs its gains"):
        controller_arguments("skyhook-lqr", "empty", params)


def test_best_reductions_pick_the_largest_reduction_per_condition():
    """The paper's best controller per condition comes from Table 6 as printed, the model's
    from the cells' mean changes; a NaN change (failed trials) is never the best."""
    import math

    from loader_model.experiments.statistics import Comparison
    from loader_model.experiments.table6 import Table6Cell, best_reductions

    def cell(speed: float, load: str, controller: str, change: float) -> Table6Cell:
        model = Comparison(
            change_percent=change, low_percent=change, high_percent=change, p_value=0.5
        )
        return Table6Cell(speed, load, controller, model, math.nan, math.nan)

    best = best_reductions(
        [
            cell(9.0, "empty", "skyhook", -2.5),
            cell(9.0, "empty", "skyhook-refined", -38.4),
            cell(9.0, "empty", "passive", math.nan),
            cell(18.0, "full", "passive", -20.3),
            cell(18.0, "full", "skyhook", -4.7),
        ]
    )
    assert best["9 km/h empty"] == {
        "simulated": ("skyhook-refined", -38.4),
        "measured": ("skyhook", -33.6),
    }
    assert best["18 km/h full"] == {
        "simulated": ("passive", -20.3),
        "measured": ("virtual-accumulator", -16.1),
    }
    assert set(best) == {"9 km/h empty", "18 km/h full"}


def test_progress_counts_the_trials_and_the_report_steps(capsys) -> None:
    specs = trial_specs(
        0, 1, speeds_kmh=(9.0,), loads=("empty",), controllers=("baseline",), duration_s=3.0
    )
    ran: list[str] = []
    steps = [("Fig. 13", lambda: ran.append("fig13")), ("Table 4", lambda: ran.append("t4"))]
    run_trials(specs, jobs=1, progress=True, meanwhile=steps)
    bar = capsys.readouterr().err
    assert ran == ["fig13", "t4"]
    assert "1 trials + 2 report steps" in bar
    assert "3/3" in bar and "0/3" in bar
