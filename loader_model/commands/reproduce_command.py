"""Reproduce the paper on the default loader: Table 1 (modal analysis) for both bucket loads, and
the linear model at the static equilibrium (Eq. 38-40)."""

from __future__ import annotations

import argparse

HELP = "reproduce the paper's results on the default loader"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    del parser  # no options yet


def run(args: argparse.Namespace) -> int:
    from loader_model.dynamics import LoaderDynamics
    from loader_model.modal import modal_analysis
    from loader_model.modal_report import format_modes
    from loader_model.parameters import LOAD_CASES, bucket_load, default_loader
    from loader_model.report import model_summary
    from loader_model.undamped import undamped_matrices

    del args
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
    return 0
