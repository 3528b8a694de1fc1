"""When a Table 6 cell of the model agrees with the paper's: its mean change and its scatter.

One rule for the calibration, its check on the held-out cells, the fidelity budget and the
uncertainty study:

- the mean: the model's change of a_total against the baseline within :data:`WITHIN_PP`
  percentage points of the paper's (Table 6);
- the scatter: the model's trial standard deviation (pooled over the controller's and the
  baseline's trials, in percent of the baseline mean, :func:`~loader_model.experiments.scatter.
  model_scatter`) within a factor :data:`SCATTER_FACTOR` of the one the paper's Δ and p imply
  (:func:`~loader_model.experiments.scatter.implied_scatter`). Where the paper prints
  p = 0.0000, the implied scatter is only an upper bound: the model agrees if its scatter is
  at most :data:`SCATTER_FACTOR` times that bound, and any smaller scatter is no misfit.

The misfit terms of the calibration's cost (:func:`mean_misfit`, :func:`scatter_misfit`) are
measured in the same units as these rules, so that one unit of misfit is the edge of agreement.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = [
    "SCATTER_FACTOR",
    "WITHIN_PP",
    "mean_agrees",
    "mean_misfit",
    "paper_scatter",
    "scatter_agrees",
    "scatter_misfit",
]

#: Percentage points within which a cell's mean change counts as reproduced.
WITHIN_PP = 10.0
#: Factor within which a cell's trial scatter counts as reproduced.
SCATTER_FACTOR = 2.0


def mean_misfit(change_percent: float, paper_percent: float) -> float:
    """(Δ_model − Δ_paper) / :data:`WITHIN_PP`: ±1 at the edge of agreement."""
    return (change_percent - paper_percent) / WITHIN_PP


def scatter_misfit(sd_percent: float, paper_sd_percent: float, upper_bound: bool) -> float:
    """log(s_model / s_paper) / log :data:`SCATTER_FACTOR`: ±1 at the edge of agreement.

    With ``upper_bound`` (the paper's p printed as 0) a model scatter below the bound is no
    misfit (0). A model scatter of 0 (every trial alike) is an infinite misfit below.

    Raises
    ------
    ValueError
        If ``paper_sd_percent`` is not positive and finite, or ``sd_percent`` is negative or
        not finite.
    """
    if not math.isfinite(paper_sd_percent) or paper_sd_percent <= 0.0:
        raise ValueError(f"paper_sd_percent must be > 0 and finite; got {paper_sd_percent!r}")
    if not math.isfinite(sd_percent) or sd_percent < 0.0:
        raise ValueError(f"sd_percent must be >= 0 and finite; got {sd_percent!r}")
    if sd_percent == 0.0:
        return -math.inf
    ratio = math.log(sd_percent / paper_sd_percent) / math.log(SCATTER_FACTOR)
    return max(ratio, 0.0) if upper_bound else ratio


def mean_agrees(change_percent: float, paper_percent: float) -> bool:
    """The mean rule of the module notes."""
    return abs(mean_misfit(change_percent, paper_percent)) <= 1.0


def scatter_agrees(sd_percent: float, paper_sd_percent: float, upper_bound: bool) -> bool:
    """The scatter rule of the module notes."""
    return abs(scatter_misfit(sd_percent, paper_sd_percent, upper_bound)) <= 1.0


def paper_scatter(speed_kmh: float, load: str, controller: str) -> Any:
    """The paper's implied scatter (:class:`~loader_model.experiments.scatter.ImpliedScatter`)
    of one cell, reading that cell of Table 6 only."""
    from loader_model.experiments import table6
    from loader_model.experiments.scatter import implied_scatter

    if speed_kmh not in table6.SPEED_LABELS or load not in table6.LOAD_LABELS:
        raise ValueError(
            f"cell {speed_kmh!r}/{load!r}: allowed speeds {list(table6.SPEED_LABELS)}, "
            f"loads {list(table6.LOAD_LABELS)}"
        )
    row = table6.PAPER_TABLE_6[(table6.SPEED_LABELS[speed_kmh], table6.LOAD_LABELS[load])]
    if controller not in row:
        raise ValueError(f"controller {controller!r}: allowed: {sorted(row)}")
    change, p_value = row[controller]
    return implied_scatter(float(change), float(p_value))
