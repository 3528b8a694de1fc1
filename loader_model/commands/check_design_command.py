"""Check a ride-control design on the nonlinear machine over its operating envelope.

Drives every condition of the envelope (both loads; the paper's five 40 mm boards at several
speeds, spaced by the paper's rule; ISO 8608 roads of classes B to D at 5 to 30 km/h; a settle
window on flat ground after each) with the design, the baseline and the passive accumulator, and
prints per condition a_total (ISO 2631-1, Eq. 50) beside the baseline's and the passive's, the
pitch axis, the pump command's and displacement rate's time at their limits, the lift-offs and
the residual pitch at the end of the settle window, then the loop's stability margin on each
load's linearised plant and over sampled plants, and the verdict: every failing condition with
its reason. A TOML file overrides the envelope and the criteria (--conditions; the user guide's
page on the design check shows its format).

Exit codes: 0 the design passes, 4 it fails the check, 2 a usage error.
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import (
    add_jobs_argument,
    add_machine_argument,
    add_progress_argument,
)

HELP = "check a controller design on the nonlinear machine over its operating envelope"
GUIDE = "design_check.md"  # its page of the user guide (docs/guide/)

#: Exit code of a design that fails its check.
EXIT_CHECK_FAILED = 4


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register the arguments of ``loader-model check-design``."""
    parser.add_argument(
        "settings",
        metavar="SETTINGS.toml",
        help="controller settings file to check (e.g. written by loader-model design --output; "
        "'default' for the shipped Table 3 settings)",
    )
    parser.add_argument(
        "--controller",
        choices=("skyhook", "virtual-accumulator"),
        default="skyhook",
        help="the control law the settings are for",
    )
    add_machine_argument(parser)
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="the machine's parameter file (default: its shipped values)",
    )
    parser.add_argument(
        "--conditions",
        metavar="FILE.toml",
        default=None,
        help="conditions and criteria to check over (default: the default envelope)",
    )
    parser.add_argument(
        "--sampled-plants",
        type=int,
        default=None,
        metavar="N",
        help="plants drawn for the sampled stability margin (default: the envelope's, 16; 0: none)",
    )
    parser.add_argument(
        "--study",
        metavar="FILE.toml",
        default=None,
        help="robustness study whose parameter distributions the sampled plants are drawn "
        "from (default: the shipped example for the skid-steer, none for another machine)",
    )
    add_jobs_argument(parser, 2, "driving the conditions")
    parser.add_argument(
        "--output",
        metavar="FILE.md|FILE.csv",
        default=None,
        help="also write the check as Markdown or CSV",
    )
    add_progress_argument(parser)


def run(args: argparse.Namespace) -> int:
    """Run the check, print it, write it where asked; exit code 4 when the design fails."""
    from loader_model.io.interrupts import files_note, keeping

    written: list[str] = []
    with keeping(lambda: files_note((args.output,), written)):
        return _check(args, written)


def load_design(settings: str, controller: str, machine: str, params: str | None):
    """The :class:`~loader_model.experiments.design_check.Design` of the command's arguments."""
    from loader_model.control.settings import default_settings, load_settings
    from loader_model.experiments.design_check import Design
    from loader_model.plant.layout import plant_layout

    loaded = default_settings() if settings == "default" else load_settings(settings)
    layout = plant_layout(machine)
    return Design(loaded, controller, layout.name, params, layout=layout)


def _check(args: argparse.Namespace, written: list[str]) -> int:
    from loader_model.experiments.design_check import DEFAULT_ENVELOPE, check_design, load_envelope
    from loader_model.experiments.design_check.report import check_csv, check_markdown, check_text
    from loader_model.io.export import check_output_path, write_atomically

    if args.output is not None:
        check_output_path(args.output, (".md", ".csv"), "--output")
    if args.jobs < 1:
        raise ValueError(f"--jobs {args.jobs}: allowed: an integer >= 1")
    if args.sampled_plants is not None and args.sampled_plants < 0:
        raise ValueError(f"--sampled-plants {args.sampled_plants}: allowed: an integer >= 0")
    envelope = DEFAULT_ENVELOPE if args.conditions is None else load_envelope(args.conditions)
    design = load_design(args.settings, args.controller, args.machine, args.params)
    check = check_design(
        design,
        envelope,
        jobs=args.jobs,
        progress=not args.no_progress,
        sampled_plants=args.sampled_plants,
        study=args.study,
    )
    print(check_text(check))
    if args.output is not None:
        text = check_csv(check) if args.output.endswith(".csv") else check_markdown(check)
        write_atomically(
            args.output,
            lambda path: path.write_text(text, encoding="utf-8", newline="\n"),
            (".md", ".csv"),
            "--output",
        )
        written.append(args.output)
        print(f"wrote {args.output}")
    return 0 if check.passed else EXIT_CHECK_FAILED
