"""Arguments shared by subcommands: the machine, its parameter file, the bucket load, the worker
processes and the progress bar, each under one name and with one default on every command."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = [
    "DEFAULT_LOAD",
    "OutsideValidityError",
    "add_jobs_argument",
    "add_machine_argument",
    "add_model_arguments",
    "add_progress_argument",
    "machine_from_arguments",
    "model_from_arguments",
    "require_skid_steer",
]


class OutsideValidityError(ValueError):
    """A simulation stopped outside the model's range of validity (the command line's exit code
    3); the message names the time, the state, the bound and the files written up to the stop."""


#: The bucket load of every command that runs one load (the paper's nominal Table 6 drive).
DEFAULT_LOAD = "empty"


def add_model_arguments(parser: argparse.ArgumentParser, *, machine: bool = False) -> None:
    """Add ``--params FILE`` and ``--load empty|full|FILE``, and with ``machine``
    ``--machine NAME|FILE`` (the commands whose layers take any described machine)."""
    if machine:
        add_machine_argument(parser)
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="parameter file (TOML; for another machine than the skid-steer its flat file) "
        "(default: the shipped values of the machine)",
    )
    parser.add_argument(
        "--load",
        default=DEFAULT_LOAD,
        metavar="CASE",
        help="bucket load: 'empty' (340 kg), 'full' (770 kg) or a TOML file; for another "
        "machine a load case of its parameter file",
    )


def add_machine_argument(parser: argparse.ArgumentParser, note: str = "") -> None:
    """Add ``--machine NAME|FILE`` (default: the skid-steer of the paper)."""
    parser.add_argument(
        "--machine",
        metavar="NAME|FILE",
        default="skid_steer",
        help="a generated machine (skid_steer, compact_wheel_loader, ...) or its description "
        f"file (TOML){note}",
    )


def add_jobs_argument(parser: argparse.ArgumentParser, default: int | None, what: str) -> None:
    """Add ``--jobs N``, the number of worker processes (``default`` None: the number of cores)."""
    parser.add_argument(
        "--jobs",
        type=int,
        default=default,
        metavar="N",
        help=f"worker processes {what}"
        + (" (default: the number of cores)" if default is None else ""),
    )


def add_progress_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--no-progress`` (no progress bar on standard error)."""
    parser.add_argument(
        "--no-progress", action="store_true", help="no progress bar on standard error"
    )


def machine_from_arguments(args: argparse.Namespace) -> Any:
    """The :class:`loader_model.machines.MachineInfo` of ``--machine`` (ValueError if unknown)."""
    from loader_model.machines import machine

    return machine(getattr(args, "machine", "skid_steer"))


def layout_from_arguments(args: argparse.Namespace) -> Any:
    """The machine of ``--machine`` resolved once: its
    :class:`loader_model.plant.layout.PlantLayout` (ValueError if unknown), which the command
    hands to everything below it."""
    from loader_model.plant.layout import plant_layout

    return plant_layout(getattr(args, "machine", "skid_steer"))


def model_from_arguments(args: argparse.Namespace) -> Any:
    """Build the :class:`loader_model.vehicle.dynamics.LoaderDynamics` the arguments describe."""
    from loader_model.vehicle.dynamics import LoaderDynamics

    info = machine_from_arguments(args)
    return LoaderDynamics.from_parameters(args.params, args.load, machine=info.name)


def require_skid_steer(args: argparse.Namespace, reason: str) -> None:
    """Refuse ``--machine`` other than the skid-steer for a command built on it alone.

    Raises
    ------
    ValueError
        Naming ``--machine``, the value given, what is allowed and ``reason`` (the command
        line's one-line error, exit code 2); an unknown machine as
        :func:`machine_from_arguments` does.
    """
    if not machine_from_arguments(args).is_default:
        raise ValueError(f"--machine {args.machine!r}: allowed: skid_steer ({reason})")
