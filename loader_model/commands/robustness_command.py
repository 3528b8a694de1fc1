"""Robustness study: every controller against the baseline over sampled plants, roads, speeds
and bucket loads, from a study file (TOML; the guide's page docs/guide/robustness.md, example
``loader_model/data/robustness_example.toml``).

Writes into the results folder: ``parts/`` (one Parquet file per finished batch; a rerun resumes
from them), ``results.parquet`` and ``results.csv`` (one row per sample and controller),
``gains.json`` (the K_fb each gain-based controller ran with) and ``report.md`` (per controller:
how many samples fell in each category of :mod:`~loader_model.robustness.outcomes` (evaluated,
unstable on the linearised plant, diverged, outside the model's validity, failed, persistent
oscillation, pump saturated, no baseline), the probability of worse comfort over all samples with
every failure counted as worse and among the evaluated ones, the change of a_total over the
evaluated samples, worst cases, Spearman rank correlations, stability margin of the gains).
The study file is checked completely before anything runs or is written. An interrupt (Ctrl-C,
SIGTERM) stops the workers at once and says how many samples are saved; rerunning the same
command resumes.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any

from loader_model.commands.common import add_jobs_argument, add_progress_argument

__all__ = ["GUIDE", "HELP", "add_arguments", "run"]

HELP = "robustness study over sampled plants, roads, speeds and loads (local pool or Dask)"
GUIDE = "robustness.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``STUDY``, ``--output``, ``--jobs`` (``--workers``, its former name, hidden),
    ``--scheduler``, ``--no-progress``."""
    parser.add_argument("study", metavar="STUDY.toml", help="study file")
    parser.add_argument(
        "--output",
        metavar="DIR",
        default=None,
        help="results folder (default: <study name>_results in the current folder); "
        "rerunning on it resumes",
    )
    add_jobs_argument(parser, None, "of the local pool (1: this process)")
    parser.add_argument("--workers", type=int, dest="jobs", help=argparse.SUPPRESS)  # former name
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="Dask scheduler address (e.g. tcp://host:8786, from dask-jobqueue); "
        "runs on that cluster instead of the local pool",
    )
    add_progress_argument(parser)


def _kept(study: Any, folder: Path) -> str:
    """What an interrupted study kept: its saved samples and how to resume."""
    from loader_model.robustness.table import read_parts

    parts = repr(str(folder / "parts"))
    try:
        saved = f"{len(read_parts(folder, study))} of {study.samples} samples are saved in {parts}"
    except Exception:  # an unreadable part: the resumed run will say which
        saved = f"the finished batches are saved in {parts}"
    return f"{saved}; run the same command again to resume"


def run(args: argparse.Namespace) -> int:
    """Check the study and the folder, run or resume it, write and print the report."""
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(name, "1")  # before NumPy loads BLAS: see robustness.engine
    from loader_model.robustness.study import load_study

    study = load_study(args.study)
    workers = (os.cpu_count() or 1) if args.jobs is None else args.jobs
    if workers < 1:
        raise ValueError(f"--jobs {workers}: allowed: an integer >= 1")
    folder = Path(args.output or f"{Path(args.study).stem}_results")
    if not folder.parent.is_dir():
        raise ValueError(f"--output {str(folder)!r}: the folder {str(folder.parent)!r} is missing")
    from loader_model.io.export import write_atomically
    from loader_model.io.interrupts import keeping
    from loader_model.robustness.engine import read_gains, run_study
    from loader_model.robustness.report import report_text

    client = None
    if args.scheduler is not None:  # connect before writing anything
        from distributed import Client

        try:
            client = Client(args.scheduler, timeout="20s")
        except (OSError, ValueError) as error:
            raise ValueError(f"--scheduler {args.scheduler!r}: cannot connect: {error}") from None
    try:
        with keeping(lambda: _kept(study, folder)):
            table = run_study(
                study, folder, workers=workers, scheduler=client, progress=not args.no_progress
            )
    finally:
        if client is not None:
            client.close()
    text = report_text(study, table, read_gains(folder))
    write_atomically(
        folder / "report.md",
        lambda path: path.write_text(text, encoding="utf-8"),
        (".md",),
        "report",
    )
    print(text, end="")
    print(f"wrote {folder / 'results.parquet'}, {folder / 'results.csv'}, {folder / 'report.md'}")
    return 0
