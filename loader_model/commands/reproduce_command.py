"""Reproduce the paper on the default loader: the model at its static equilibrium."""

from __future__ import annotations

import argparse

HELP = "reproduce the paper's results on the default loader"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    del parser  # no options yet


def run(args: argparse.Namespace) -> int:
    from loader_model.dynamics import LoaderDynamics
    from loader_model.report import model_summary

    del args
    for case in ("empty", "full"):
        print(f"=== default loader, {case} bucket ===")
        print(model_summary(LoaderDynamics.from_parameters(None, case)))
        print()
    return 0
