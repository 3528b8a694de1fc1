"""Calibrate the estimated parameters to one speed's cells of Table 6, the other speed held out.

The parameters whose source is an estimate and that the ride depends on (the accumulator's
precharge, gas volume and orifice, the tyres' vertical damping, the seat cushion and the seated
mass) are listed with their plausible ranges and sources in ``data/table6_estimates.toml``, a
robustness study (:mod:`loader_model.robustness`) whose samples are the uncertainty study of the
report. The calibration looks for ONE parameter set for all cells (nothing per condition) inside
those ranges that brings the model's means AND its trial scatter (Table 6, section 5.3) closest
to the paper's at the fitted speed:

.. math::

    J(\\theta) = \\sum_{c} \\left(\\frac{\\Delta_c(\\theta) - \\Delta_c^{paper}}{10\\ \\text{pp}}
        \\right)^2 + w \\sum_{c} \\left(\\frac{\\log(s_c(\\theta) / s_c^{paper})}{\\log 2}
        \\right)^2

over the six cells c of the fitted speed (two loads × passive, virtual accumulator, skyhook):
Δ_c the change of the mean a_total against the baseline over N trials per group, s_c the
pooled trial standard deviation in percent of the baseline mean, s_c^paper the scatter the
paper's Δ and p imply (:mod:`~loader_model.experiments.calibration_cost`, which states the
assumptions and the treatment of p = 0.0000 and of stopped trials). Each evaluation runs the
fitted speed's N trials per group (:func:`~loader_model.experiments.trials.trial_specs`, the
report's seeds) on the model as built (:data:`~loader_model.experiments.variant.AS_BUILT`) with
θ applied. The trials are common random numbers, the same speeds, boards and sensor noise for
every θ, so J is a deterministic function of θ; averaging over N trials smooths the jumps that
a tyre lift-off coming or going makes in a single trial. The search runs in the unit cube (log
scale for the log-uniform ranges): a scrambled Sobol design of the whole box first, then
Nelder-Mead with bounds from the best point. A θ the parameter files refuse, or one whose trials
the validity checks stop too often, costs :data:`REFUSED_COST`.

The held-out cells are never read: the targets are taken for the fitted speed only
(:func:`paper_targets`, :func:`scatter_targets`), and the trials run at that speed only (a test
replaces the held-out cells of the paper's table by garbage and gets the same result). After
the fit, :func:`check_calibration` runs both speeds with more trials (the fidelity budget's
step, :func:`~loader_model.experiments.fidelity.run_budget`) and counts the cells whose mean
and scatter agree with the paper's (:mod:`~loader_model.experiments.agreement`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from loader_model.experiments.calibration_cost import (
    SCATTER_WEIGHT,
    cell_statistics,
    mean_changes,
    paper_targets,
    scatter_targets,
    table6_cost,
)
from loader_model.experiments.calibration_files import (
    calibrated_loader,
    calibrated_values,
    shipped_calibration,
    write_summary,
)
from loader_model.experiments.variant import AS_BUILT, ModelVariant

__all__ = [
    "CALIBRATED_FILES",
    "ESTIMATES_FILE",
    "REFUSED_COST",
    "CalibrationResult",
    "calibrate_table6",
    "calibrated_loader",
    "calibrated_values",
    "cell_statistics",
    "check_calibration",
    "estimated_parameters",
    "mean_changes",
    "paper_targets",
    "scatter_targets",
    "shipped_calibration",
    "shipped_value",
    "table6_cost",
    "write_summary",
]

#: The estimated parameters' study file (package data).
ESTIMATES_FILE = "table6_estimates.toml"
#: The shipped calibrated loader files per fitted speed (package data, ``make calibrate-table6``).
CALIBRATED_FILES = {
    9.0: "loader_calibrated_table6_9kmh.toml",
    18.0: "loader_calibrated_table6_18kmh.toml",
}
#: Cost of a parameter set the files refuse or a drive the validity checks stop.
REFUSED_COST = 1e6


def estimated_parameters() -> list[tuple[str, Any]]:
    """(path, :class:`~loader_model.robustness.distributions.Distribution`) of each estimated
    parameter, from :data:`ESTIMATES_FILE`."""
    from loader_model.robustness.study import parse_study

    text = resources.files("loader_model").joinpath("data", ESTIMATES_FILE).read_text("utf-8")
    return list(parse_study(text, ESTIMATES_FILE).parameters)


@dataclass(frozen=True)
class CalibrationResult:
    """Outcome of :func:`calibrate_table6`.

    Attributes
    ----------
    fit_speed_kmh : float
        The speed whose cells were fitted.
    values, start : dict
        Path -> calibrated / shipped value (SI).
    bounds : dict
        Path -> (low, high) of the plausible range.
    at_bounds : tuple of str
        Paths within 1 % of the range (in the search's scale) of a bound.
    cost, start_cost : float
        J at the calibrated and the shipped values.
    evaluations : int
        Cost evaluations (each one run of the fitted speed's trials).
    trials : int
        Trials per group of each evaluation (N).
    scatter_weight : float
        Weight w of the scatter terms.
    """

    fit_speed_kmh: float
    values: dict[str, float]
    start: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    at_bounds: tuple[str, ...]
    cost: float
    start_cost: float
    evaluations: int
    trials: int = 0
    scatter_weight: float = SCATTER_WEIGHT


def _grid(u: np.ndarray) -> tuple[float, ...]:
    """The search point as evaluated: clipped to the box and rounded to 1e-12."""
    return tuple(float(x) for x in np.round(np.clip(u, 0.0, 1.0), 12))


def _to_value(distribution: Any, u: float) -> float:
    low, high = distribution.low, distribution.high
    if distribution.kind == "loguniform":
        return float(math.exp(math.log(low) + (math.log(high) - math.log(low)) * u))
    return float(low + (high - low) * u)


def _to_unit(distribution: Any, value: float, path: str) -> float:
    low, high = distribution.low, distribution.high
    if not low <= value <= high:
        raise ValueError(f"{path}: the shipped value {value:g} lies outside [{low:g}, {high:g}]")
    if distribution.kind == "loguniform":
        return (math.log(value) - math.log(low)) / (math.log(high) - math.log(low))
    return (value - low) / (high - low)


def shipped_value(path: str) -> float:
    """The shipped parameter files' value at a dotted ``path`` (``load.*``: the empty bucket)."""
    from functools import reduce

    from loader_model import parameters
    from loader_model.parameters.toml_format import to_raw

    if path.startswith("load."):
        raw, keys = to_raw(parameters.bucket_load("empty")), path.removeprefix("load.")
    else:
        raw, keys = to_raw(parameters.default_loader()), path
    return float(reduce(lambda node, key: node[key], keys.split("."), raw)["value"])


def calibrate_table6(
    fit_speed_kmh: float = 9.0,
    *,
    evaluations: int = 128,
    design_points: int = 32,
    trials: int = 8,
    scatter_weight: float = SCATTER_WEIGHT,
    seed: int = 0,
    jobs: int = 2,
    duration_s: float | None = None,
    progress: bool = True,
    variant: ModelVariant = AS_BUILT,
    evaluate: Callable[[ModelVariant], float] | None = None,
) -> CalibrationResult:
    """Fit the estimated parameters to the cells at ``fit_speed_kmh`` (module notes).

    Parameters
    ----------
    fit_speed_kmh : float
        9 or 18: the speed whose six cells are fitted; the other is held out.
    evaluations : int
        Budget of cost evaluations in all (design points included), >= design_points + 2.
    design_points : int
        Points of the Sobol design before Nelder-Mead (a power of 2).
    trials : int
        Trials per group of each evaluation (N >= 2; the same trials for every θ).
    scatter_weight : float
        Weight w >= 0 of the scatter terms of J (0: the means alone).
    seed : int
        Seed of the trials' draws (as ``loader-model reproduce``).
    jobs : int
        Processes for the trials.
    duration_s : float, optional
        Simulated time per trial (default: the whole course; shorter for tests).
    progress : bool
        Show a progress bar.
    variant : ModelVariant
        The model the parameters are applied to.
    evaluate : callable, optional
        variant -> J (default: run the trials; for tests).

    Returns
    -------
    CalibrationResult
    """
    from scipy.optimize import minimize
    from scipy.stats import qmc
    from tqdm import tqdm

    targets = paper_targets(fit_speed_kmh)
    paper_scatters = scatter_targets(fit_speed_kmh)
    if isinstance(evaluations, bool) or not isinstance(evaluations, int):
        raise ValueError(f"evaluations must be an integer; got {evaluations!r}")
    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 2:
        raise ValueError(f"trials {trials!r}: allowed: an integer >= 2 (a scatter needs two)")
    if not math.isfinite(scatter_weight) or scatter_weight < 0.0:
        raise ValueError(f"scatter_weight {scatter_weight!r}: allowed: a finite number >= 0")
    if design_points < 1 or design_points & (design_points - 1):
        raise ValueError(f"design_points {design_points}: allowed: a power of 2 (Sobol balance)")
    if evaluations < design_points + 2:
        raise ValueError(
            f"evaluations {evaluations}: allowed: at least design_points + 2 = {design_points + 2}"
        )
    estimates = estimated_parameters()
    paths = [path for path, _ in estimates]
    start = {path: shipped_value(path) for path in paths}
    u0 = np.array([_to_unit(d, start[p], p) for p, d in estimates])
    bar = tqdm(
        total=evaluations,
        desc=f"Table 6 calibration ({fit_speed_kmh:g} km/h)",
        unit="eval",
        disable=not progress,
    )
    memo: dict[tuple[float, ...], float] = {}

    def values_at(u: np.ndarray) -> dict[str, float]:
        clipped = np.clip(u, 0.0, 1.0)  # Nelder-Mead's bounds keep u inside; guard rounding
        return {p: _to_value(d, float(x)) for (p, d), x in zip(estimates, clipped, strict=True)}

    def run(variant_u: ModelVariant) -> float:
        from loader_model.experiments.table6 import run_trials
        from loader_model.experiments.trials import trial_specs

        specs = trial_specs(
            seed, trials, speeds_kmh=(fit_speed_kmh,), duration_s=duration_s, variant=variant_u
        )
        outcomes = run_trials(specs, jobs=jobs, progress=False, keep_failures=True)
        changes, scatters = cell_statistics(outcomes)
        return table6_cost(changes, targets, scatters, paper_scatters, scatter_weight)

    def cost(u: np.ndarray) -> float:
        key = _grid(u)
        if key not in memo:
            try:
                candidate = variant.with_values(values_at(np.array(key)))
                memo[key] = float((evaluate or run)(candidate))
            except ValueError:  # refused by the parameter files or stopped by validity
                memo[key] = REFUSED_COST
            bar.update(1)
        return memo[key]

    try:
        # the shipped values must run: a refusal here is an error, not a cost
        start_cost = float((evaluate or run)(variant.with_values(values_at(u0))))
        memo[_grid(u0)] = start_cost
        bar.update(1)
        sobol = qmc.Sobol(len(paths), scramble=True, rng=np.random.default_rng(seed))
        design = sobol.random(design_points)
        best_u, best = u0, start_cost
        for u in design:
            value = cost(u)
            if value < best:
                best_u, best = u, value
        remaining = evaluations - len(memo)
        result = minimize(
            cost,
            best_u,
            method="Nelder-Mead",
            bounds=[(0.0, 1.0)] * len(paths),
            options={"maxfev": remaining, "xatol": 1e-3, "fatol": 1e-3, "initial_simplex": None},
        )
        final_u = np.clip(result.x, 0.0, 1.0) if result.fun <= best else best_u
        final = min(float(result.fun), best)
    finally:
        bar.close()
    # the values J was evaluated at: a failed integration step can turn on the last digits
    values = values_at(np.array(_grid(final_u)))
    at_bounds = tuple(p for p, x in zip(paths, final_u, strict=True) if x < 0.01 or x > 0.99)
    return CalibrationResult(
        fit_speed_kmh=float(fit_speed_kmh),
        values=values,
        start=start,
        bounds={p: (d.low, d.high) for p, d in estimates},
        at_bounds=at_bounds,
        cost=final,
        start_cost=start_cost,
        evaluations=len(memo),
        trials=trials,
        scatter_weight=float(scatter_weight),
    )


def check_calibration(
    values: dict[str, float],
    fit_speed_kmh: float,
    *,
    trials: int = 80,
    seed: int = 0,
    jobs: int = 2,
    progress: bool = False,
) -> dict[str, Any]:
    """Both speeds' cells on the calibrated ``values``, with ``trials`` trials per group.

    The fidelity budget's step "calibrated to ``fit_speed_kmh``" (:func:`~loader_model.
    experiments.fidelity.run_budget`, the same trials and seed): per cell the mean change and its
    standard error, the trial scatter beside the paper's implied one, and the counts of cells
    within 10 pp, with the scatter within a factor 2, and both, over all twelve cells and the six
    held-out ones (:func:`~loader_model.experiments.fidelity.scatter_summary`).
    """
    from loader_model.experiments.fidelity import BudgetStep, run_budget

    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 2:
        raise ValueError(f"trials {trials!r}: allowed: an integer >= 2")
    held_out = 18.0 if float(fit_speed_kmh) == 9.0 else 9.0
    label = f"+ calibrated to {fit_speed_kmh:g} km/h"
    step = BudgetStep(label, AS_BUILT.with_values(values, label), held_out)
    summary = run_budget([step], trials=trials, seed=seed, jobs=jobs, progress=progress)[0]
    return summary | {"trials": trials, "seed": seed}
