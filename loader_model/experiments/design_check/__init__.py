"""Check a ride-control design on the nonlinear machine over its operating envelope.

A design that looks good on one number on one course can still be wrong on the machine: it may
ride the pump's limit in a limit cycle after the last obstacle (ISO 2631-1's pitch weighting
barely counts 5 Hz, so a_total can reward that), or make a rough road worse than no control.
:func:`check_design` drives every condition of an envelope
(:mod:`~loader_model.experiments.design_check.envelope`) with the design, the baseline and the
passive accumulator on the nonlinear closed loop
(:mod:`~loader_model.experiments.design_check.runs`), computes the loop's stability margin on
each load's linearised plant and over sampled plants
(:mod:`~loader_model.experiments.design_check.margins`), and judges every condition against its
baseline (:mod:`~loader_model.experiments.design_check.verdict`).

Examples
--------
Table 3's gains on the full bucket over the paper's boards at 9 km/h (measured: a_total 4.58
against the baseline's 3.37 m/s², so the check fails and names the condition):

>>> from loader_model.control.settings import default_settings
>>> from loader_model.experiments.design_check import Design, Envelope, check_design
>>> envelope = Envelope(loads=("full",), board_speeds_kmh=(9.0,), road_classes=())
>>> check = check_design(Design(default_settings()), envelope, progress=False, sampled_plants=0)
>>> check.passed, check.failures[0].split(":")[0]
(False, 'full, boards 9 km/h')
"""

from __future__ import annotations

from typing import Any

from loader_model.experiments.design_check.envelope import (
    DEFAULT_ENVELOPE,
    Condition,
    Envelope,
    load_envelope,
)
from loader_model.experiments.design_check.margins import (
    LinearMargin,
    linear_margins,
    sampled_margins,
)
from loader_model.experiments.design_check.margins import sampled_plants as sampled_plants_of
from loader_model.experiments.design_check.runs import (
    COMPARED,
    Design,
    RunOutcome,
    holds_still,
    rest_run,
    run_condition,
)
from loader_model.experiments.design_check.verdict import (
    ConditionCheck,
    DesignCheck,
    judge_condition,
)

__all__ = [
    "COMPARED",
    "DEFAULT_ENVELOPE",
    "DEFAULT_SAMPLED_PLANTS",
    "Condition",
    "ConditionCheck",
    "Design",
    "DesignCheck",
    "Envelope",
    "LinearMargin",
    "RunOutcome",
    "check_design",
    "load_envelope",
]

#: Plants drawn for the sampled margins by default.
DEFAULT_SAMPLED_PLANTS = DEFAULT_ENVELOPE.sampled_plants


def _run_batch(design: Design, envelope: Envelope, conditions: list[Condition]) -> list[Any]:
    return [run_condition(design, envelope, condition) for condition in conditions]


def check_design(
    design: Design,
    envelope: Envelope = DEFAULT_ENVELOPE,
    *,
    jobs: int = 1,
    progress: bool = True,
    sampled_plants: int | None = None,
    study: str | None = None,
) -> DesignCheck:
    """Drive, measure and judge ``design`` over ``envelope`` (module notes).

    Parameters
    ----------
    design : Design
        The controller, its settings and the machine.
    envelope : Envelope
        Conditions and criteria (default :data:`DEFAULT_ENVELOPE`).
    jobs : int
        Processes that drive the conditions (1: this one).
    progress : bool
        Show a progress bar over the conditions.
    sampled_plants : int, optional
        Plants drawn for the sampled margins (skyhook designs), >= 0 (default: the envelope's
        :attr:`~Envelope.sampled_plants`).
    study : str, optional
        A robustness study file the plants are drawn from (default: the shipped example for
        the skid-steer; none for another machine).

    Returns
    -------
    DesignCheck

    Raises
    ------
    ValueError
        For bad ``jobs`` or ``sampled_plants``, or settings the machine's plant refuses.
    """
    from tqdm import tqdm

    from loader_model.io.processes import worker_pool

    if sampled_plants is None:
        sampled_plants = envelope.sampled_plants
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs = {jobs!r}; allowed: an integer >= 1")
    if (
        isinstance(sampled_plants, bool)
        or not isinstance(sampled_plants, int)
        or sampled_plants < 0
    ):
        raise ValueError(f"sampled_plants = {sampled_plants!r}; allowed: an integer >= 0")
    if design.controller not in ("skyhook", "virtual-accumulator"):
        raise ValueError(
            f"controller = {design.controller!r}; allowed: 'skyhook' or 'virtual-accumulator'"
        )
    conditions = list(envelope.conditions())
    margins: dict[str, LinearMargin] = {}
    if design.controller == "skyhook":
        margins = linear_margins(design, envelope.loads)
        plants = sampled_plants_of(design, sampled_plants, study)
        for load, (count, unstable, worst) in sampled_margins(plants, design).items():
            if load in margins:
                nominal = margins[load]
                margins[load] = LinearMargin(
                    load, nominal.margin_rad_s, nominal.min_damping, count, unstable, worst
                )
    bar = tqdm(total=len(conditions), desc="design check", unit="condition", disable=not progress)
    runs: list[Any] = []
    try:
        if jobs == 1:
            for condition in conditions:
                runs.append(run_condition(design, envelope, condition))
                bar.update(1)
        else:
            # by load, so that each worker resolves a load's plants once
            batches = [[c for c in conditions if c.load == load] for load in envelope.loads]
            batches = [b[i::jobs] for b in batches for i in range(jobs) if b[i::jobs]]
            found: dict[Condition, Any] = {}
            with worker_pool(jobs) as pool:
                futures = {pool.submit(_run_batch, design, envelope, b): b for b in batches}
                for future in pool.completed(list(futures)):
                    for condition, outcome in zip(futures[future], future.result(), strict=True):
                        found[condition] = outcome
                    bar.update(len(futures[future]))
            runs = [found[condition] for condition in conditions]
    finally:
        bar.close()
    rest = {load: rest_run(design, envelope, load) for load in envelope.loads}
    floor = {load: run.tail_rms if holds_still(run) else 0.0 for load, run in rest.items()}
    checks = tuple(
        judge_condition(
            condition, outcome, envelope, floor[condition.load], design.layout.machine.circuit
        )
        for condition, outcome in zip(conditions, runs, strict=True)
    )
    return DesignCheck(design, envelope, checks, margins, rest)
