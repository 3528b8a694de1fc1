"""Print the model at its static equilibrium: loads, M, K, linear modes; export the linear model."""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_model_arguments, model_from_arguments

HELP = "print the model at the static equilibrium and export its linear model"
GUIDE = "model.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser, machine=True)
    parser.add_argument(
        "--export",
        metavar="FILE",
        help="write A, B, E, C, D_u, D_w and the signal names to FILE.npz or FILE.mat",
    )


def run(args: argparse.Namespace) -> int:
    from loader_model.io.export import ARRAY_SUFFIXES, check_output_path
    from loader_model.vehicle.summary import model_summary

    if args.export is not None:  # refuse a bad path (also '') before any work
        check_output_path(args.export, ARRAY_SUFFIXES, "--export")
    model = model_from_arguments(args)
    print(model_summary(model))
    if args.export is not None:
        path = model.linearise().save(args.export)
        print(f"\nwrote the linear model to {path}")
    return 0
