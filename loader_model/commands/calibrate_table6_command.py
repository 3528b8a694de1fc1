"""Calibrate the estimated parameters to one speed's Table 6 cells, the other speed held out.

The parameters and their plausible ranges are ``data/table6_estimates.toml``; one parameter set
for all cells of the fitted speed (:mod:`loader_model.experiments.calibration_table6`). Writes a
loader parameter file whose calibrated values say to which cells and on what date; the held-out
cells are never read. ``make calibrate-table6`` runs both fits and ships the files.
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_jobs_argument, add_progress_argument

HELP = "fit the estimated parameters to Table 6's cells at one speed (the other held out)"
GUIDE = "reproduction.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--fit-speed", type=float, choices=(9.0, 18.0), default=9.0, metavar="KMH",
        help="the speed whose six cells are fitted: 9 or 18 km/h (the other is held out)",
    )  # fmt: skip
    parser.add_argument(
        "--evaluations", type=int, default=128, metavar="N",
        help="cost evaluations in all (each one run of the fitted speed's trials)",
    )  # fmt: skip
    parser.add_argument(
        "--design-points", type=int, default=32, metavar="N",
        help="points of the Sobol design before Nelder-Mead, a power of 2",
    )  # fmt: skip
    parser.add_argument("--trials", type=int, default=1, metavar="N", help="trials per cell")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="seed of the trials")
    add_jobs_argument(parser, 1, "simulating the trials")
    parser.add_argument(
        "--output", metavar="FILE.toml", default=None, help="calibrated loader file"
    )
    parser.add_argument(
        "--summary", metavar="FILE.json", default=None,
        help="the fit's summary (J before and after, evaluations, values, bounds reached)",
    )  # fmt: skip
    add_progress_argument(parser)


def run(args: argparse.Namespace) -> int:
    import datetime

    from loader_model.experiments.calibration_table6 import (
        calibrate_table6,
        calibrated_loader,
        write_summary,
    )
    from loader_model.io.export import check_output_path
    from loader_model.parameters.sets import PARAMETER_SUFFIXES, save

    if args.output is not None:
        check_output_path(args.output, PARAMETER_SUFFIXES, "--output")
    if args.summary is not None:
        check_output_path(args.summary, (".json",), "--summary")
    for name in ("evaluations", "trials", "jobs"):
        if getattr(args, name) < 1:
            raise ValueError(f"--{name} {getattr(args, name)}: allowed: an integer >= 1")
    if args.seed < 0:
        raise ValueError(f"--seed {args.seed}: allowed: an integer >= 0")
    result = calibrate_table6(
        args.fit_speed,
        evaluations=args.evaluations,
        design_points=args.design_points,
        trials=args.trials,
        seed=args.seed,
        jobs=args.jobs,
        progress=not args.no_progress,
    )
    print(
        f"Table 6 calibration to the {args.fit_speed:g} km/h cells: J {result.start_cost:.3f} -> "
        f"{result.cost:.3f} ({result.evaluations} evaluations; J = Σ ((Δ_model − Δ_paper) / "
        "10 pp)² over the six cells)"
    )
    for path, value in result.values.items():
        start, (low, high) = result.start[path], result.bounds[path]
        flag = "  at a bound" if path in result.at_bounds else ""
        print(
            f"  {path:<32} {start:12.5g} -> {value:12.5g}  ({value / start - 1:+7.1%})  "
            f"range [{low:.4g}, {high:.4g}]{flag}"
        )
    date = datetime.date.today().isoformat()
    if args.output is not None:
        save(calibrated_loader(result, date), args.output)
        print(f"wrote {args.output}")
    if args.summary is not None:
        write_summary(args.summary, result, date, _command(args))
        print(f"wrote {args.summary}")
    return 0


def _command(args: argparse.Namespace) -> str:
    return (
        f"loader-model calibrate-table6 --fit-speed {args.fit_speed:g} --evaluations "
        f"{args.evaluations} --design-points {args.design_points} --trials {args.trials} "
        f"--seed {args.seed}"
    )
