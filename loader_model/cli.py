"""The ``loader-model`` command line: one subcommand per module in :mod:`loader_model.commands`.

Each command module exposes ``HELP`` (one line), ``add_arguments(parser)`` and ``run(args) -> int``,
and keeps its heavy imports inside ``run`` so that ``loader-model --help`` stays fast.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

#: Subcommand name -> module in ``loader_model.commands``.
COMMANDS: dict[str, str] = {
    "model": "loader_model.commands.model_command",
    "modes": "loader_model.commands.modes_command",
    "calibrate": "loader_model.commands.calibrate_command",
    "calibrate-table6": "loader_model.commands.calibrate_table6_command",
    "iso2631": "loader_model.commands.iso2631_command",
    "hydraulics": "loader_model.commands.hydraulics_command",
    "identify": "loader_model.commands.identify_command",
    "reproduce": "loader_model.commands.reproduce_command",
    "simulate": "loader_model.commands.simulate_command",
    "export-fmu": "loader_model.commands.export_fmu_command",
    "design": "loader_model.commands.design_command",
    "check-design": "loader_model.commands.check_design_command",
    "robustness": "loader_model.commands.robustness_command",
    "bound": "loader_model.commands.bound_command",
    "fidelity": "loader_model.commands.fidelity_command",
    "preview": "loader_model.commands.preview_command",
}


def build_parser() -> argparse.ArgumentParser:
    """Build the argument parser with every registered subcommand."""
    parser = argparse.ArgumentParser(
        prog="loader-model",
        description="Model, control and ride evaluation of a pump-controlled skid-steer loader.",
    )
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, module_name in COMMANDS.items():
        module = importlib.import_module(module_name)
        sub = subparsers.add_parser(name, help=module.HELP, description=module.__doc__)
        module.add_arguments(sub)
        sub.set_defaults(_run=module.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``loader-model`` command; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    from loader_model.io.interrupts import (
        Interrupted,
        command_interrupts,
        interrupt_message,
        requested,
    )

    def interrupted(error: BaseException) -> int:
        message, code = interrupt_message(error)  # one line: what stopped, what was kept
        print(f"loader-model {args.command}: {message}", file=sys.stderr)
        return code

    with command_interrupts():  # Ctrl-C and SIGTERM raise loader_model.io.interrupts.Interrupted
        try:
            return int(args._run(args))
        except KeyboardInterrupt as error:
            return interrupted(error)
        except BrokenPipeError:  # output piped into e.g. `head`, which closed early
            sys.stderr.close()
            return 0
        except Exception as error:
            number = requested()
            if number is not None:  # raised because of an interrupt (e.g. in CasADi)
                return interrupted(Interrupted(number))
            if isinstance(error, ValueError):
                print(f"loader-model {args.command}: error: {error}", file=sys.stderr)
                return 2
            if isinstance(error, OSError):  # backstop: the file checks should have said it first
                where = f"{error.filename}: " if error.filename else ""
                reason = error.strerror or error
                print(f"loader-model {args.command}: error: {where}{reason}", file=sys.stderr)
                return 2
            raise


if __name__ == "__main__":
    sys.exit(main())
