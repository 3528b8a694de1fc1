"""Calibrate the estimated parameters to one speed's cells of Table 6, the other speed held out.

The parameters whose source is an estimate and that the ride depends on (the accumulator's
precharge, gas volume and orifice, the tyres' vertical damping, the seat cushion and the seated
mass) are listed with their plausible ranges and sources in ``data/table6_estimates.toml``, a
robustness study (:mod:`loader_model.robustness`) whose samples are the uncertainty study of the
report. The calibration looks for ONE parameter set for all cells (nothing per condition) inside
those ranges that brings the model's change of a_total against the baseline (Table 6, section
5.3) closest to the paper's at the fitted speed:

.. math::

    J(\\theta) = \\sum_{\\text{cells at the fitted speed}}
        \\left(\\frac{\\Delta_{model}(\\theta) - \\Delta_{paper}}{10\\ \\text{pp}}\\right)^2

over the six cells (two loads × passive, virtual accumulator, skyhook). Each evaluation runs the
fitted speed's trials (:func:`~loader_model.experiments.trials.trial_specs`, the report's seeds:
common random numbers, so J is a deterministic function of θ) on the model as built
(:data:`~loader_model.experiments.variant.AS_BUILT`) with θ applied. The search runs in the unit
cube (log scale for the log-uniform ranges): a scrambled Sobol design of the whole box first (the
cost is not smooth: tyre lift-offs come and go), then Nelder-Mead with bounds from the best
point. A θ the parameter files refuse, or a trial stopped by the validity checks, costs
:data:`REFUSED_COST`.

The held-out cells are never read: the targets are taken by :func:`paper_targets` for the fitted
speed only, and the trials run at that speed only (a test replaces the held-out cells of the
paper's table by garbage and gets the same result).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from loader_model.experiments.variant import AS_BUILT, ModelVariant

__all__ = [
    "CALIBRATED_FILES",
    "ESTIMATES_FILE",
    "REFUSED_COST",
    "CalibrationResult",
    "calibrate_table6",
    "calibrated_loader",
    "calibrated_values",
    "estimated_parameters",
    "mean_changes",
    "paper_targets",
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
#: Percentage points that count as one unit of misfit.
MISFIT_SCALE_PP = 10.0


def estimated_parameters() -> list[tuple[str, Any]]:
    """(path, :class:`~loader_model.robustness.distributions.Distribution`) of each estimated
    parameter, from :data:`ESTIMATES_FILE`."""
    from loader_model.robustness.study import parse_study

    text = resources.files("loader_model").joinpath("data", ESTIMATES_FILE).read_text("utf-8")
    return list(parse_study(text, ESTIMATES_FILE).parameters)


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


def table6_cost(
    changes: dict[tuple[str, str], float], targets: dict[tuple[str, str], float]
) -> float:
    """J of the module notes: the misfit of the model's ``changes`` against ``targets``."""
    missing = sorted(set(targets) - set(changes))
    if missing:
        raise ValueError(f"no model cells for {missing}")
    return float(
        sum(((changes[key] - value) / MISFIT_SCALE_PP) ** 2 for key, value in targets.items())
    )


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
    """

    fit_speed_kmh: float
    values: dict[str, float]
    start: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    at_bounds: tuple[str, ...]
    cost: float
    start_cost: float
    evaluations: int


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
    trials: int = 2,
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
    trials, seed : int
        Trials per cell and the seed of their draws (as ``loader-model reproduce``).
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
    if isinstance(evaluations, bool) or not isinstance(evaluations, int):
        raise ValueError(f"evaluations must be an integer; got {evaluations!r}")
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
        return table6_cost(mean_changes(run_trials(specs, jobs=jobs, progress=False)), targets)

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
    )


def calibrated_loader(result: CalibrationResult, date: str) -> Any:
    """The shipped loader with the calibrated values, each with a source that says to which cells
    and on what date it was calibrated, and what it was."""
    from loader_model import parameters

    loader = parameters.default_loader()
    held_out = 18.0 if result.fit_speed_kmh == 9.0 else 9.0
    for path, value in result.values.items():
        low, high = result.bounds[path]
        bound = " (at a bound)" if path in result.at_bounds else ""
        source = (
            f"calibrated to Table 6's six {result.fit_speed_kmh:g} km/h cells on {date} "
            f"(make calibrate-table6; the {held_out:g} km/h cells held out){bound}; shipped "
            f"estimate {result.start[path]:.6g}, plausible range [{low:.6g}, {high:.6g}] "
            f"({ESTIMATES_FILE})"
        )
        loader = parameters.replace(loader, {path: value}, source=source)
    return loader


def calibrated_values(path: Any) -> dict[str, float]:
    """The estimated parameters' values in a calibrated loader file (:func:`calibrated_loader`)."""
    from functools import reduce

    from loader_model import parameters
    from loader_model.parameters.toml_format import to_raw

    raw = to_raw(parameters.load_loader(path))
    return {
        p: float(reduce(lambda node, key: node[key], p.split("."), raw)["value"])
        for p, _ in estimated_parameters()
    }


def shipped_calibration(fit_speed_kmh: float) -> dict[str, float]:
    """The values of the shipped calibrated loader file of ``fit_speed_kmh`` (package data)."""
    name = CALIBRATED_FILES[float(fit_speed_kmh)]
    with resources.as_file(resources.files("loader_model").joinpath("data", name)) as path:
        return calibrated_values(path)


def write_summary(path: Any, result: CalibrationResult, date: str, command: str) -> None:
    """The fit's summary as JSON (atomically), for the report and the currency test."""
    import dataclasses
    import json

    from loader_model.io.export import write_atomically

    content = dataclasses.asdict(result) | {"date": date, "command": command}
    content["bounds"] = {k: list(v) for k, v in result.bounds.items()}
    text = json.dumps(content, indent=1, sort_keys=True)
    write_atomically(
        path,
        lambda temporary: temporary.write_text(text + "\n", encoding="utf-8"),
        (".json",),
        "calibration summary",
    )
