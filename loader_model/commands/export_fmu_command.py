"""Export the nonlinear plant as an FMI 2.0 Model Exchange FMU (linux64; needs a C compiler).

Inputs: the pump displacement command V_p_ref and the road under each axle with its rates (and the
disturbance forces at H); outputs: seat and chassis accelerometers, pressures, boom angle, chassis
motion, tyre loads; every plant parameter is an FMU parameter with unit and description; the
states start at the static equilibrium. Only the plant is exported (``--controller none``): the
project's controllers are discrete at 1 kHz, which a Model Exchange FMU would have to carry as
time events, and that is not built yet.
"""

from __future__ import annotations

import argparse
import time

from loader_model.commands.common import add_model_arguments

HELP = "export the nonlinear plant as an FMI 2.0 Model Exchange FMU"

#: Accepted by ``--controller``; only ``none`` is built (see the module docstring).
CONTROLLER_CHOICES = ("none", "baseline", "skyhook", "virtual-accumulator")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--params``, ``--load``, ``--controller``, ``--no-sources`` and ``OUTPUT.fmu``."""
    add_model_arguments(parser)
    parser.add_argument(
        "--controller",
        choices=CONTROLLER_CHOICES,
        default="none",
        help="controller inside the FMU; only 'none' (the plant alone) is built (default: none)",
    )
    parser.add_argument(
        "--no-sources",
        action="store_true",
        help="leave the C sources out of the FMU (binary only)",
    )
    parser.add_argument("output", metavar="OUTPUT.fmu", help="FMU file to write")


def run(args: argparse.Namespace) -> int:
    """Check the arguments, build the FMU in a temporary folder and move it to OUTPUT."""
    from loader_model.export import check_output_path
    from loader_model.fmu.build import export_plant_fmu, find_compiler

    check_output_path(args.output, (".fmu",), "FMU")  # before any work
    if args.controller != "none":
        raise ValueError(
            f"--controller {args.controller}: a closed-loop FMU is not built yet (the controllers "
            "are discrete at 1 kHz and would need time events in the Model Exchange FMU); "
            "allowed: none (the plant alone, to be closed in the importing tool)"
        )
    find_compiler()  # a clear error before the parameter files are read
    from loader_model.plant.plant_parameters import plant_parameter_vector

    params = plant_parameter_vector(args.params, args.load)
    started = time.perf_counter()
    path = export_plant_fmu(args.output, params, include_sources=not args.no_sources)
    seconds = time.perf_counter() - started
    size_kb = path.stat().st_size / 1024
    print(
        f"wrote {path} (FMI 2.0 Model Exchange, linux64, {size_kb:.0f} kB, built in {seconds:.1f} s)"
    )
    return 0
