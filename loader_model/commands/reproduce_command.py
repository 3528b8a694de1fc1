"""Reproduce the paper on the default loader: Table 1 (modal analysis) for both bucket loads,
the linear model at the static equilibrium (Eq. 38-40), printed; then the report folder
(``--output``, default ``results/report``): the Table 6 experiment of section 5.3 beside the
paper, Fig. 10, 13, 14, the Eq. 43 comparison, Tables 4 and 5 from a synthetic record, the gains,
CSV files of every table and what differs from the paper. The folder is written atomically: an
interrupt (Ctrl-C, SIGTERM) leaves the previous report, or none, and says which."""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_jobs_argument, add_progress_argument

HELP = "reproduce the paper's results on the default loader and write the report folder"
GUIDE = "reproduction.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register ``--output``, ``--jobs``, ``--trials``, ``--seed``, ``--envelope``,
    ``--no-progress``."""
    parser.add_argument("--output", default="results/report", metavar="DIR", help="report folder")
    add_jobs_argument(parser, 2, "simulating the trials")
    parser.add_argument("--trials", type=int, default=4, metavar="N", help="trials per cell")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="base seed of the trials")
    parser.add_argument(
        "--envelope",
        choices=("tandem-cam", "rigid"),
        default="tandem-cam",
        help="how the tyres envelop the boards: tandem elliptical cams per axle from the static "
        "tyre deflection or rigid discs",
    )
    add_progress_argument(parser)


def _print_model() -> None:
    from loader_model.modal.modes import modal_analysis
    from loader_model.modal.report import format_modes
    from loader_model.modal.undamped import undamped_matrices
    from loader_model.parameters.sets import LOAD_CASES, bucket_load, default_loader
    from loader_model.vehicle.dynamics import LoaderDynamics
    from loader_model.vehicle.summary import model_summary

    loader = default_loader()
    for case in LOAD_CASES:
        load = bucket_load(case)
        title = f"=== Table 1: default loader, bucket load {case} ({load.mass:g} kg) ==="
        matrices = undamped_matrices(loader, load)
        print(format_modes(title, matrices, modal_analysis(matrices.mass, matrices.stiffness)))
        print()
    for case in LOAD_CASES:
        print(f"=== Linear model: default loader, bucket load {case} ===")
        print(model_summary(LoaderDynamics.from_parameters(loader, case)))
        print()


def run(args: argparse.Namespace) -> int:
    """Print Table 1 and the linear models, write the report folder. Returns 0."""
    import os
    from pathlib import Path

    from loader_model.bound.table6 import render_markdown
    from loader_model.experiments.report import ReportOptions, markdown_table, write_report
    from loader_model.experiments.reproduction import build_reproduction
    from loader_model.experiments.table6 import best_reductions
    from loader_model.io.interrupts import keeping

    if args.jobs < 1 or args.jobs > max(os.cpu_count() or 1, 1) * 4:
        raise ValueError(f"--jobs must be in [1, {(os.cpu_count() or 1) * 4}]; got {args.jobs}")
    if not 2 <= args.trials <= 100:
        raise ValueError(f"--trials must be in [2, 100] (a t-test needs 2); got {args.trials}")
    if args.seed < 0:
        raise ValueError(f"--seed must be >= 0; got {args.seed}")
    options = ReportOptions(
        trials=args.trials,
        seed=args.seed,
        jobs=args.jobs,
        progress=not args.no_progress,
        envelope=args.envelope,
        appendix=(lambda cells: render_markdown(reductions=best_reductions(cells)),),
    )
    summary: dict = {}

    def build(folder):
        summary.update(build_reproduction(folder, options))

    output = repr(args.output)
    kept = f"the report in {output} is unchanged" if Path(args.output).is_dir() else ""
    with keeping(lambda: kept or f"nothing written to {output}"):
        _print_model()
        path = write_report(args.output, build)
    print("=== Table 6: change of a_total against the baseline (model beside paper) ===")
    print(markdown_table(summary["tables"]["table6"]))
    print(
        f"{summary['within']} of {len(summary['paper_cells'])} paper cells within 10 percentage points; "
        f"report in {summary['timings']['total']:.1f} s"
    )
    print(f"wrote {path / 'report.md'}")
    return 0
