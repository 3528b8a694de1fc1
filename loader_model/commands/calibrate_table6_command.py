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
    parser.add_argument(
        "--trials", type=int, default=8, metavar="N",
        help="trials per group of each evaluation, the same for every parameter set (>= 2)",
    )  # fmt: skip
    parser.add_argument(
        "--scatter-weight", type=float, default=1.0, metavar="W",
        help="weight of the scatter terms of the cost against the means' (0: the means alone)",
    )  # fmt: skip
    parser.add_argument(
        "--check-trials", type=int, default=80, metavar="N",
        help="trials per group of the check of both speeds after the fit (0: no check)",
    )  # fmt: skip
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
    import math

    from loader_model.experiments.calibration_table6 import (
        calibrate_table6,
        calibrated_loader,
        check_calibration,
        write_summary,
    )
    from loader_model.io.export import check_output_path
    from loader_model.parameters.sets import PARAMETER_SUFFIXES, save

    if args.output is not None:
        check_output_path(args.output, PARAMETER_SUFFIXES, "--output")
    if args.summary is not None:
        check_output_path(args.summary, (".json",), "--summary")
    for name in ("evaluations", "jobs"):
        if getattr(args, name) < 1:
            raise ValueError(f"--{name} {getattr(args, name)}: allowed: an integer >= 1")
    if args.trials < 2:
        raise ValueError(f"--trials {args.trials}: allowed: an integer >= 2 (a scatter needs two)")
    if args.check_trials != 0 and args.check_trials < 2:
        raise ValueError(f"--check-trials {args.check_trials}: allowed: 0 or an integer >= 2")
    if not math.isfinite(args.scatter_weight) or args.scatter_weight < 0.0:
        raise ValueError(f"--scatter-weight {args.scatter_weight}: allowed: a finite number >= 0")
    if args.seed < 0:
        raise ValueError(f"--seed {args.seed}: allowed: an integer >= 0")
    result = calibrate_table6(
        args.fit_speed,
        evaluations=args.evaluations,
        design_points=args.design_points,
        trials=args.trials,
        scatter_weight=args.scatter_weight,
        seed=args.seed,
        jobs=args.jobs,
        progress=not args.no_progress,
    )
    print(
        f"Table 6 calibration to the {args.fit_speed:g} km/h cells: J {result.start_cost:.3f} -> "
        f"{result.cost:.3f} ({result.evaluations} evaluations of {args.trials} trials per "
        f"group; J = Σ ((Δ_model − Δ_paper) / 10 pp)² + {args.scatter_weight:g} Σ "
        "(log(s_model / s_paper) / log 2)² over the six cells)"
    )
    for path, value in result.values.items():
        start, (low, high) = result.start[path], result.bounds[path]
        flag = "  at a bound" if path in result.at_bounds else ""
        print(
            f"  {path:<32} {start:12.5g} -> {value:12.5g}  ({value / start - 1:+7.1%})  "
            f"range [{low:.4g}, {high:.4g}]{flag}"
        )
    check = None
    if args.check_trials:
        check = check_calibration(
            result.values,
            args.fit_speed,
            trials=args.check_trials,
            seed=args.seed,
            jobs=args.jobs,
            progress=not args.no_progress,
        )
        _print_check(check)
    date = datetime.date.today().isoformat()
    if args.output is not None:
        save(calibrated_loader(result, date), args.output)
        print(f"wrote {args.output}")
    if args.summary is not None:
        write_summary(args.summary, result, date, _command(args), check)
        print(f"wrote {args.summary}")
    return 0


def _print_check(check: dict) -> None:
    """The check's counts and its cells, one line each."""
    held = f"{check['held_out_kmh']:g} km/h"
    print(
        f"check with {check['trials']} trials per group (largest standard error of a mean "
        f"{check['largest_se']:.2f} pp): means within 10 pp {check['within']}/{check['count']} "
        f"(held out, {held}: {check['held_out_within']}/{check['held_out_count']}); scatter "
        f"within a factor 2 {check['scatter_within']}/{check['count']} "
        f"({check['held_out_scatter_within']}/{check['held_out_count']}); both "
        f"{check['both_within']}/{check['count']} ({check['held_out_both_within']}/"
        f"{check['held_out_count']})"
    )
    for key, cell in check["cells"].items():
        bound = "≤ " if cell["paper_sd_bound"] else ""
        print(
            f"  {key:<28} Δ {cell['change']:+6.1f} ± {cell['se']:.1f} (paper {cell['paper']:+6.1f})"
            f"  SD {cell['sd']:5.1f} (paper {bound}{cell['paper_sd']:.1f})"
        )


def _command(args: argparse.Namespace) -> str:
    return (
        f"loader-model calibrate-table6 --fit-speed {args.fit_speed:g} --evaluations "
        f"{args.evaluations} --design-points {args.design_points} --trials {args.trials} "
        f"--scatter-weight {args.scatter_weight:g} --check-trials {args.check_trials} "
        f"--seed {args.seed}"
    )
