"""The agreement rule of a Table 6 cell (mean within 10 pp, scatter within a factor 2) and the
misfit terms of the calibration's cost (fast: no trials)."""

from __future__ import annotations

import math
import re

import pytest

from loader_model.experiments.agreement import (
    mean_agrees,
    mean_misfit,
    paper_scatter,
    scatter_agrees,
    scatter_misfit,
)
from loader_model.experiments.scatter import implied_scatter


def test_the_mean_rule_is_ten_percentage_points_either_way() -> None:
    assert mean_misfit(-16.4, -26.4) == pytest.approx(1.0, rel=1e-12)
    assert mean_misfit(-36.4, -26.4) == pytest.approx(-1.0, rel=1e-12)
    assert mean_agrees(-16.5, -26.4) and mean_agrees(-36.3, -26.4)
    assert not mean_agrees(-16.3, -26.4) and not mean_agrees(-36.5, -26.4)


def test_the_scatter_rule_is_a_factor_two_either_way() -> None:
    assert scatter_misfit(8.0, 4.0, False) == pytest.approx(1.0, rel=1e-12)
    assert scatter_misfit(1.0, 4.0, False) == pytest.approx(-2.0, rel=1e-12)
    assert scatter_agrees(7.9, 4.0, False) and scatter_agrees(2.1, 4.0, False)
    assert not scatter_agrees(8.1, 4.0, False) and not scatter_agrees(1.9, 4.0, False)


def test_an_upper_bound_only_counts_a_scatter_above_it() -> None:
    assert scatter_misfit(0.5, 4.6, True) == 0.0
    assert scatter_misfit(18.4, 4.6, True) == pytest.approx(2.0, rel=1e-12)
    assert scatter_agrees(0.1, 4.6, True) and not scatter_agrees(9.3, 4.6, True)


def test_a_scatter_of_zero_is_an_infinite_misfit_and_bad_values_are_named() -> None:
    assert scatter_misfit(0.0, 4.0, False) == -math.inf
    with pytest.raises(
        ValueError, match=re.escape("paper_sd_percent must be > 0 and finite; got 0.0")
    ):
        scatter_misfit(1.0, 0.0, False)
    with pytest.raises(ValueError, match=re.escape("sd_percent must be >= 0 and finite; got nan")):
        scatter_misfit(math.nan, 4.0, False)


def test_the_paper_scatter_of_a_cell_is_its_implied_scatter() -> None:
    # Table 6, 9 km/h, 340 kg, passive: Δ = -26.4 %, p = 0.0001; skyhook p = 0.0000 (a bound)
    assert paper_scatter(9.0, "empty", "passive") == implied_scatter(-26.4, 0.0001)
    assert paper_scatter(9.0, "empty", "skyhook").upper_bound
    with pytest.raises(ValueError, match=re.escape("cell 12.0/'empty': allowed speeds")):
        paper_scatter(12.0, "empty", "passive")
    with pytest.raises(ValueError, match="controller 'baseline': allowed"):
        paper_scatter(9.0, "empty", "baseline")
