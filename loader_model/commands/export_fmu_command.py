"""Export the nonlinear plant as an FMI 2.0 Model Exchange FMU (linux64; needs a C compiler).

Inputs: the pump displacement command V_p_ref and the road under each axle with its rates (and the
disturbance forces at H); outputs: seat and chassis accelerometers, pressures, boom angle, chassis
motion, tyre loads; every plant parameter is an FMU parameter with unit and description; the
states start at the static equilibrium. ``--controller`` closes the loop inside the FMU with one
of the project's discrete 1 kHz controllers, kept discrete and sampled by FMI time events (not a
continuous equivalent; see :mod:`loader_model.fmu.closed_loop`): the pump command is then an
output and the controller's settings (Table 3, the shipped defaults) are FMU parameters.
``--machine`` exports another described machine with the names and sizes of its plant layout;
its controllers read the same named sensors, with ‖p_A‖∞ of
:func:`~loader_model.plant.machine_parameters.pressure_norm` (1.5 × the load's static piston
pressure), and ``--settings`` gives a designed settings file (``design --output``).
"""

from __future__ import annotations

import argparse
import time
from typing import TYPE_CHECKING, Any

from loader_model.commands.common import add_model_arguments, layout_from_arguments

if TYPE_CHECKING:
    from loader_model.control.settings import ControllerSettings

HELP = "export the nonlinear plant as an FMI 2.0 Model Exchange FMU"
GUIDE = "fmu.md"  # its page of the user guide (docs/guide/)

#: ``--controller`` choice -> controller Function name (None: the plant alone).
CONTROLLER_CHOICES = {
    "none": None,
    "baseline": "baseline",
    "skyhook": "skyhook",
    "virtual-accumulator": "virtual_accumulator",
}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--machine``, ``--params``, ``--load``, ``--controller``, ``--settings``,
    ``--no-sources`` and ``OUTPUT.fmu``."""
    add_model_arguments(parser, machine=True)
    parser.add_argument(
        "--controller",
        choices=list(CONTROLLER_CHOICES),
        default="none",
        help="close the loop inside the FMU with this 1 kHz controller (default: none, the plant)",
    )
    parser.add_argument(
        "--settings",
        metavar="FILE.toml",
        default=None,
        help="controller settings file (default: the shipped Table 3 settings)",
    )
    parser.add_argument(
        "--no-sources",
        action="store_true",
        help="leave the C sources out of the FMU (binary only)",
    )
    parser.add_argument("output", metavar="OUTPUT.fmu", help="FMU file to write")


def run(args: argparse.Namespace) -> int:
    """Check the arguments, build the FMU in a temporary folder and move it to OUTPUT."""
    from loader_model.fmu.build import export_plant_fmu, find_compiler
    from loader_model.io.export import check_output_path

    check_output_path(args.output, (".fmu",), "FMU")  # before any work
    find_compiler()  # a clear error before the parameter files are read
    if args.settings is not None and CONTROLLER_CHOICES[args.controller] in (None, "baseline"):
        raise ValueError(
            f"--settings {args.settings}: --controller {args.controller} reads no settings "
            "(give --controller skyhook or virtual-accumulator)"
        )
    layout = layout_from_arguments(args)
    info = layout.machine
    if not info.is_default:
        return _run_machine(args, layout)
    from loader_model.plant.plant_parameters import plant_parameter_vector
    from loader_model.vehicle.statics import resolve_machine

    loader, load = resolve_machine(args.params, args.load)
    params = plant_parameter_vector(loader, load)
    controller = CONTROLLER_CHOICES[args.controller]
    settings = None
    if controller is not None:
        from loader_model.control.settings import settings_vector_for_plant

        settings = settings_vector_for_plant(_settings(args), params, load.pressure_normalisation)
    started = time.perf_counter()
    path = export_plant_fmu(
        args.output,
        params,
        controller=controller,
        settings=settings,
        include_sources=not args.no_sources,
    )
    seconds = time.perf_counter() - started
    size_kb = path.stat().st_size / 1024
    what = "plant" if controller is None else f"plant + {args.controller} controller"
    print(
        f"wrote {path}: {what}, FMI 2.0 Model Exchange, linux64, {size_kb:.0f} kB, "
        f"built in {seconds:.1f} s"
    )
    return 0


def _settings(args: argparse.Namespace) -> ControllerSettings:
    """The ``--settings`` file, else the shipped Table 3 settings."""
    from loader_model.control.settings import default_settings, load_settings

    return default_settings() if args.settings is None else load_settings(args.settings)


def _run_machine(args: argparse.Namespace, layout: Any) -> int:
    """The FMU of another described machine (its flat parameter file and load case)."""
    from loader_model.fmu.build import export_plant_fmu
    from loader_model.plant.scenario import resolve_plant

    controller = CONTROLLER_CHOICES[args.controller]
    plant = resolve_plant(args.params, args.load, machine=layout)
    settings = None
    if controller is not None:
        from loader_model.control.settings import settings_vector_for_plant
        from loader_model.plant.machine_parameters import pressure_norm

        settings = settings_vector_for_plant(
            _settings(args),
            plant.params,
            pressure_norm(plant.output("p_A")),
            hold_command=plant.u0,
            layout=layout,
        )
    started = time.perf_counter()
    path = export_plant_fmu(
        args.output,
        plant.params,
        controller=controller,
        settings=settings,
        include_sources=not args.no_sources,
        machine=layout,
    )
    seconds = time.perf_counter() - started
    size_kb = path.stat().st_size / 1024
    what = "plant" if controller is None else f"plant + {args.controller} controller"
    print(
        f"wrote {path}: {layout.name} {what}, FMI 2.0 Model Exchange, linux64, {size_kb:.0f} kB, "
        f"built in {seconds:.1f} s"
    )
    return 0
