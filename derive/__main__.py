"""``python -m derive [DESCRIPTION.toml] [--output DIR] [--machine NAME]``: derive machines.

The same command is installed as ``loader-model-derive``; either runs from any folder.

Without a description file: the machines of ``derive/machines``. The default machine (the
skid-steer) is written into the output folder itself (the package ``loader_model_generated``),
every other machine into ``<output>/<name>/`` (``loader_model_generated.<name>``). Without
``--machine``, every machine of ``derive/machines``.

With a description file (``path/to/<stem>.toml``): that machine, into the runtime's private
cache (``loader_model.machines.generated_folder``, named by the hash of the file and of the
deriving code), the only place from which ``--machine path/to/<stem>.toml`` imports it; with
``--output DIR``, into ``DIR`` instead (to read it; the runtime does not import it from there).

Nothing is derived into a symbolic link, a file or a folder holding anything derive did not
write; the package is renamed into place whole (``derive.install``).
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import tempfile
import time
from functools import partial
from pathlib import Path

from derive.description import DescriptionError, available_machines
from derive.description_checks import MAX_BYTES
from derive.install import OutputError
from loader_model import machine_packages

#: The console script of the derivation (pyproject.toml), the same as ``python -m derive``.
SCRIPT = "loader-model-derive"
#: The errors of a derivation that are the user's to fix (printed as one line, exit code 2).
_USER_ERRORS = (DescriptionError, OutputError, OSError, ValueError, RuntimeError)


def _derive_copy(description: Path, data: bytes, output: Path | None) -> Path:
    """Derive the bytes ``data`` of ``description`` (a private copy: the file may change
    meanwhile) into ``output`` or the runtime's cache; returns the folder."""
    from derive.generate import generate

    with tempfile.TemporaryDirectory(prefix="loader-model-description-") as scratch:
        copy = Path(scratch) / description.name
        copy.write_bytes(data)
        if output is not None:
            generate(output, str(copy))
            return output
        machine_packages.prepare_cache()
        folder = machine_packages.generated_folder(data)
        finish = partial(machine_packages.write_manifest, description=data)
        generate(folder, str(copy), finish=finish, mode=0o700)
        return folder


def _derive_file(description: Path, output: Path | None) -> int:
    """Derive one description file into ``output`` (default: the runtime's cache)."""
    if description.suffix != ".toml" or not description.is_file():
        print(f"python -m derive: {description}: no such description file (.toml)", file=sys.stderr)
        return 2
    start = time.perf_counter()
    try:
        data = description.read_bytes()
        if len(data) > MAX_BYTES:
            raise DescriptionError(description.name, "(file)", f"more than {MAX_BYTES} bytes")
        folder = _derive_copy(description, data, output)
    except _USER_ERRORS as error:
        print(f"python -m derive: {error}", file=sys.stderr)
        return 2
    elapsed = time.perf_counter() - start
    print(f"{description}: wrote its generated package to {folder}/ in {elapsed:.2f} s")
    if output is not None:
        print("(to read: the runtime imports a description's package only from its own cache)")
    return 0


def _prog() -> str:
    """The command's name as the user called it: ``loader-model-derive`` (the console script)
    or ``python -m derive``."""
    called = Path(sys.argv[0]).name if sys.argv else ""
    return SCRIPT if called == SCRIPT else "python -m derive"


def main(argv: list[str] | None = None) -> int:
    # the module notes as plain-text help, without reST markup
    parser = argparse.ArgumentParser(prog=_prog(), description=__doc__.replace("``", ""))
    parser.add_argument(
        "description",
        nargs="?",
        type=Path,
        help="a machine description file outside derive/machines (default: derive/machines)",
    )
    parser.add_argument(
        "--output",
        type=Path,
        default=None,
        help="output folder (default: generated/ in the working folder for the described "
        "machines, the runtime's cache for a description file)",
    )
    parser.add_argument(
        "--machine",
        choices=available_machines(),
        action="append",
        help="machine to derive (repeatable; default: every described machine)",
    )
    parser.add_argument(
        "--no-numeric-models",
        dest="numeric_models",
        action="store_false",
        help="skip the default loader's numeric linear models (written with the runtime)",
    )
    args = parser.parse_args(argv)
    if importlib.util.find_spec("sympy") is None:
        print(
            "python -m derive: needs SymPy; install the derive extra: "
            f"{machine_packages.derive_extra_command()}",
            file=sys.stderr,
        )
        return 2
    if args.description is not None:
        if args.machine:
            parser.error("give either a description file or --machine, not both")
        return _derive_file(args.description, args.output)
    from derive.generate import DEFAULT_MACHINE, generate
    from derive.input_hash import input_hash
    from derive.numeric_models import write_numeric_models

    output = args.output or Path("generated")
    machines = args.machine or list(available_machines())
    # the default machine first: its files sit beside the other machines' folders
    for machine in sorted(machines, key=lambda name: name != DEFAULT_MACHINE):
        folder = output if machine == DEFAULT_MACHINE else output / machine
        start = time.perf_counter()
        try:
            names = generate(folder, machine)
        except _USER_ERRORS as error:
            print(f"python -m derive: {error}", file=sys.stderr)
            return 2
        elapsed = time.perf_counter() - start
        print(f"{machine}: wrote {len(names)} files to {folder}/ in {elapsed:.2f} s")
        if machine == DEFAULT_MACHINE and args.numeric_models:
            path = write_numeric_models(output, input_hash())
            print(f"wrote the default loader's linear models to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
