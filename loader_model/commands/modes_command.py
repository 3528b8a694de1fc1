"""Modal analysis of a machine (Eq. 27-29); the skid-steer's side by side with the paper's Table 1."""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_model_arguments, machine_from_arguments

HELP = "undamped modes of a loader side by side with the paper's Table 1"
GUIDE = "model.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser, machine=True)
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

    info = machine_from_arguments(args)
    if not info.is_default:
        return _run_machine(args, info)
    loader, load = resolve_machine(args.params, args.load)
    matrices = undamped_matrices(loader, load, gravity_stiffness=not args.no_gravity)
    result = modal_analysis(matrices.mass, matrices.stiffness)
    title = f"{args.params or 'default loader'}, bucket load {args.load} ({load.mass:g} kg)"
    print(format_modes(title, matrices, result))
    return 0


def _run_machine(args: argparse.Namespace, info) -> int:
    """Modes of another described machine (no paper reference)."""
    from loader_model.modal.modes import modal_analysis
    from loader_model.modal.report import format_machine_modes
    from loader_model.modal.undamped import machine_undamped_matrices

    matrices = machine_undamped_matrices(
        info, args.params, args.load, gravity_stiffness=not args.no_gravity
    )
    result = modal_analysis(matrices.mass, matrices.stiffness)
    title = f"{info.title} ({args.params or 'shipped values'}), bucket load {args.load}"
    units = [info.coordinate_unit(name) for name in matrices.coordinate_names]
    print(format_machine_modes(title, matrices, result, units))
    return 0
