"""The fidelity budget of Table 6 and the uncertainty of its signs.

Runs the Table 6 matrix once per modelling step (as it was; circuit states; seat pad and occupant;
tyre enveloping; k_φ sign; calibrated to 9 km/h; calibrated to 18 km/h:
:mod:`loader_model.experiments.fidelity`), then the robustness study of the estimated parameters
(``data/table6_estimates.toml``): per cell the share of plausible machines with the paper's sign.
Writes one JSON file with the command that made it; ``make fidelity`` ships it for the report.
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_jobs_argument, add_progress_argument

HELP = "measure the fidelity budget of Table 6 step by step and the uncertainty of its signs"
GUIDE = "reproduction.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--trials", type=int, default=4, metavar="N", help="trials per cell")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="seed of the trials")
    add_jobs_argument(parser, 2, "simulating the trials")
    parser.add_argument(
        "--samples", type=int, default=None, metavar="N",
        help="machines of the uncertainty study (default: the study file's, 96)",
    )  # fmt: skip
    parser.add_argument("--output", metavar="FILE.json", required=True, help="the budget (JSON)")
    add_progress_argument(parser)


def run(args: argparse.Namespace) -> int:
    import datetime
    import time

    from loader_model.experiments.calibration_table6 import shipped_calibration
    from loader_model.experiments.fidelity import (
        budget_steps,
        run_budget,
        uncertainty_shares,
        write_budget,
    )
    from loader_model.io.export import check_output_path

    check_output_path(args.output, (".json",), "--output")
    for name in ("trials", "jobs"):
        if getattr(args, name) < 1:
            raise ValueError(f"--{name} {getattr(args, name)}: allowed: an integer >= 1")
    if args.trials < 2:
        raise ValueError(f"--trials {args.trials}: allowed: >= 2 (the 95 % intervals need two)")
    if args.samples is not None and args.samples < 4:
        raise ValueError(f"--samples {args.samples}: allowed: an integer >= 4")
    start = time.perf_counter()
    calibrated = {speed: shipped_calibration(speed) for speed in (9.0, 18.0)}
    steps = budget_steps(calibrated)
    summaries = run_budget(
        steps, trials=args.trials, seed=args.seed, jobs=args.jobs, progress=not args.no_progress
    )
    for summary in summaries:
        held = (
            f", held-out {summary['held_out_within']}/{summary['held_out_count']}"
            if summary["held_out_count"]
            else ""
        )
        print(
            f"  {summary['label']:<28} {summary['within']:2d}/{summary['count']} within 10 pp"
            f"{held}; significant findings in sign {summary['significant_in_sign']}/"
            f"{summary['significant_count']}"
        )
    uncertainty = uncertainty_shares(args.samples, workers=args.jobs, progress=not args.no_progress)
    command = (
        f"loader-model fidelity --trials {args.trials} --seed {args.seed} --jobs {args.jobs}"
        f"{'' if args.samples is None else f' --samples {args.samples}'}"
    )
    write_budget(
        args.output,
        {"steps": summaries, "uncertainty": uncertainty},
        command,
        datetime.date.today().isoformat(),
        time.perf_counter() - start,
    )
    print(f"wrote {args.output} in {time.perf_counter() - start:.0f} s")
    return 0
