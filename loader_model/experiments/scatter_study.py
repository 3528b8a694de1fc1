"""The model's Table 6 scatter and means from many trials, shipped as a CSV for the report.

Runs the Table 6 matrix (2 speeds × 2 loads × 4 controllers, :func:`~loader_model.experiments.
trials.trial_specs` and :func:`~loader_model.experiments.table6.run_trials`, the report's own
trials and seeds) with many trials per group, and writes one row per cell: the model's trial
scatter and mean change with its standard error (:func:`~loader_model.experiments.scatter.
model_scatter`), and what the first four trials give, which are the trials of
``loader-model reproduce`` with the same seed (each trial draws from its own seed, so trial k is
the same whatever the count). It takes longer than the report's minute, so ``make scatter`` ships
the file (``data/table6_scatter.csv``) with the command that made it and the report reads it::

    python -m loader_model.experiments.scatter_study --trials 100 --output table6_scatter.csv
"""

from __future__ import annotations

import argparse
import csv
import datetime
import io
import sys
import time
from collections.abc import Sequence
from importlib import resources
from typing import Any

import numpy as np

from loader_model.experiments.scatter import PAPER_TRIALS, model_scatter
from loader_model.experiments.statistics import compare_with_baseline

__all__ = ["COLUMNS", "SCATTER_FILE", "main", "read_scatter", "scatter_rows", "shipped_scatter"]

#: The shipped result (package data).
SCATTER_FILE = "table6_scatter.csv"
#: Columns of the result file, one row per cell (speed, load, controller against the baseline).
COLUMNS = (
    "speed_kmh",
    "load",
    "controller",
    "trials",
    "failed_controller",
    "failed_baseline",
    "baseline_mean_m_s2",
    "sd_pct",
    "sd_controller_pct",
    "sd_baseline_pct",
    "change_pct",
    "se_pp",
    "lift_offs_controller",
    "lift_offs_baseline",
    "four_change_pct",
    "four_low_pct",
    "four_high_pct",
    "four_p",
    "four_sd_pct",
)


def scatter_rows(
    trials: int,
    seed: int = 0,
    jobs: int = 2,
    cells: Sequence[tuple[float, str, str]] | None = None,
    progress: bool = False,
) -> list[dict[str, Any]]:
    """Run ``trials`` trials per group and return one row per cell (:data:`COLUMNS`).

    The trials are those of the whole matrix (:func:`~loader_model.experiments.trials.
    trial_specs` with the paper's factors), so a cell run alone draws the same speeds, boards
    and noise as in the whole study. A trial the simulator stops (outside the model's validity)
    is counted in ``failed_*`` and left out of the statistics.

    Parameters
    ----------
    trials : int
        Trials per speed, load and controller (the baseline included), >= 4.
    seed : int
        Base seed (the report's: 0).
    jobs : int
        Worker processes.
    cells : sequence of tuple, optional
        The cells to run, each (speed in km/h, load, controller) (default: all twelve of
        Table 6); their baselines run with them.
    progress : bool
        Show a progress bar.

    Returns
    -------
    list of dict
    """
    from loader_model.experiments.table6 import run_trials
    from loader_model.experiments.trials import trial_specs

    if isinstance(trials, bool) or not isinstance(trials, int) or trials < PAPER_TRIALS:
        raise ValueError(f"trials must be an integer >= {PAPER_TRIALS}; got {trials!r}")
    every = trial_specs(seed, trials)
    wanted = {(s.speed_kmh, s.load, s.controller) for s in every if s.controller != "baseline"}
    if cells is not None:
        unknown = sorted(set(cells) - wanted)
        if unknown:
            raise ValueError(f"cells {unknown} are not Table 6 cells; allowed: {sorted(wanted)}")
        wanted = set(cells)
    conditions = {(speed, load) for speed, load, _ in wanted}
    specs = [
        s
        for s in every
        if (s.speed_kmh, s.load, s.controller) in wanted
        or (s.controller == "baseline" and (s.speed_kmh, s.load) in conditions)
    ]
    outcomes = run_trials(specs, jobs=jobs, progress=progress, keep_failures=True)
    groups: dict[tuple[float, str, str], list[Any]] = {}
    for outcome in outcomes:
        s = outcome.spec
        groups.setdefault((s.speed_kmh, s.load, s.controller), []).append(outcome)
    rows = []
    for (speed, load, controller), group in groups.items():
        if controller == "baseline":
            continue
        rows.append(_row(speed, load, controller, groups[(speed, load, "baseline")], group))
    return rows


def _row(speed: float, load: str, controller: str, base: list, group: list) -> dict[str, Any]:
    """One cell's statistics; trials the simulator stopped (NaN a_total) are counted apart."""
    a_base = np.array([o.a_total_m_s2 for o in base])
    a_ctrl = np.array([o.a_total_m_s2 for o in group])
    ok_base, ok_ctrl = np.isfinite(a_base), np.isfinite(a_ctrl)
    many = model_scatter(a_base[ok_base], a_ctrl[ok_ctrl])
    first_base = a_base[:PAPER_TRIALS][ok_base[:PAPER_TRIALS]]
    first_ctrl = a_ctrl[:PAPER_TRIALS][ok_ctrl[:PAPER_TRIALS]]
    four = compare_with_baseline(first_base, first_ctrl)
    return {
        "speed_kmh": speed,
        "load": load,
        "controller": controller,
        "trials": len(group),
        "failed_controller": int((~ok_ctrl).sum()),
        "failed_baseline": int((~ok_base).sum()),
        "baseline_mean_m_s2": many.baseline_mean_m_s2,
        "sd_pct": many.sd_percent,
        "sd_controller_pct": many.sd_controller_percent,
        "sd_baseline_pct": many.sd_baseline_percent,
        "change_pct": many.change_percent,
        "se_pp": many.standard_error_pp,
        "lift_offs_controller": float(np.mean([o.lift_offs for o in group if o.lift_offs >= 0])),
        "lift_offs_baseline": float(np.mean([o.lift_offs for o in base if o.lift_offs >= 0])),
        "four_change_pct": four.change_percent,
        "four_low_pct": four.low_percent,
        "four_high_pct": four.high_percent,
        "four_p": four.p_value,
        "four_sd_pct": model_scatter(first_base, first_ctrl).sd_percent,
    }


def write_scatter(path: str, rows: Sequence[dict[str, Any]], header: Sequence[str]) -> None:
    """Write ``rows`` as CSV with ``header`` as ``#`` comment lines first (atomically)."""
    from loader_model.io.export import write_atomically

    buffer = io.StringIO()
    for line in header:
        buffer.write(f"# {line}\n")
    writer = csv.DictWriter(buffer, fieldnames=COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    write_atomically(
        path,
        lambda temporary: temporary.write_text(buffer.getvalue(), encoding="utf-8"),
        (".csv",),
        "scatter table",
    )


def read_scatter(text: str) -> tuple[dict[str, str], list[dict[str, Any]]]:
    """Parse the file of :func:`write_scatter`: its ``# key: value`` header and its rows."""
    header: dict[str, str] = {}
    lines = []
    for line in text.splitlines():
        if line.startswith("#"):
            key, _, value = line[1:].strip().partition(":")
            header[key.strip()] = value.strip()
        elif line.strip():
            lines.append(line)
    rows: list[dict[str, Any]] = []
    for raw in csv.DictReader(lines):
        row: dict[str, Any] = dict(raw)
        for key in COLUMNS:
            if key not in ("load", "controller"):
                integer = key in ("trials", "failed_controller", "failed_baseline")
                row[key] = int(raw[key]) if integer else float(raw[key])
        rows.append(row)
    return header, rows


def shipped_scatter() -> tuple[dict[str, str], list[dict[str, Any]]] | None:
    """The shipped result (header, rows), or None if it was never made."""
    entry = resources.files("loader_model").joinpath("data", SCATTER_FILE)
    if not entry.is_file():
        return None
    return read_scatter(entry.read_text(encoding="utf-8"))


def main(argv: list[str] | None = None) -> int:
    """Run the study and write ``--output``; a bad argument exits 2 with a one-line message."""
    parser = argparse.ArgumentParser(
        prog="python -m loader_model.experiments.scatter_study",
        description="the model's Table 6 scatter and means from many trials per group (CSV)",
    )
    parser.add_argument("--trials", type=int, default=100, metavar="N", help="trials per group")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="base seed of the trials")
    parser.add_argument("--jobs", type=int, default=2, metavar="N", help="worker processes")
    parser.add_argument("--output", required=True, metavar="FILE.csv", help="the result file")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    if args.trials < PAPER_TRIALS:
        parser.error(f"--trials {args.trials}: allowed: an integer >= {PAPER_TRIALS}")
    if args.jobs < 1:
        parser.error(f"--jobs {args.jobs}: allowed: an integer >= 1")
    if args.seed < 0:
        parser.error(f"--seed {args.seed}: allowed: an integer >= 0")
    from loader_model.io.export import check_output_path

    try:
        check_output_path(args.output, (".csv",), "--output")
    except ValueError as error:
        parser.error(str(error))
    start = time.perf_counter()
    rows = scatter_rows(args.trials, args.seed, args.jobs, progress=not args.no_progress)
    seconds = time.perf_counter() - start
    command = (
        f"python -m loader_model.experiments.scatter_study --trials {args.trials} "
        f"--seed {args.seed} --jobs {args.jobs} --output {args.output}"
    )
    header = [
        f"command: {command}",
        f"date: {datetime.date.today().isoformat()}",
        f"wall_time_s: {seconds:.0f}",
    ]
    write_scatter(args.output, rows, header)
    print(
        f"wrote {args.output} ({len(rows)} cells, {args.trials} trials per group) in {seconds:.0f} s"
    )
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
