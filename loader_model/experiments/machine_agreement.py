"""How many plausible machines reproduce each Table 6 cell's mean AND scatter.

The uncertainty study of the fidelity budget draws machines over the estimated parameters'
plausible ranges (``data/table6_estimates.toml``). Here each drawn machine runs the whole Table 6
matrix (2 speeds × 2 loads × 4 controllers) with ``trials`` trials per group, the report's trials
and seeds (:func:`~loader_model.experiments.trials.trial_specs`: every machine sees the same
speeds, boards and sensor noise), and per cell the study counts the machines whose

- mean change lies within 10 pp of the paper's, and
- trial scatter (pooled SD in % of the baseline mean, :func:`~loader_model.experiments.scatter.
  model_scatter`) lies within a factor 2 of the one the paper's Δ and p imply (an upper bound
  where p = 0.0000 is printed),

the rule of :mod:`~loader_model.experiments.agreement`. With a few trials per machine, a
machine's own mean and scatter are uncertain too: the result states the trial count and the
median standard error of the machines' means per cell.

The machines are a Latin hypercube over the study file's distributions from its seed
(:func:`~loader_model.robustness.sampling.sample_specs`; the speed, load and road columns of
that design are not used: every machine runs every condition). A machine the parameter files
refuse counts as failed in every cell; a cell whose group keeps fewer than two trials after the
validity checks counts as failed for that machine.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["cell_shares", "machine_values", "run_machines"]


def machine_values(machines: int) -> list[dict[str, float]]:
    """The estimated parameters' values of ``machines`` plausible machines (module notes)."""
    from importlib import resources

    from loader_model.robustness.sampling import sample_specs
    from loader_model.robustness.study import parse_study

    if isinstance(machines, bool) or not isinstance(machines, int) or machines < 2:
        raise ValueError(f"machines {machines!r}: allowed: an integer >= 2")
    text = (
        resources.files("loader_model").joinpath("data", "table6_estimates.toml").read_text("utf-8")
    )
    study = parse_study(text, "table6_estimates.toml")
    return [dict(spec.values) for spec in sample_specs(study, machines)]


def cell_shares(per_machine: list[dict[str, Any] | None]) -> dict[str, dict[str, Any]]:
    """Per cell, the shares of machines that agree (module notes).

    Parameters
    ----------
    per_machine : list
        Per machine, None if the parameter files refused it, else ``"speed/load/controller"``
        -> (change [%], SD [%], standard error [pp]) or None where its group kept too few trials.

    Returns
    -------
    dict
        ``"speed/load/controller"`` -> ``paper``, ``paper_sd``, ``paper_sd_bound``, ``count``
        (machines evaluated), ``failed``, ``mean_share``, ``scatter_share``, ``both_share``
        (NaN without an evaluated machine), ``se_median`` [pp], ``sd_median`` [%].
    """
    from loader_model.experiments.agreement import mean_agrees, paper_scatter, scatter_agrees
    from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS

    cells: dict[str, dict[str, Any]] = {}
    for speed, speed_label in SPEED_LABELS.items():
        for load, load_label in LOAD_LABELS.items():
            for controller, (paper, _) in PAPER_TABLE_6[(speed_label, load_label)].items():
                key = f"{speed:g}/{load}/{controller}"
                implied = paper_scatter(speed, load, controller)
                found = [m.get(key) if m is not None else None for m in per_machine]
                rows = [row for row in found if row is not None]
                means = [mean_agrees(change, paper) for change, _, _ in rows]
                scatters = [
                    scatter_agrees(sd, implied.sd_percent, implied.upper_bound) for _, sd, _ in rows
                ]
                both = [m and s for m, s in zip(means, scatters, strict=True)]

                def share(flags: list[bool]) -> float:
                    return float(np.mean(flags)) if flags else float("nan")

                cells[key] = {
                    "paper": float(paper),
                    "paper_sd": float(implied.sd_percent),
                    "paper_sd_bound": bool(implied.upper_bound),
                    "count": len(rows),
                    "failed": len(found) - len(rows),
                    "mean_share": share(means),
                    "scatter_share": share(scatters),
                    "both_share": share(both),
                    "se_median": float(np.median([r[2] for r in rows])) if rows else float("nan"),
                    "sd_median": float(np.median([r[1] for r in rows])) if rows else float("nan"),
                }
    return cells


def _machine_cells(outcomes: list[Any]) -> dict[str, tuple[float, float, float] | None]:
    """One machine's (change, SD, standard error) per cell from its trial outcomes."""
    from loader_model.experiments.scatter import model_scatter

    groups: dict[tuple[float, str, str], list[float]] = {}
    for o in outcomes:
        groups.setdefault((o.spec.speed_kmh, o.spec.load, o.spec.controller), []).append(
            o.a_total_m_s2
        )
    finite = {key: [v for v in values if np.isfinite(v)] for key, values in groups.items()}
    result: dict[str, tuple[float, float, float] | None] = {}
    for (speed, load, controller), values in finite.items():
        if controller == "baseline":
            continue
        key = f"{speed:g}/{load}/{controller}"
        base = finite[(speed, load, "baseline")]
        if len(base) < 2 or len(values) < 2:
            result[key] = None
            continue
        model = model_scatter(base, values)
        result[key] = (model.change_percent, model.sd_percent, model.standard_error_pp)
    return result


def run_machines(
    machines: int = 24,
    trials: int = 8,
    seed: int = 0,
    jobs: int = 2,
    progress: bool = True,
    duration_s: float | None = None,
) -> dict[str, Any]:
    """Run the study of the module notes.

    Parameters
    ----------
    machines : int
        Plausible machines drawn (>= 2).
    trials : int
        Trials per group and machine (>= 2).
    seed : int
        Seed of the trials (the report's: 0).
    jobs : int
        Worker processes.
    progress : bool
        Show a progress bar.
    duration_s : float, optional
        Simulated time per trial (default: the whole course; shorter for tests).

    Returns
    -------
    dict
        ``machines``, ``trials``, ``seed``, ``refused`` (machines the parameter files refused),
        ``stopped`` (trials the validity checks stopped) and ``cells`` (:func:`cell_shares`).
    """
    from loader_model.experiments.table6 import run_trials
    from loader_model.experiments.trials import LOADS, trial_specs
    from loader_model.experiments.variant import AS_BUILT

    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 2:
        raise ValueError(f"trials {trials!r}: allowed: an integer >= 2 (a scatter needs two)")
    variants: list[Any] = []
    for index, values in enumerate(machine_values(machines)):
        variant = AS_BUILT.with_values(values, f"plausible machine {index}")
        try:
            for load in LOADS:
                variant.parameter_sets(load)
        except ValueError:
            variant = None
        variants.append(variant)
    specs = [
        spec
        for variant in variants
        if variant is not None
        for spec in trial_specs(seed, trials, duration_s=duration_s, variant=variant)
    ]
    outcomes = run_trials(specs, jobs=jobs, progress=progress, keep_failures=True)
    by_variant: dict[Any, list[Any]] = {}
    for outcome in outcomes:
        by_variant.setdefault(outcome.spec.variant, []).append(outcome)
    per_machine = [None if v is None else _machine_cells(by_variant[v]) for v in variants]
    return {
        "machines": machines,
        "trials": trials,
        "seed": seed,
        "refused": sum(v is None for v in variants),
        "stopped": int(sum(not np.isfinite(o.a_total_m_s2) for o in outcomes)),
        "cells": cell_shares(per_machine),
    }
