"""The report's fidelity sections, rendered from the shipped budget and this run's trials.

- :func:`budget_section`: the fidelity budget of :mod:`~loader_model.experiments.fidelity` (one
  modelling step at a time), the calibrated values and the uncertainty study, from the JSON that
  ``make fidelity`` ships (``data/fidelity_budget.json``);
- :func:`comfort_rows`: this run's absolute a_total per condition and controller beside
  ISO 2631-1 Annex C's likely reactions (:func:`~loader_model.iso2631.comfort.comfort_reaction`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from importlib import resources
from typing import Any

import numpy as np

from loader_model.experiments.report import markdown_table
from loader_model.experiments.tables import Rows

__all__ = [
    "BUDGET_FILE",
    "action_minutes",
    "budget_section",
    "comfort_rows",
    "comfort_summary",
    "largest_standard_error",
    "shipped_budget",
    "trial_count",
]

#: The shipped budget (package data).
BUDGET_FILE = "fidelity_budget.json"
_ROW_CONTROLLERS = ("passive", "virtual-accumulator", "skyhook")


def shipped_budget() -> dict[str, Any] | None:
    """The shipped budget, or None if it was never made."""
    from loader_model.experiments.fidelity import read_budget

    entry = resources.files("loader_model").joinpath("data", BUDGET_FILE)
    if not entry.is_file():
        return None
    with resources.as_file(entry) as path:
        return read_budget(path)


#: z-quantile of the 95 % interval: its half-width over this bounds the standard error from above
#: (the Welch interval uses Student's t, which is larger for any degrees of freedom).
_Z95 = 1.959964


def trial_count(budget: dict[str, Any]) -> int:
    """Trials per group of the budget: its ``trials`` entry, else the ``--trials`` of the
    command that made it, else the command's default (4, the paper's)."""
    if "trials" in budget:
        return int(budget["trials"])
    match = re.search(r"--trials[ =](\d+)", str(budget.get("command", "")))
    return int(match.group(1)) if match else 4


def largest_standard_error(steps: Sequence[dict[str, Any]]) -> float:
    """The largest standard error of a cell's mean change over every step and cell, in pp
    (bounded from above by the 95 % interval's half-width over 1.96)."""
    halves = [
        (cell["high"] - cell["low"]) / 2.0
        for step in steps
        for cell in step["cells"].values()
        if np.isfinite(cell["high"] - cell["low"])
    ]
    return max(halves, default=float("nan")) / _Z95


def _interval(cell: dict[str, float]) -> str:
    return f"{cell['change']:+.1f} [{cell['low']:+.1f}, {cell['high']:+.1f}]"


def _step_rows(steps: Sequence[dict[str, Any]]) -> Rows:
    rows: Rows = [
        [
            "step",
            "cells within 10 pp",
            "held-out cells within 10 pp",
            *(f"9 km/h empty {c} Δ [%] [95 % CI]" for c in _ROW_CONTROLLERS),
            "significant findings in sign (and p < 0.05)",
            "baseline a_total 9 km/h empty / full, 18 km/h empty / full [m/s²]",
            "trials stopped by the validity checks",
        ]
    ]
    for step in steps:
        held = (
            f"{step['held_out_within']} of {step['held_out_count']} ({step['held_out_kmh']:g} km/h)"
            if step.get("held_out_count")
            else "-"
        )
        base = step["baseline_a_total"]
        levels = " / ".join(
            f"{base.get(k, float('nan')):.2f}" for k in ("9/empty", "9/full", "18/empty", "18/full")
        )
        rows.append(
            [
                step["label"],
                f"{step['within']} of {step['count']}",
                held,
                *(_interval(step["cells"][f"9/empty/{c}"]) for c in _ROW_CONTROLLERS),
                f"{step['significant_in_sign']} of {step['significant_count']} "
                f"({step['significant_in_sign_and_p']})",
                levels,
                str(len(step.get("failed_trials", []))),
            ]
        )
    return rows


def _stopped(steps: Sequence[dict[str, Any]]) -> str:
    """The trials the simulator stopped, per step (left out of the cells)."""
    lines = [
        f"- {step['label']}: {failure}"
        for step in steps
        for failure in step.get("failed_trials", [])
    ]
    if not lines:
        return "No trial left the model's range of validity.\n"
    return (
        "Trials stopped by the validity checks, left out of their cells:\n\n"
        + "\n".join(lines)
        + "\n"
    )


def _value_rows(steps: Sequence[dict[str, Any]]) -> Rows:
    from loader_model.experiments.calibration_table6 import estimated_parameters, shipped_value

    fits = [s for s in steps if s.get("held_out_kmh") is not None]
    rows: Rows = [
        ["parameter", "shipped (estimate)", *(s["label"].removeprefix("+ ") for s in fits), "range"]
    ]
    for path, distribution in estimated_parameters():
        low, high = distribution.low, distribution.high
        cells = []
        for step in fits:
            value = step["values"].get(path, float("nan"))
            span = np.log(high / low) if distribution.kind == "loguniform" else high - low
            where = np.log(value / low) if distribution.kind == "loguniform" else value - low
            flag = " (at a bound)" if not 0.01 <= where / span <= 0.99 else ""
            cells.append(f"{value:.4g}{flag}")
        rows.append([path, f"{shipped_value(path):.4g}", *cells, f"[{low:.4g}, {high:.4g}]"])
    return rows


def _uncertainty_rows(uncertainty: dict[str, Any]) -> Rows:
    rows: Rows = [
        [
            "cell (speed/load/controller)",
            "paper Δ [%]",
            "share with the paper's sign",
            "runs (failed)",
        ]
    ]
    for key, cell in uncertainty["cells"].items():
        share = cell["share"]
        shown = "-" if not np.isfinite(share) else f"{100 * share:.0f} %"
        rows.append([key, f"{cell['paper']:+.1f}", shown, f"{cell['count']} ({cell['failed']})"])
    return rows


def _updates(budget: dict[str, Any]) -> str:
    """Where parts of the budget were recomputed since (``loader-model fidelity --update``)."""
    return "".join(
        f"; {', '.join(u['recomputed'])} recomputed by `{u['command']}` on {u['date']} in "
        f"{u['wall_time_s']:.0f} s"
        for u in budget.get("updates", [])
    )


def budget_section(budget: dict[str, Any] | None) -> tuple[str, dict[str, Rows]]:
    """Markdown of the budget and its tables (for the CSV files); a note if none was shipped.

    With the calibrated steps' scatter and the plausible machines' mean-and-scatter study
    (:mod:`~loader_model.experiments.agreement_report`) where the budget has them."""
    from loader_model.experiments.agreement_report import agreement_text

    if budget is None:
        return (
            "## Fidelity budget\n\nNo budget shipped: run `make fidelity` (after "
            "`make calibrate-table6`).\n",
            {},
        )
    steps = budget["steps"]
    tables = {
        "fidelity_budget": _step_rows(steps),
        "calibrated_values": _value_rows(steps),
        "uncertainty": _uncertainty_rows(budget["uncertainty"]),
    }
    text = "\n".join(
        [
            "## Fidelity budget: one modelling step at a time\n",
            f"Shipped result `loader_model/data/{BUDGET_FILE}`, made by `{budget['command']}` "
            f"on {budget['date']} in {budget['wall_time_s']:.0f} s (`make fidelity`; a slow test "
            f"checks that it is current){_updates(budget)}. Each step runs the whole Table 6 "
            "matrix, "
            f"{trial_count(budget)} trials per group with the report's seed, so that every "
            f"cell's mean change has a standard error of at most "
            f"{largest_standard_error(steps):.1f} pp (its 95 % interval's half-width over 1.96); "
            "the Table 6 above runs the paper's four trials per group and shows what four "
            "trials give. The steps add up: Table 5's flow as a cylinder leak, the seat on "
            "the rigid chassis, rigid-wheel tyres and Table 3 as printed (as it was); then the "
            "load-holding valves closed while the pump is idle (errata 11); the seat pad under "
            "an occupant (errata 13); the tandem-cam tyres (errata 13); k_φ = +0.22 (errata 12): "
            "the model as built, which the Table 6 above runs. The calibrated steps fit the "
            "estimated parameters (`data/table6_estimates.toml`, `make calibrate-table6`) to one "
            "speed's six cells and hold the other speed's out. The paper's significant findings "
            "are its nine cells with p < 0.05.\n",
            markdown_table(tables["fidelity_budget"]) + "\n",
            _stopped(steps),
            "Calibrated values (one set for all cells; Sobol design then Nelder-Mead inside the "
            "plausible ranges; the cost weighs each fitted cell's mean change in units of 10 pp "
            "and its trial scatter in factors of 2 against the paper's, over the same trials "
            "for every parameter set; `make calibrate-table6` records the trials per group):\n",
            markdown_table(tables["calibrated_values"]) + "\n",
            f"Uncertainty: {budget['uncertainty']['samples']} machines drawn over the estimated "
            "parameters' ranges (Latin hypercube, `loader-model robustness "
            "loader_model/data/table6_estimates.toml`), each on one speed and load with every "
            "controller against its own baseline; per cell the share whose change has the "
            "paper's sign:\n",
            markdown_table(tables["uncertainty"]) + "\n",
        ]
    )
    scatter_text, scatter_tables = agreement_text(budget)
    tables.update(scatter_tables)
    if scatter_text:
        text += "\n" + scatter_text
    return text, tables


def action_minutes(a_wx_m_s2: float, a_wz_m_s2: float) -> float:
    """Minutes per day at which the Directive 2002/44/EC action value A(8) = 0.5 m/s² is reached.

    The health weighting of ISO 2631-1 7.2.3 (seated): the larger of 1.4 a_wx and a_wz, and
    A(8) = a √(T / 8 h) (:func:`~loader_model.iso2631.exposure.daily_exposure_a8`), solved for
    T. The planar model has no lateral axis. Infinite for no vibration.
    """
    from loader_model.iso2631.exposure import A8_ACTION_VALUE_M_S2, HEALTH_K_FACTORS

    dominant = max(HEALTH_K_FACTORS["x"] * a_wx_m_s2, HEALTH_K_FACTORS["z"] * a_wz_m_s2)
    if not dominant > 0.0:
        return float("inf")
    return 480.0 * (A8_ACTION_VALUE_M_S2 / dominant) ** 2


def comfort_rows(outcomes: Sequence[Any], controllers: Sequence[str]) -> Rows:
    """Mean a_total [m/s²] per condition and controller, and the minutes per day of such driving
    before the Directive 2002/44/EC action value (:func:`action_minutes` of the mean a_wx, a_wz).

    ISO 2631-1 Annex C's reaction to each mean is in :func:`comfort_summary`: on the paper's
    course every mean lies in its top band, so the label alone does not tell the cells apart.
    """
    totals: dict[tuple[float, str, str], list[Any]] = {}
    for o in outcomes:
        key = (o.spec.speed_kmh, o.spec.load, o.spec.controller)
        totals.setdefault(key, []).append(o)
    rows: Rows = [
        [
            "speed",
            "load",
            *(f"{c} [m/s²] (min)" for c in controllers),
        ]
    ]
    for speed, load in sorted({(s, ld) for s, ld, _ in totals}):
        row = [f"{speed:g} km/h", load]
        for controller in controllers:
            found = totals.get((speed, load, controller))
            if found is None:
                row.append("-")
                continue
            mean = float(np.mean([o.a_total_m_s2 for o in found]))
            a_wx, a_wz = (float(np.mean([o.weighted_rms[a] for o in found])) for a in "xz")
            row.append(f"{mean:.2f} ({action_minutes(a_wx, a_wz):.1f} min)")
        rows.append(row)
    return rows


def comfort_summary(outcomes: Sequence[Any]) -> str:
    """One sentence: how many condition/controller means fall in each ISO 2631-1 Annex C band."""
    from loader_model.iso2631.comfort import comfort_reaction

    totals: dict[tuple[float, str, str], list[float]] = {}
    for o in outcomes:
        key = (o.spec.speed_kmh, o.spec.load, o.spec.controller)
        totals.setdefault(key, []).append(o.a_total_m_s2)
    means = [float(np.mean(v)) for v in totals.values()]
    counts: dict[str, int] = {}
    for mean in means:
        reaction = comfort_reaction(mean)
        counts[reaction] = counts.get(reaction, 0) + 1
    bands = "; ".join(f"{n} of {len(means)} {reaction!r}" for reaction, n in counts.items())
    return (
        f"mean a_total from {min(means):.2f} to {max(means):.2f} m/s². ISO 2631-1 Annex C.2.3's "
        f"likely reactions (public transport; the paper's k = 1, 1, 0.4): {bands}. "
    )
