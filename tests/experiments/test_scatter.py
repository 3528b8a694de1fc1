"""The scatter that Table 6's Δ and p imply, and the model's scatter statistics."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from loader_model.experiments.scatter import (
    implied_scatter,
    model_scatter,
    paper_implied_scatter,
)


def _pair(change: float, sd: float, trials: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Two samples of ``trials`` with sample SD ``sd`` each, means 100 and 100 + ``change``."""
    z = np.arange(trials) - (trials - 1) / 2.0
    z = z / z.std(ddof=1)
    return 100.0 + sd * z, 100.0 + change + sd * z


@pytest.mark.parametrize(("change", "p_value"), [(-26.4, 0.0001), (6.0, 0.0159), (-1.1, 0.6377)])
def test_a_pair_with_the_implied_sd_gives_back_the_p_value(change: float, p_value: float) -> None:
    sd = implied_scatter(change, p_value).sd_percent
    baseline, treated = _pair(change, sd)
    p_back = stats.ttest_ind(treated, baseline, equal_var=False).pvalue
    # exact inversion up to the t quantile's round-off (1e-12 relative measured)
    assert p_back == pytest.approx(p_value, rel=1e-8)


def test_the_rounding_interval_brackets_the_printed_p() -> None:
    scatter = implied_scatter(-22.6, 0.0003)
    assert scatter.low_percent < scatter.sd_percent < scatter.high_percent
    for sd, p_value in ((scatter.low_percent, 0.00025), (scatter.high_percent, 0.00035)):
        baseline, treated = _pair(-22.6, sd)
        assert stats.ttest_ind(treated, baseline, equal_var=False).pvalue == pytest.approx(
            p_value, rel=1e-8
        )
    assert not scatter.upper_bound and scatter.dof == 6.0


def test_a_printed_zero_p_is_an_upper_bound() -> None:
    scatter = implied_scatter(-33.6, 0.0)
    assert scatter.upper_bound and scatter.low_percent == 0.0
    baseline, treated = _pair(-33.6, scatter.sd_percent)
    assert stats.ttest_ind(treated, baseline, equal_var=False).pvalue == pytest.approx(
        5e-5, rel=1e-8
    )
    # any smaller scatter prints as 0.0000 too
    baseline, treated = _pair(-33.6, 0.5 * scatter.sd_percent)
    assert stats.ttest_ind(treated, baseline, equal_var=False).pvalue < 5e-5


def test_closed_form_with_a_tabulated_quantile() -> None:
    # t_{0.975, 6} = 2.446912 (Student's table): p = 0.05 gives s = |Δ| / (2.446912 sqrt(1/2))
    assert implied_scatter(10.0, 0.05).sd_percent == pytest.approx(
        10.0 / (2.446912 * np.sqrt(0.5)), rel=1e-6
    )


def test_every_table6_cell_has_a_scatter() -> None:
    cells = paper_implied_scatter()
    assert len(cells) == 12
    skyhook = cells[(9.0, "empty", "skyhook")]
    assert skyhook.upper_bound
    assert sum(c.upper_bound for c in cells.values()) == 1


@pytest.mark.parametrize(
    ("args", "match"),
    [((0.0, 0.01), "change_percent"), ((5.0, 1.0), "p_value"), ((5.0, 0.1, 1), "trials")],
)
def test_bad_input_is_named(args: tuple, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        implied_scatter(*args)


def test_model_scatter_standard_error_against_monte_carlo() -> None:
    """The delta-method standard error of the change equals the spread of the change over
    repeated experiments (normal trials, 12 % and 8 % SD, ratio 0.7, 40 trials per group)."""
    rng = np.random.default_rng(1)
    n, repeats = 40, 20000
    base = rng.normal(4.0, 0.48, (repeats, n))
    treated = rng.normal(2.8, 0.32, (repeats, n))
    changes = 100.0 * (treated.mean(axis=1) / base.mean(axis=1) - 1.0)
    one = model_scatter(base[0], treated[0])
    expected = 100.0 * np.sqrt(0.32**2 / n + 0.7**2 * 0.48**2 / n) / 4.0
    # the sample SD of 20000 changes is within 3 % of the truth (its relative SE is 0.5 %)
    assert changes.std() == pytest.approx(expected, rel=0.03)
    # one experiment's estimate scatters with its sample SDs (40 trials: about 11 % relative)
    assert one.standard_error_pp == pytest.approx(expected, rel=0.35)
    assert (
        one.trials_controller == one.trials_baseline == n
        and one.baseline_mean_m_s2 == pytest.approx(base[0].mean())
    )
    assert one.sd_percent == pytest.approx(
        np.hypot(treated[0].std(ddof=1), base[0].std(ddof=1)) / np.sqrt(2) * 100 / base[0].mean()
    )


def test_model_scatter_bad_input() -> None:
    with pytest.raises(ValueError, match="treated must hold at least 2"):
        model_scatter([1.0, 2.0, 3.0], [1.0])
    with pytest.raises(ValueError, match="baseline mean must be > 0"):
        model_scatter([-1.0, -2.0], [1.0, 2.0])
    with pytest.raises(ValueError, match="baseline"):
        model_scatter([1.0, np.nan], [1.0, 2.0])
