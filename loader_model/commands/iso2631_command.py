"""Evaluate measured seat accelerations per ISO 2631-1:1997 (the paper's section 5.3, Eq. 49-50).

DATA.csv has a header row with a ``time`` column in s and axis columns among x, y, z (m/s²) and
roll, pitch, yaw (rad/s²). Each axis is frequency weighted (x, y: Wd; z: Wk; rotations: We by
default) and reported as weighted r.m.s. (Eq. 49), crest factor, MTVV, VDV and eVDV; the axes
combine into the vibration total value (Eq. 50, k = 1 for x, y, z, 0.4 for pitch by default).
The daily exposure A(8) and daily VDV of the translational axes are compared with the values of
Directive 2002/44/EC.
"""

from __future__ import annotations

import argparse

__all__ = ["GUIDE", "HELP", "add_arguments", "run"]

HELP = "ISO 2631-1 whole-body vibration evaluation of a CSV record (Eq. 49, 50)"
GUIDE = "iso2631.md"  # its page of the user guide (docs/guide/)


def _pair(text: str) -> tuple[str, str]:
    axis, separator, value = text.partition("=")
    if not separator or not axis.strip() or not value.strip():
        raise argparse.ArgumentTypeError(f"expected AXIS=VALUE, got {text!r}")
    return axis.strip(), value.strip()


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register the arguments of ``loader-model iso2631``."""
    parser.add_argument(
        "data",
        nargs="?",
        metavar="DATA.csv",
        help="CSV with a 'time' column (s) and axis columns x, y, z (m/s²), roll, pitch, yaw "
        "(rad/s²)",
    )
    parser.add_argument(
        "--weighting",
        action="append",
        type=_pair,
        default=[],
        metavar="AXIS=W",
        help="weighting of an axis (Wk, Wd, Wc, We, Wj, Wf); repeatable; defaults x,y=Wd, z=Wk, "
        "roll,pitch,yaw=We",
    )
    parser.add_argument(
        "--k-factor",
        action="append",
        type=_pair,
        default=[],
        metavar="AXIS=K",
        help="k factor of an axis in Eq. 50; repeatable; defaults 1 for x, y, z, 0.63 roll, "
        "0.4 pitch, 0.2 yaw",
    )
    parser.add_argument(
        "--integration-time",
        type=float,
        default=1.0,
        metavar="S",
        help="running r.m.s. integration time for MTVV in s",
    )
    parser.add_argument(
        "--running-rms",
        choices=("linear", "exponential"),
        default="linear",
        help="running r.m.s. integration (ISO 2631-1 6.3.1)",
    )
    parser.add_argument(
        "--exposure-hours",
        type=float,
        default=8.0,
        metavar="H",
        help="daily exposure time for A(8) and the daily VDV in h",
    )
    parser.add_argument(
        "--plot-weightings",
        metavar="FILE.png",
        help="also write a plot of the weighting curves (PNG, PDF or SVG)",
    )


def _once(option: str, pairs: list[tuple[str, str]]) -> dict[str, str]:
    axes = [axis for axis, _ in pairs]
    for axis in axes:
        if axes.count(axis) > 1:
            raise ValueError(f"{option} {axis}= is given more than once")
    return dict(pairs)


def _k_factors(pairs: list[tuple[str, str]]) -> dict[str, float]:
    factors = {}
    for axis, text in pairs:
        try:
            factors[axis] = float(text)
        except ValueError:
            raise ValueError(f"--k-factor {axis}: K must be a number; got {text!r}") from None

    return factors


def run(args: argparse.Namespace) -> int:
    """Evaluate ``args.data`` and print the table; write the plot if asked. Returns 0."""
    from loader_model.io.export import check_output_path
    from loader_model.iso2631 import (
        evaluate_record,
        format_evaluation,
        health_assessment,
        plot_weightings,
        read_vibration_csv,
    )
    from loader_model.iso2631.plot import PLOT_SUFFIXES

    if args.plot_weightings is not None:
        check_output_path(args.plot_weightings, PLOT_SUFFIXES, "--plot-weightings")
    if args.data is None and args.plot_weightings is None:
        raise ValueError("give DATA.csv and/or --plot-weightings FILE.png; got neither")
    if not 0.0 < args.exposure_hours <= 24.0:
        raise ValueError(
            f"--exposure-hours must be in (0, 24] (a daily exposure); got {args.exposure_hours!r}"
        )
    report = None
    if args.data is not None:
        record = read_vibration_csv(args.data)
        try:
            evaluation = evaluate_record(
                record,
                weightings=_once("--weighting", args.weighting),
                k_factors=_k_factors(list(_once("--k-factor", args.k_factor).items())),
                integration_time_s=args.integration_time,
                running_rms_method=args.running_rms,
            )
        except ValueError as error:
            raise ValueError(f"{args.data}: {error}") from None
        assessment = health_assessment(evaluation, args.exposure_hours * 3600.0)
        report = format_evaluation(evaluation, assessment, title=f"{args.data}:")
    if args.plot_weightings is not None:
        plot_weightings(args.plot_weightings)
    if report is not None:
        print(report)
    if args.plot_weightings is not None:
        print(f"wrote {args.plot_weightings}")
    return 0
