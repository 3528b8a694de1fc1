"""Arguments shared by subcommands: the machine, its parameter file and the bucket load."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_model_arguments", "machine_from_arguments", "model_from_arguments"]


def add_model_arguments(parser: argparse.ArgumentParser, *, machine: bool = False) -> None:
    """Add ``--params FILE`` and ``--load empty|full|FILE``, and with ``machine``
    ``--machine NAME|FILE`` (the commands whose layers take any described machine)."""
    if machine:
        parser.add_argument(
            "--machine",
            metavar="NAME|FILE",
            default="skid_steer",
            help="a generated machine (skid_steer, compact_wheel_loader, ...) or its description "
            "file (TOML); default: skid_steer",
        )
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="parameter file (TOML; for another machine than the skid-steer its flat file); "
        "default: the shipped values of the machine",
    )
    parser.add_argument(
        "--load",
        default="empty",
        metavar="CASE",
        help="bucket load: 'empty' (340 kg), 'full' (770 kg) or a TOML file (default: empty); "
        "for another machine a load case of its parameter file",
    )


def machine_from_arguments(args: argparse.Namespace) -> Any:
    """The :class:`loader_model.machines.MachineInfo` of ``--machine`` (ValueError if unknown)."""
    from loader_model.machines import machine

    return machine(getattr(args, "machine", "skid_steer"))


def model_from_arguments(args: argparse.Namespace) -> Any:
    """Build the :class:`loader_model.vehicle.dynamics.LoaderDynamics` the arguments describe."""
    from loader_model.vehicle.dynamics import LoaderDynamics

    info = machine_from_arguments(args)
    return LoaderDynamics.from_parameters(args.params, args.load, machine=info.name)
