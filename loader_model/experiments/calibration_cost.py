"""The cost of the Table 6 calibration: the fitted speed's means and trial scatter together.

.. math::

    J(\\theta) = \\sum_{c} \\left(\\frac{\\Delta_c(\\theta) - \\Delta_c^{paper}}{10\\ \\text{pp}}
        \\right)^2 + w \\sum_{c} \\left(\\frac{\\log(s_c(\\theta) / s_c^{paper})}{\\log 2}
        \\right)^2

over the six cells c of the fitted speed (two loads × passive, virtual accumulator, skyhook).
Δ_c is the change of the mean a_total against the baseline's mean over N trials per group
(Table 6's change); s_c the pooled trial standard deviation of the controller's and the
baseline's trials in percent of the baseline mean, as the scatter study computes it
(:func:`~loader_model.experiments.scatter.model_scatter`); s_c^paper the scatter that the
paper's Δ and p imply (:func:`~loader_model.experiments.scatter.implied_scatter`: Welch,
n = 4 per group, equal variances, normal). Where the paper prints p = 0.0000 its scatter is an
upper bound and only a model scatter above it is a misfit
(:func:`~loader_model.experiments.agreement.scatter_misfit`). Each unit of a term is the edge
of the agreement rule of :mod:`~loader_model.experiments.agreement`: 10 pp of mean, a factor 2
of scatter; w weighs the scatter against the means (w = 0: the means alone).

Trials the simulator stops (a run outside the model's validity) are left out of their group,
as in the fidelity budget and the scatter study; a parameter set that loses more than
:data:`MAX_STOPPED_SHARE` of its trials, or keeps fewer than two in a group, is refused.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from loader_model.experiments.agreement import (
    WITHIN_PP,
    mean_misfit,
    paper_scatter,
    scatter_misfit,
)

__all__ = [
    "MAX_STOPPED_SHARE",
    "MISFIT_SCALE_PP",
    "SCATTER_WEIGHT",
    "cell_statistics",
    "mean_changes",
    "paper_targets",
    "scatter_targets",
    "table6_cost",
]

#: Percentage points that count as one unit of misfit of a mean.
MISFIT_SCALE_PP = WITHIN_PP
#: Default weight w of the scatter terms.
SCATTER_WEIGHT = 1.0
#: Largest share of a parameter set's trials the simulator may stop before the set is refused.
MAX_STOPPED_SHARE = 0.125


def paper_targets(speed_kmh: float) -> dict[tuple[str, str], float]:
    """The paper's change of a_total [%] per (load, controller) at ``speed_kmh`` only."""
    from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS

    if speed_kmh not in SPEED_LABELS:
        raise ValueError(f"speed_kmh {speed_kmh!r}: allowed: {list(SPEED_LABELS)}")
    targets = {}
    for load, label in LOAD_LABELS.items():
        for controller, (change, _) in PAPER_TABLE_6[(SPEED_LABELS[speed_kmh], label)].items():
            targets[(load, controller)] = float(change)
    return targets


def scatter_targets(speed_kmh: float) -> dict[tuple[str, str], Any]:
    """The paper's implied scatter (:class:`~loader_model.experiments.scatter.ImpliedScatter`)
    per (load, controller) at ``speed_kmh`` only."""
    return {
        (load, controller): paper_scatter(float(speed_kmh), load, controller)
        for load, controller in paper_targets(speed_kmh)
    }


def mean_changes(outcomes: list[Any]) -> dict[tuple[str, str], float]:
    """Change of the mean a_total against the baseline's mean [%] per (load, controller), from
    trial outcomes of one speed (Table 6's "change"; no interval, so one trial per cell will do)."""
    totals: dict[tuple[str, str], list[float]] = {}
    for outcome in outcomes:
        key = (outcome.spec.load, outcome.spec.controller)
        totals.setdefault(key, []).append(outcome.a_total_m_s2)
    changes = {}
    for (load, controller), values in totals.items():
        if controller != "baseline":
            base = float(np.mean(totals[(load, "baseline")]))
            changes[(load, controller)] = 100.0 * (float(np.mean(values)) / base - 1.0)
    return changes


def cell_statistics(
    outcomes: list[Any],
) -> tuple[dict[tuple[str, str], float], dict[tuple[str, str], float]]:
    """Mean change [%] and pooled trial scatter [% of the baseline mean] per (load, controller)
    from trial outcomes of one speed (module notes; stopped trials, NaN a_total, left out).

    Raises
    ------
    ValueError
        If more than :data:`MAX_STOPPED_SHARE` of the trials were stopped, or a group keeps
        fewer than two trials.
    """
    from loader_model.experiments.scatter import model_scatter

    totals: dict[tuple[str, str], list[float]] = {}
    for outcome in outcomes:
        totals.setdefault((outcome.spec.load, outcome.spec.controller), []).append(
            outcome.a_total_m_s2
        )
    stopped = sum(not np.isfinite(o.a_total_m_s2) for o in outcomes)
    if stopped > MAX_STOPPED_SHARE * len(outcomes):
        raise ValueError(
            f"{stopped} of {len(outcomes)} trials stopped by the validity checks; allowed: at "
            f"most {MAX_STOPPED_SHARE:.1%}"
        )
    finite = {key: [v for v in values if np.isfinite(v)] for key, values in totals.items()}
    changes, scatters = {}, {}
    for (load, controller), values in finite.items():
        if controller == "baseline":
            continue
        scatter = model_scatter(finite[(load, "baseline")], values)  # raises below two trials
        changes[(load, controller)] = scatter.change_percent
        scatters[(load, controller)] = scatter.sd_percent
    return changes, scatters


def table6_cost(
    changes: dict[tuple[str, str], float],
    targets: dict[tuple[str, str], float],
    scatters: dict[tuple[str, str], float] | None = None,
    paper_scatters: dict[tuple[str, str], Any] | None = None,
    weight: float = SCATTER_WEIGHT,
) -> float:
    """J of the module notes: the misfit of the model's ``changes`` (and ``scatters``, if given
    with the paper's ``paper_scatters``) against the paper's cells ``targets``.

    Parameters
    ----------
    changes, scatters : dict
        (load, controller) -> the model's mean change [%] and pooled scatter [%].
    targets : dict
        (load, controller) -> the paper's change [%]; the cells that count.
    paper_scatters : dict, optional
        (load, controller) -> :class:`~loader_model.experiments.scatter.ImpliedScatter`.
    weight : float
        w >= 0 of the scatter terms (ignored without ``scatters``).

    Returns
    -------
    float
    """
    missing = sorted(set(targets) - set(changes))
    if missing:
        raise ValueError(f"no model cells for {missing}")
    cost = sum(mean_misfit(changes[key], value) ** 2 for key, value in targets.items())
    if scatters is None:
        return float(cost)
    if paper_scatters is None:
        raise ValueError("scatters need paper_scatters (the paper's implied scatter per cell)")
    if not np.isfinite(weight) or weight < 0.0:
        raise ValueError(f"weight must be >= 0 and finite; got {weight!r}")
    for key in targets:
        paper = paper_scatters[key]
        misfit = scatter_misfit(scatters[key], paper.sd_percent, paper.upper_bound)
        cost += weight * misfit**2
    return float(cost)
