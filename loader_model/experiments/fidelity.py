"""The fidelity budget of Table 6: one modelling step at a time, each measured.

The steps run the whole Table 6 matrix (:mod:`~loader_model.experiments.trials`, the report's
seeds) on a :class:`~loader_model.experiments.variant.ModelVariant` each, cumulatively:

1. as it was: Table 5's flow as a cylinder leak for every controller, the seat on the rigid
   chassis, rigid-wheel tyres, Table 3 as printed (k_φ = −0.22);
2. then circuit states: baseline and passive on closed load-holding valves (errata 11);
3. then seat pad and occupant (errata 13);
4. then tyre enveloping: the tandem elliptical cam (errata 13);
5. then k_φ sign: Table 3 with k_φ = +0.22 (errata 12): the model as built, the shipped files;
6. then calibrated: the estimated parameters fitted to the six 9 km/h cells
   (:mod:`~loader_model.experiments.calibration_table6`), the 18 km/h cells held out;
7. the reverse check: fitted to the 18 km/h cells, 9 km/h held out.

Per step: the cells within 10 pp of the paper, the 9 km/h empty row with its 95 % intervals, and
the paper's significant findings (p < 0.05, nine cells) reproduced in sign, and in sign with
the model's own p < 0.05; per cell the model's trial scatter beside the one the paper's Δ and p
imply, and the cells whose scatter, and whose mean and scatter both, agree with the paper's
(:mod:`~loader_model.experiments.agreement`: mean within 10 pp, scatter within a factor 2).
The result is written as JSON (:func:`write_budget`) beside the command that made it, since the
whole budget takes minutes; the report renders the shipped file.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from loader_model.experiments.agreement import WITHIN_PP
from loader_model.experiments.variant import AS_BUILT, AS_IT_WAS, ModelVariant

__all__ = [
    "SIGNIFICANCE",
    "BudgetStep",
    "budget_steps",
    "read_budget",
    "run_budget",
    "scatter_summary",
    "step_summary",
    "uncertainty_shares",
    "write_budget",
]

#: p-value below which a paper cell counts as a significant finding.
SIGNIFICANCE = 0.05


@dataclass(frozen=True)
class BudgetStep:
    """One step of the budget: its label, the model variant and the held-out speed (if any)."""

    label: str
    variant: ModelVariant
    held_out_kmh: float | None = None


def budget_steps(calibrated: dict[float, dict[str, float]] | None = None) -> list[BudgetStep]:
    """The steps of the module notes; ``calibrated`` maps the fitted speed (9, 18) to its values."""
    steps = [BudgetStep("as it was", AS_IT_WAS)]
    circuit = replace(AS_IT_WAS, label="+ circuit states", holding_valves=True)
    seat = replace(circuit, label="+ seat pad and occupant", occupant=True)
    envelope = replace(seat, label="+ tyre enveloping", envelope="tandem-cam")
    sign = replace(envelope, label="+ k_φ sign (as built)", table3_gain=AS_BUILT.table3_gain)
    steps += [BudgetStep(v.label, v) for v in (circuit, seat, envelope, sign)]
    for speed, values in sorted((calibrated or {}).items()):
        held_out = 18.0 if speed == 9.0 else 9.0
        label = f"+ calibrated to {speed:g} km/h"
        steps.append(BudgetStep(label, AS_BUILT.with_values(values, label), held_out))
    return steps


def _comparison(cell: Any) -> dict[str, float]:
    model = cell.model
    return {
        "change": float(model.change_percent),
        "low": float(model.low_percent),
        "high": float(model.high_percent),
        "p": float(model.p_value),
        "paper": float(cell.paper_change_percent),
        "paper_p": float(cell.paper_p_value),
    }


def step_summary(step: BudgetStep, cells: list[Any]) -> dict[str, Any]:
    """What the budget table shows of one step (module notes), from its Table 6 cells."""
    paper = [c for c in cells if np.isfinite(c.paper_change_percent)]
    significant = [c for c in paper if c.paper_p_value < SIGNIFICANCE]

    def same_sign(c: Any) -> bool:
        return bool(np.sign(c.model.change_percent) == np.sign(c.paper_change_percent))

    held = [c for c in paper if step.held_out_kmh is not None and c.speed_kmh == step.held_out_kmh]
    return {
        "label": step.label,
        "values": dict(step.variant.values),
        "cells": {f"{c.speed_kmh:g}/{c.load}/{c.controller}": _comparison(c) for c in paper},
        "within": sum(c.within <= WITHIN_PP for c in paper),
        "count": len(paper),
        "held_out_kmh": step.held_out_kmh,
        "held_out_within": sum(c.within <= WITHIN_PP for c in held) if held else None,
        "held_out_count": len(held) if held else None,
        "significant_count": len(significant),
        "significant_in_sign": sum(same_sign(c) for c in significant),
        "significant_in_sign_and_p": sum(
            same_sign(c) and c.model.p_value < SIGNIFICANCE for c in significant
        ),
        "baseline_a_total": {},
    }


def run_budget(
    steps: list[BudgetStep], *, trials: int = 4, seed: int = 0, jobs: int = 2, progress: bool = True
) -> list[dict[str, Any]]:
    """Run the Table 6 matrix on every step; returns :func:`step_summary` per step, with the
    baseline's mean a_total per condition and the trials the simulator stopped (listed, left
    out of the cells: a run outside the model's validity is not a result)."""
    from loader_model.experiments.table6 import run_trials, table6_cells
    from loader_model.experiments.trials import trial_specs

    summaries = []
    for step in steps:
        specs = trial_specs(seed, trials, variant=step.variant)
        every = run_trials(specs, jobs=jobs, progress=progress, keep_failures=True)
        outcomes = [o for o in every if np.isfinite(o.a_total_m_s2)]
        summary = step_summary(step, table6_cells(outcomes))
        summary["failed_trials"] = [
            f"{o.spec.speed_kmh:g}/{o.spec.load}/{o.spec.controller}/trial {o.spec.trial}: "
            f"{o.weighted_rms['failed']}"
            for o in every
            if not np.isfinite(o.a_total_m_s2)
        ]
        baseline: dict[str, list[float]] = {}
        for o in outcomes:
            if o.spec.controller == "baseline":
                key = f"{o.spec.speed_kmh:g}/{o.spec.load}"
                baseline.setdefault(key, []).append(o.a_total_m_s2)
        summary["baseline_a_total"] = {k: float(np.mean(v)) for k, v in baseline.items()}
        summaries.append(summary | scatter_summary(outcomes, step.held_out_kmh, summary["cells"]))
    return summaries


def scatter_summary(
    outcomes: list[Any], held_out_kmh: float | None, cells: dict[str, dict[str, float]]
) -> dict[str, Any]:
    """Each cell's scatter beside the paper's implied one, and the agreement counts.

    Adds to each entry of ``cells`` (keyed ``"speed/load/controller"``, as :func:`step_summary`
    makes them) the model's pooled trial SD ``sd`` [% of the baseline mean] and the standard
    error of its mean change ``se`` [pp] (:func:`~loader_model.experiments.scatter.
    model_scatter`), the paper's implied SD ``paper_sd`` and whether it is an upper bound
    ``paper_sd_bound``, and ``scatter_agrees`` / ``agrees`` (scatter / mean and scatter,
    :mod:`~loader_model.experiments.agreement`). Returns the counts over all cells and over
    the held-out speed's: ``scatter_within``, ``both_within``, ``held_out_scatter_within``,
    ``held_out_both_within``, and ``largest_se`` [pp].
    """
    from loader_model.experiments.agreement import mean_agrees, paper_scatter, scatter_agrees
    from loader_model.experiments.scatter import model_scatter

    groups: dict[tuple[float, str, str], list[float]] = {}
    for o in outcomes:
        key = (o.spec.speed_kmh, o.spec.load, o.spec.controller)
        groups.setdefault(key, []).append(o.a_total_m_s2)
    counts = dict.fromkeys(
        ("scatter_within", "both_within", "held_out_scatter_within", "held_out_both_within"), 0
    )
    largest = 0.0
    for key, cell in cells.items():
        speed, load, controller = key.split("/")
        base = groups[(float(speed), load, "baseline")]
        model = model_scatter(base, groups[(float(speed), load, controller)])
        paper = paper_scatter(float(speed), load, controller)
        scatter_ok = scatter_agrees(model.sd_percent, paper.sd_percent, paper.upper_bound)
        both = scatter_ok and mean_agrees(cell["change"], cell["paper"])
        cell.update(
            sd=model.sd_percent,
            se=model.standard_error_pp,
            paper_sd=float(paper.sd_percent),
            paper_sd_bound=paper.upper_bound,
            scatter_agrees=scatter_ok,
            agrees=both,
        )
        largest = max(largest, model.standard_error_pp)
        held = held_out_kmh is not None and float(speed) == held_out_kmh
        for name, ok in (("scatter_within", scatter_ok), ("both_within", both)):
            counts[name] += int(ok)
            counts[f"held_out_{name}"] += int(ok and held)
    result: dict[str, Any] = counts | {"largest_se": largest}
    if held_out_kmh is None:
        result |= {"held_out_scatter_within": None, "held_out_both_within": None}
    return result


def write_budget(
    path: Any, results: dict[str, Any], command: str, date: str, seconds: float
) -> None:
    """Write the budget and the uncertainty study as JSON with the command that made them, their
    date and wall time (atomically: a failed run leaves no file)."""
    from loader_model.io.export import write_atomically

    content = {"command": command, "date": date, "wall_time_s": round(seconds, 1), **results}
    text = json.dumps(content, indent=1, sort_keys=True, allow_nan=True)
    write_atomically(
        path,
        lambda temporary: temporary.write_text(text + "\n", encoding="utf-8"),
        (".json",),
        "fidelity budget",
    )


def read_budget(path: Any) -> dict[str, Any]:
    """The JSON of :func:`write_budget`."""
    with open(path, encoding="utf-8") as handle:
        return json.load(handle)


def uncertainty_shares(samples: int | None = None, workers: int = 2, progress: bool = True) -> dict:
    """The share of plausible machines that reproduce the paper's sign, per Table 6 cell.

    Runs the robustness study of the estimated parameters (``data/table6_estimates.toml``, each
    sample one machine, speed and load with every controller; :mod:`loader_model.robustness`)
    and counts, per cell, the samples whose change against their own baseline has the paper's
    sign. Returns ``{"samples": n, "cells": {"9/empty/passive": {"share": s, "count": k,
    "failed": f, "paper": Δ}}}``; a failed run (refused plant, validity stop) counts in
    ``failed``, not in the share.
    """
    import dataclasses
    import tempfile
    from importlib import resources

    from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS
    from loader_model.robustness.engine import run_study
    from loader_model.robustness.study import parse_study

    text = (
        resources.files("loader_model").joinpath("data", "table6_estimates.toml").read_text("utf-8")
    )
    study = parse_study(text, "table6_estimates.toml")
    if samples is not None:
        study = dataclasses.replace(study, samples=int(samples))
    with tempfile.TemporaryDirectory(prefix="loader-model-uncertainty-") as folder:
        rows = run_study(study, folder, workers=workers, progress=progress).to_pylist()
    cells: dict[str, dict[str, float]] = {}
    for row in rows:
        if row["controller"] == "baseline":
            continue
        key = f"{row['speed_kmh']:g}/{row['load']}/{row['controller']}"
        paper = PAPER_TABLE_6[(SPEED_LABELS[row["speed_kmh"]], LOAD_LABELS[row["load"]])]
        cell = cells.setdefault(
            key, {"agree": 0, "count": 0, "failed": 0, "paper": paper[row["controller"]][0]}
        )
        change = row["change_percent"]
        if row["failed"] or change is None or not np.isfinite(change):
            cell["failed"] += 1
            continue
        cell["count"] += 1
        cell["agree"] += int(np.sign(change) == np.sign(cell["paper"]))
    for cell in cells.values():
        cell["share"] = cell["agree"] / cell["count"] if cell["count"] else float("nan")
    return {"samples": study.samples, "cells": dict(sorted(cells.items()))}
