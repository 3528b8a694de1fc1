"""Calibrate a loader's least-known parameters so that its modes reproduce Table 1.

Fits tyre stiffnesses (k_x, k_Ay, k_By), the chassis and boom inertias and the piston-side dead
volume within physical bounds (loader_model.modal.table1.FREE_PARAMETERS), on the generated
model, reading Table 1's columns as M·φ (item 7 of the errata page, docs/guide/errata.md).
Writes the calibrated parameter file only if every frequency is within 1 % and every MAC at least 0.99.
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import (
    add_machine_argument,
    add_model_arguments,
    require_skid_steer,
)

HELP = "fit the least-known parameters to the paper's Table 1 and write a parameter file"
GUIDE = "parameters.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_machine_argument(parser, note=" (the skid-steer only: Table 1 was measured on it)")
    add_model_arguments(parser)
    parser.add_argument("--output", metavar="FILE", help="write the calibrated parameters (TOML)")


def run(args: argparse.Namespace) -> int:
    from loader_model.io.export import check_output_path
    from loader_model.modal.modes import modal_analysis
    from loader_model.modal.report import format_modes
    from loader_model.modal.table1 import FREE_PARAMETERS, calibrate_to_table_1
    from loader_model.modal.undamped import undamped_matrices
    from loader_model.parameters.sets import PARAMETER_SUFFIXES, save
    from loader_model.vehicle.statics import resolve_machine

    require_skid_steer(
        args,
        "the fit targets the paper's Table 1, measured on the skid-steer; "
        "`loader-model modes --machine NAME` gives any machine's modes",
    )
    if args.output is not None:  # refuse a bad output path before the long fit
        check_output_path(args.output, PARAMETER_SUFFIXES, "--output")
    loader, load = resolve_machine(args.params, args.load)
    result, calibrated = calibrate_to_table_1(loader, load)
    print(f"Calibration to Table 1 ({result.n_evaluations} model evaluations)")
    for name, value in result.parameters.items():
        item = FREE_PARAMETERS[name]
        low, high = item.bounds
        print(f"  {name:<5} = {value:12.6g} {item.unit:<7} bounds [{low:g}, {high:g}]")
    if result.at_bounds:
        print(f"  at a bound: {', '.join(result.at_bounds)}")
    matrices = undamped_matrices(calibrated, load)
    print()
    print(
        format_modes(
            "Calibrated loader", matrices, modal_analysis(matrices.mass, matrices.stiffness)
        )
    )
    if not result.meets_targets:
        raise ValueError(
            "the calibration misses a target (1 % frequency, MAC 0.99); nothing written"
        )
    if args.output is not None:
        save(calibrated, args.output)
        print(f"\nwrote {args.output}")
    return 0
