"""Arguments shared by subcommands: the loader parameter file and the bucket load."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_model_arguments", "model_from_arguments"]


def add_model_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--params FILE`` and ``--load empty|full|FILE``."""
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="loader parameter file (TOML); default: the shipped default loader",
    )
    parser.add_argument(
        "--load",
        default="empty",
        metavar="CASE",
        help="bucket load: 'empty' (340 kg), 'full' (770 kg) or a TOML file (default: empty)",
    )


def model_from_arguments(args: argparse.Namespace) -> Any:
    """Build the :class:`loader_model.vehicle.dynamics.LoaderDynamics` the arguments describe."""
    from loader_model.vehicle.dynamics import LoaderDynamics

    return LoaderDynamics.from_parameters(args.params, args.load)
