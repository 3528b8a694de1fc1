"""``python -m derive --output generated [--machine NAME]``: derive the described machines.

The default machine (the skid-steer) is written into the output folder itself (the package
``loader_model_generated``), every other machine into ``<output>/<name>/``
(``loader_model_generated.<name>``). Without ``--machine``, every machine of ``derive/machines``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from derive.description import available_machines
from derive.generate import DEFAULT_MACHINE, generate
from derive.input_hash import input_hash
from derive.numeric_models import write_numeric_models


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m derive", description=__doc__)
    parser.add_argument("--output", type=Path, default=Path("generated"), help="output folder")
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
    machines = args.machine or list(available_machines())
    # the default machine first: its files sit beside the other machines' folders
    for machine in sorted(machines, key=lambda name: name != DEFAULT_MACHINE):
        folder = args.output if machine == DEFAULT_MACHINE else args.output / machine
        start = time.perf_counter()
        names = generate(folder, machine)
        elapsed = time.perf_counter() - start
        print(f"{machine}: wrote {len(names)} files to {folder}/ in {elapsed:.2f} s")
        if machine == DEFAULT_MACHINE and args.numeric_models:
            path = write_numeric_models(args.output, input_hash())
            print(f"wrote the default loader's linear models to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
