"""The ``loader-model`` command line: one subcommand per module in :mod:`loader_model.commands`.

Each command module exposes ``HELP`` (one line), ``GUIDE`` (its page of the user guide),
``add_arguments(parser)`` and ``run(args) -> int``, and keeps its heavy imports inside ``run`` so
that ``loader-model --help`` stays fast. The help is plain text: the modules' docstrings lose
their reST markup, and every option's default is shown once, as "(default: X)".

Exit codes (the command page of the guide lists them): 0 success; 2 a usage error or bad input,
with a one-line message; 3 a simulation stopped outside the model's range of validity; 4 a
design that fails its check (check-design, design); 128 + N an interrupt by signal N (130 Ctrl-C,
143 SIGTERM); 1 an unexpected failure.
"""

from __future__ import annotations

import argparse
import difflib
import importlib
import re
import sys
import textwrap
from collections.abc import Sequence
from typing import Any, NoReturn

from loader_model import __version__
from loader_model.commands.common import OutsideValidityError

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

#: Exit code of a usage error or of bad input (argparse's own).
EXIT_USAGE = 2
#: Exit code of a simulation stopped outside the model's range of validity.
EXIT_OUTSIDE_VALIDITY = 3

_ROLE = re.compile(r":[a-z]+:`~?([^`<]*?)(?:\s*<[^>]*>)?`")  # :mod:`x`, :func:`~a.b`, :ref:`t <x>`
_LITERAL = re.compile(r"``([^`]*)``|`([^`]*)`")


def plain_text(text: str) -> str:
    """``text`` without reST markup: roles become their target's name, literals their text."""

    def role(match: re.Match[str]) -> str:
        target = match.group(1)
        return target.rsplit(".", 1)[-1] if match.group(0).count("~") else target

    text = _ROLE.sub(role, text)
    return _LITERAL.sub(lambda match: match.group(1) or match.group(2) or "", text)


class HelpFormatter(argparse.HelpFormatter):
    """Plain-text help: paragraphs of a description kept and refilled, markup removed, and every
    option's default shown once as "(default: X)" (left to the help text when it says it)."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        paragraphs = [" ".join(part.split()) for part in plain_text(text).split("\n\n")]
        return "\n\n".join(
            textwrap.fill(part, width, initial_indent=indent, subsequent_indent=indent)
            for part in paragraphs
            if part
        )

    def _get_help_string(self, action: argparse.Action) -> str:
        text = plain_text(action.help or "")
        default = action.default
        shown = not (default is None or isinstance(default, bool) or default == argparse.SUPPRESS)
        shown = shown and default != []
        if not action.option_strings or not shown or "(default: " in text:
            return text
        shown = f"{default:g}" if isinstance(default, float) else str(default)
        return f"{text} (default: {shown.replace('%', '%%')})"


class Parser(argparse.ArgumentParser):
    """An argument parser whose help is plain text and whose misspelt options are reported by
    the (sub)command that was given them, with its own usage and the closest option."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def parse_known_args(self, args: Any = None, namespace: Any = None) -> Any:
        namespace, extras = super().parse_known_args(args, namespace)
        if extras and getattr(namespace, "_extras_parser", None) is None:
            namespace._extras_parser = self  # the innermost (sub)command that saw them
        return namespace, extras

    def unrecognized(self, extras: list[str]) -> NoReturn:
        """Exit with this parser's usage, the unrecognised arguments and the closest option."""
        options = [name for action in self._actions for name in action.option_strings]
        hint = ""
        for extra in extras:
            close = difflib.get_close_matches(extra.split("=", 1)[0], options, n=1, cutoff=0.6)
            if extra.startswith("-") and close:
                hint = f" (did you mean {close[0]}?)"
                break
        self.error(f"unrecognized arguments: {' '.join(extras)}{hint}")


def build_parser() -> Parser:
    """Build the argument parser with every registered subcommand."""
    parser = Parser(
        prog="loader-model",
        description="Model, control and ride evaluation of a pump-controlled skid-steer loader "
        "(Williamson, Lee and Ivantysynova, International Journal of Fluid Power, 2009).",
        epilog="'loader-model COMMAND --help' describes a command; the guide's page "
        "docs/guide/commands.md lists them all, their options and the exit codes.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, module_name in COMMANDS.items():
        module = importlib.import_module(module_name)
        sub = subparsers.add_parser(
            name,
            help=module.HELP,
            description=module.__doc__,
            epilog=f"Guide: docs/guide/{module.GUIDE}; every command: docs/guide/commands.md.",
        )
        module.add_arguments(sub)
        sub.set_defaults(_run=module.run)
    return parser


def _outside_validity(error: BaseException) -> bool:
    """Whether ``error`` says a simulation left the model's range of validity (the simulator's
    module is only looked at when it was imported: otherwise no run raised it)."""
    if isinstance(error, OutsideValidityError):
        return True
    module = sys.modules.get("loader_model.simulation.validity_check")
    return module is not None and isinstance(error, module.ModelValidityError)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``loader-model`` command; returns the process exit code."""
    parser = build_parser()
    args, extras = parser.parse_known_args(argv)
    if extras:
        (getattr(args, "_extras_parser", None) or parser).unrecognized(extras)
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
            if _outside_validity(error):
                print(f"loader-model {args.command}: error: {error}", file=sys.stderr)
                return EXIT_OUTSIDE_VALIDITY
            if isinstance(error, ValueError):
                print(f"loader-model {args.command}: error: {error}", file=sys.stderr)
                return EXIT_USAGE
            if isinstance(error, OSError):  # backstop: the file checks should have said it first
                where = f"{error.filename}: " if error.filename else ""
                reason = error.strerror or error
                print(f"loader-model {args.command}: error: {where}{reason}", file=sys.stderr)
                return EXIT_USAGE
            raise


if __name__ == "__main__":
    sys.exit(main())
