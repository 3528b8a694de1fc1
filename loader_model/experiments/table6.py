"""The Table 6 experiment: run the trials on a process pool, compare each controller with the
baseline, and put the result beside the paper's Table 6.

Table 6's row labels are garbled in the extracted text ("Low / Low / Low High / High Low /
High High" over two rows each). Read as Speed/Load: Low/Low, Low/High, High/Low, High/High. The
text confirms the second block is low speed with high load ("The combination of low travel speed
and high bucket load produced relatively small accelerations; vibration was more or less the same
with or without additional damping"), the block with −1.3, 6.0, 2.5.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from loader_model.experiments.statistics import Comparison, compare_with_baseline
from loader_model.experiments.trials import TrialOutcome, TrialSpec, run_trial
from loader_model.io.processes import worker_pool

__all__ = [
    "LOAD_LABELS",
    "PAPER_TABLE_6",
    "SPEED_LABELS",
    "Table6Cell",
    "best_reductions",
    "run_trials",
    "table6_cells",
]

#: Low / high labels of the factors.
SPEED_LABELS = {9.0: "Low", 18.0: "High"}
LOAD_LABELS = {"empty": "Low", "full": "High"}
#: Table 6 of the paper: (speed, load) -> controller -> (change %, p-value).
PAPER_TABLE_6: dict[tuple[str, str], dict[str, tuple[float, float]]] = {
    ("Low", "Low"): {
        "passive": (-26.4, 0.0001),
        "virtual-accumulator": (-22.6, 0.0003),
        "skyhook": (-33.6, 0.0000),
    },
    ("Low", "High"): {
        "passive": (-1.3, 0.2683),
        "virtual-accumulator": (6.0, 0.0159),
        "skyhook": (2.5, 0.0046),
    },
    ("High", "Low"): {
        "passive": (-2.6, 0.1548),
        "virtual-accumulator": (-1.1, 0.6377),
        "skyhook": (-17.4, 0.0004),
    },
    ("High", "High"): {
        "passive": (-10.7, 0.0038),
        "virtual-accumulator": (-16.1, 0.0007),
        "skyhook": (-14.4, 0.0008),
    },
}


@dataclass(frozen=True)
class Table6Cell:
    """One cell of Table 6: model comparison beside the paper's numbers."""

    speed_kmh: float
    load: str
    controller: str
    model: Comparison
    paper_change_percent: float
    paper_p_value: float

    @property
    def within(self) -> float:
        """|model change − paper change| in percentage points."""
        return abs(self.model.change_percent - self.paper_change_percent)


def _run_chunk(specs: list[TrialSpec]) -> list[TrialOutcome]:
    return [run_trial(spec) for spec in specs]


def _run_chunk_keeping_failures(specs: list[TrialSpec]) -> list[TrialOutcome]:
    """As :func:`_run_chunk`, but a trial the simulator stops (a failed step, a run outside the
    model's validity) gives an outcome with a NaN a_total and the reason, instead of raising."""
    from loader_model.simulation.validity_check import SimulationError

    outcomes = []
    for spec in specs:
        try:
            outcomes.append(run_trial(spec))
        except SimulationError as error:
            outcomes.append(TrialOutcome(spec, float("nan"), {"failed": str(error)[:300]}, -1))
    return outcomes


def _one_blas_thread() -> None:
    """Pool worker start: one BLAS thread. A trial's linear algebra is small; with threaded BLAS
    in two workers on two cores the 64-run matrix took 8.6 s instead of 4.7 s (measured)."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)


def run_trials(
    specs: Sequence[TrialSpec],
    jobs: int = 2,
    progress: bool = True,
    meanwhile: Callable[[], None] | Sequence[tuple[str, Callable[[], None]]] | None = None,
    keep_failures: bool = False,
) -> list[TrialOutcome]:
    """Run ``specs`` on ``jobs`` processes (1: in this process), in the order given.

    Trials are batched per (load, controller) so that each worker sets up each controller once;
    the results do not depend on ``jobs`` (each trial carries its own seed). Trials run with one
    BLAS thread per process (:func:`_one_blas_thread`). The workers end with this process
    (:func:`~loader_model.io.processes.worker_pool`): an interrupt or an error stops them at once.
    ``meanwhile`` runs in this process while the workers simulate (or after the trials, with
    ``jobs`` = 1), so that the calling process does useful work instead of waiting; given as
    (label, step) pairs, each step counts as one task of the progress bar beside the trials, which
    count as their batches finish, so the bar moves while both run. With
    ``keep_failures`` a trial the simulator stops comes back with a NaN a_total (the reason in
    its ``weighted_rms["failed"]``) instead of stopping the run.
    """
    from tqdm import tqdm

    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be an integer >= 1; got {jobs!r}")
    groups: dict[tuple[str, str], list[int]] = {}
    for index, spec in enumerate(specs):
        groups.setdefault((spec.load, spec.controller), []).append(index)
    batches = [[specs[i] for i in indices] for indices in groups.values()]
    outcomes: dict[TrialSpec, TrialOutcome] = {}
    chunk = _run_chunk_keeping_failures if keep_failures else _run_chunk
    if meanwhile is None:
        steps: list[tuple[str, Callable[[], None]]] = []
    elif callable(meanwhile):
        steps = [("", meanwhile)]
    else:
        steps = list(meanwhile)
    bar = tqdm(
        total=len(specs) + len(steps),
        desc=f"{len(specs)} trials" + (f" + {len(steps)} report steps" if steps else ""),
        unit="task",
        disable=not progress,
    )

    def collect(results: list[TrialOutcome], count: bool = True) -> None:
        for outcome in results:
            outcomes[outcome.spec] = outcome
        if count:
            bar.update(len(results))

    def run_steps() -> None:
        for label, step in steps:
            bar.set_postfix_str(label, refresh=True)
            step()
            bar.update(1)
        if steps:
            bar.set_postfix_str("trials")

    def counted(size: int) -> Callable[[Any], None]:
        # runs in the pool's thread as a batch finishes, so the bar moves during a long step
        def done(future: Any) -> None:
            if not future.cancelled() and future.exception() is None:
                bar.update(size)

        return done

    try:
        if jobs == 1:
            from threadpoolctl import threadpool_limits

            with threadpool_limits(1):
                for batch in batches:
                    collect(chunk(batch))
            run_steps()
        else:
            with worker_pool(jobs, initializer=_one_blas_thread) as pool:
                futures = [pool.submit(chunk, batch) for batch in batches]
                for future, batch in zip(futures, batches, strict=True):
                    future.add_done_callback(counted(len(batch)))
                run_steps()
                for future in pool.completed(futures):
                    collect(future.result(), count=False)
    finally:
        bar.close()
    return [outcomes[spec] for spec in specs]


def table6_cells(outcomes: Sequence[TrialOutcome]) -> list[Table6Cell]:
    """Compare every non-baseline controller with the baseline of the same speed and load."""
    values: dict[tuple[float, str, str], list[float]] = {}
    for outcome in outcomes:
        spec = outcome.spec
        values.setdefault((spec.speed_kmh, spec.load, spec.controller), []).append(
            outcome.a_total_m_s2
        )
    cells = []
    for (speed, load, controller), sample in values.items():
        if controller == "baseline":
            continue
        baseline = values.get((speed, load, "baseline"))
        if baseline is None:
            raise ValueError(f"no baseline trials at {speed:g} km/h, load {load}")
        paper = PAPER_TABLE_6.get((SPEED_LABELS.get(speed, "?"), LOAD_LABELS.get(load, "?")), {})
        change, p_value = paper.get(controller, (np.nan, np.nan))
        cells.append(
            Table6Cell(
                speed, load, controller, compare_with_baseline(baseline, sample), change, p_value
            )
        )
    return cells


def best_reductions(cells: Sequence[Table6Cell]) -> dict[str, dict[str, tuple[str, float]]]:
    """The largest reduction of a_total per condition, measured (the paper) and simulated.

    Returns
    -------
    dict
        ``"9 km/h empty"`` (the condition names of the bound's result file) → ``"measured"``:
        (controller, change in %) of the paper's best controller in Table 6, and
        ``"simulated"``: the best of the cells' controllers (the mean change against the
        baseline, Eq. 50).
    """
    best: dict[str, dict[str, tuple[str, float]]] = {}
    for cell in cells:
        found = best.setdefault(f"{cell.speed_kmh:g} km/h {cell.load}", {})
        change = cell.model.change_percent
        if np.isfinite(change) and ("simulated" not in found or change < found["simulated"][1]):
            found["simulated"] = (cell.controller, float(change))
        paper = PAPER_TABLE_6.get(
            (SPEED_LABELS.get(cell.speed_kmh, "?"), LOAD_LABELS.get(cell.load, "?"))
        )
        if paper and "measured" not in found:
            controller, (measured, _) = min(paper.items(), key=lambda item: item[1][0])
            found["measured"] = (controller, measured)
    return best
