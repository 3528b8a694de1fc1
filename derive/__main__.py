"""``python -m derive [DESCRIPTION.toml] [--output DIR] [--machine NAME]``: derive machines.

Without a description file: the machines of ``derive/machines``. The default machine (the
skid-steer) is written into the output folder itself (the package ``loader_model_generated``),
every other machine into ``<output>/<name>/`` (``loader_model_generated.<name>``). Without
``--machine``, every machine of ``derive/machines``.

With a description file outside ``derive/machines`` (``path/to/<stem>.toml``): that machine,
into ``path/to/<stem>_generated/`` (or ``--output DIR``), the folder that the runtime's
``--machine path/to/<stem>.toml`` imports (``loader_model.machines.generated_folder``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from derive.description import DescriptionError, available_machines
from derive.generate import DEFAULT_MACHINE, generate
from derive.input_hash import input_hash
from derive.numeric_models import write_numeric_models


def _derive_file(description: Path, output: Path | None) -> int:
    """Derive one description file into ``output`` (default ``<stem>_generated/`` beside it)."""
    if description.suffix != ".toml" or not description.is_file():
        print(f"python -m derive: {description}: no such description file (.toml)", file=sys.stderr)
        return 2
    folder = output or description.with_name(description.stem + "_generated")
    start = time.perf_counter()
    try:
        names = generate(folder, str(description))
    except DescriptionError as error:
        print(f"python -m derive: {error}", file=sys.stderr)
        return 2
    elapsed = time.perf_counter() - start
    print(f"{description}: wrote {len(names)} files to {folder}/ in {elapsed:.2f} s")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m derive", description=__doc__)
    parser.add_argument(
        "description",
        nargs="?",
        type=Path,
        help="a machine description file outside derive/machines (default: derive/machines)",
    )
    parser.add_argument("--output", type=Path, default=None, help="output folder")
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
    if args.description is not None:
        if args.machine:
            parser.error("give either a description file or --machine, not both")
        return _derive_file(args.description, args.output)
    output = args.output or Path("generated")
    machines = args.machine or list(available_machines())
    # the default machine first: its files sit beside the other machines' folders
    for machine in sorted(machines, key=lambda name: name != DEFAULT_MACHINE):
        folder = output if machine == DEFAULT_MACHINE else output / machine
        start = time.perf_counter()
        names = generate(folder, machine)
        elapsed = time.perf_counter() - start
        print(f"{machine}: wrote {len(names)} files to {folder}/ in {elapsed:.2f} s")
        if machine == DEFAULT_MACHINE and args.numeric_models:
            path = write_numeric_models(output, input_hash())
            print(f"wrote the default loader's linear models to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
