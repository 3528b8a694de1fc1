"""Modal analysis of a loader (Eq. 27-29) side by side with the paper's Table 1."""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_model_arguments

HELP = "undamped modes of a loader side by side with the paper's Table 1"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument(
        "--no-gravity",
        action="store_true",
        help="drop the geometric stiffness of gravity and static loads, as Eq. 33-34 do",
    )


def run(args: argparse.Namespace) -> int:
    from loader_model.modal.modes import modal_analysis
    from loader_model.modal.report import format_modes
    from loader_model.modal.undamped import undamped_matrices
    from loader_model.vehicle.statics import resolve_machine

    loader, load = resolve_machine(args.params, args.load)
    matrices = undamped_matrices(loader, load, gravity_stiffness=not args.no_gravity)
    result = modal_analysis(matrices.mass, matrices.stiffness)
    title = f"{args.params or 'default loader'}, bucket load {args.load} ({load.mass:g} kg)"
    print(format_modes(title, matrices, result))
    return 0
