"""Simulate the loader over a course with a ride controller and evaluate the seat (ISO 2631-1).

The plant (pump-controlled lift cylinders, tyres that may leave the ground) starts in its static
equilibrium and drives over the course at constant speed; the controller runs at 1 kHz. Prints
the ISO 2631-1 evaluation of the seat (x: Wd, z: Wk, pitch: We; Eq. 49, a_total Eq. 50 with
k = 0.4 for pitch) and the events of the run (tyre lift-off, end stops, cavitation, pump
saturation); writes the time series (CSV with units or NPZ) and a PNG of the seat accelerations.
A run that leaves the model's range of validity (tipping over, the boom past its end stops, the
machine in the air for over 0.5 s, the seat above 50 g: :mod:`loader_model.simulation.validity`)
stops there: no evaluation, an error naming the time, the state and the bound (exit code 3), and
the time series up to the stop written where --output asks.

Controllers: ``baseline`` (the pump holds the boom at its static command), ``passive`` (the
same, with the accumulator connected: the commercial ride control), ``virtual-accumulator``
(pressure regulation, p_A,ref = 0 on the high-passed p_A) and ``skyhook`` (Table 3 gains on the
semi-integrated accelerations; section 3.3), each the 1 kHz controller of
:mod:`loader_model.control` started at its fixed point.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

from loader_model.commands.common import (
    OutsideValidityError,
    add_model_arguments,
    layout_from_arguments,
)
from loader_model.commands.course_options import (
    add_course_arguments,
    check_drive,
    course_from_arguments,
)

if TYPE_CHECKING:
    from loader_model.simulation.result import Event
    from loader_model.simulation.validity_check import ModelValidityError

__all__ = ["CONTROLLERS", "GUIDE", "HELP", "add_arguments", "run"]

HELP = "simulate a course with a ride controller and evaluate the seat per ISO 2631-1"
GUIDE = "simulation.md"  # its page of the user guide (docs/guide/)

_SHOWN_EVENTS = 10

#: Controllers the command knows.
CONTROLLERS = ("baseline", "passive", "virtual-accumulator", "skyhook")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register the arguments of ``loader-model simulate``."""
    add_model_arguments(parser, machine=True)
    parser.add_argument(
        "--controller",
        default="baseline",
        metavar="NAME|FILE.toml",
        help=f"one of {', '.join(CONTROLLERS)}, or a controller settings file (the skyhook "
        "with its settings, e.g. written by loader-model design --output)",
    )
    parser.add_argument("--speed", type=float, default=9.0, metavar="KMH", help="speed in km/h")
    add_course_arguments(parser)
    parser.add_argument(
        "--duration",
        type=float,
        default=None,
        metavar="S",
        help="simulated time in s (default: the course, 200 m of an ISO 8608 road)",
    )
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="seed of the random roads")
    parser.add_argument(
        "--envelope",
        choices=("tandem-cam", "rigid"),
        default="tandem-cam",
        help="how the tyres envelop the road: tandem elliptical cams per axle from the static "
        "tyre deflection or rigid discs of each axle's free tyre radius (the parameter set's "
        "tyres: 0.42 m on the shipped machines)",
    )
    parser.add_argument(
        "--substeps",
        type=int,
        default=None,
        metavar="N",
        help="ROS2 integration steps per 1 ms controller period, 1-64 (default: 4, within 0.3 %% "
        "of the CVODES reference's a_total on the paper course)",
    )
    parser.add_argument(
        "--output",
        metavar="FILE",
        default=None,
        help="write the time series to FILE.csv or FILE.npz",
    )
    parser.add_argument(
        "--compare",
        action="store_true",
        help="run the four controllers (the skyhook with --controller FILE.toml's settings when "
        "given) and print a_total of each and its change against the baseline",
    )
    parser.add_argument(
        "--plot",
        metavar="FILE.png",
        default=None,
        help="seat-acceleration figure (default: beside --output, with suffix .png)",
    )


def run(args: argparse.Namespace) -> int:
    """Run the simulation, print the evaluation and write the files. Returns 0.

    A run that leaves the model's range of validity prints its events, writes its time series
    up to the violation and raises ValueError naming the time, the state, the bound and the
    files (exit code 3): no ISO 2631 evaluation of it.
    """
    from loader_model.io.export import check_output_path
    from loader_model.iso2631 import format_evaluation
    from loader_model.simulation.result import RESULT_SUFFIXES
    from loader_model.simulation.scenario import resolve_scenario
    from loader_model.simulation.seat_plot import PLOT_SUFFIXES, plot_seat
    from loader_model.simulation.simulator import ModelValidityError, course_input, simulate

    plot = args.plot
    if args.output is not None:
        check_output_path(args.output, RESULT_SUFFIXES, "--output")
        plot = plot or str(Path(args.output).with_suffix(".png"))
    if plot is not None:
        check_output_path(plot, PLOT_SUFFIXES, "--plot")
    if args.duration is not None and not 0.0 < args.duration <= 3600.0:
        raise ValueError(f"--duration must be in (0, 3600] s; got {args.duration!r}")
    if not 0.0 < args.speed <= 40.0:
        raise ValueError(f"--speed must be in (0, 40] km/h; got {args.speed!r}")
    if args.seed < 0:
        raise ValueError(f"--seed must be >= 0; got {args.seed}")
    if args.substeps is not None and not 1 <= args.substeps <= 64:
        raise ValueError(f"--substeps must be an integer from 1 to 64; got {args.substeps}")
    settings_file = None
    if args.controller not in CONTROLLERS:
        if not args.controller.endswith(".toml"):
            raise ValueError(
                f"--controller {args.controller!r}: allowed: {', '.join(CONTROLLERS)} or a "
                "controller settings file FILE.toml"
            )
        from loader_model.control.settings import load_settings

        settings_file = load_settings(args.controller)
    law = "skyhook" if settings_file is not None else args.controller
    layout = layout_from_arguments(args)
    machine = layout.name
    course = course_from_arguments(args)
    if args.duration is None:
        check_drive(course, args.speed)
    if args.compare:
        return _compare(args, layout, course, settings_file)
    scenario = resolve_scenario(
        args.params,
        args.load,
        controller=law,
        settings=settings_file,
        envelope=args.envelope,
        machine=layout,
    )
    title = f"{course.name}; {args.controller} controller, load {args.load}, {args.envelope} tyres"
    if machine != "skid_steer":
        title = f"{machine}: {title}"
    try:
        steps = {} if args.substeps is None else {"substeps": args.substeps}
        result = simulate(
            course_input(course, scenario), scenario, duration_s=args.duration, **steps
        )
    except ModelValidityError as error:  # no comfort figure for it: the evidence, then the error
        raise OutsideValidityError(_stopped(error, args.output, plot, title)) from None
    print(format_evaluation(result.seat_evaluation(), title=title))
    print(
        f"simulated {result.time_s.size * result.metadata['period_s']:.3f} s in "
        f"{result.metadata['wall_time_s']:.3f} s (real-time factor "
        f"{result.metadata['real_time_factor']:.0f}, {result.metadata['backend']})"
    )
    if "ride_control" in result.metadata:  # below the settings' ride_control_min_speed
        print(f"ride control: {result.metadata['ride_control']}; the run is the baseline's")
    _print_limits(result, scenario.plant)
    _print_events(result.events)
    if args.output is not None:
        print(f"wrote {result.write(args.output)}")
    if plot is not None:
        print(f"wrote {plot_seat(result, plot, title)}")
    return 0


def _compare(args: argparse.Namespace, layout: Any, course: object, settings: object) -> int:
    """Print the four controllers' a_total over the course (``--compare``). Returns 0."""
    from loader_model.simulation.machine_comparison import compare_controllers, format_comparison

    rows = compare_controllers(
        layout,
        args.params,
        args.load,
        course=course,
        settings=settings,
        substeps=args.substeps,
    )
    title = f"{layout.name}: {getattr(course, 'name', '')}; load {args.load}"
    print(format_comparison(rows, title))
    return 0


def _print_events(events: tuple[Event, ...]) -> None:
    """Print the count of events per kind, the first few, and always the stop outside the
    model's validity and a persistent oscillation (what ends or judges the run)."""
    kinds = sorted({event.kind for event in events})
    counts = ", ".join(f"{sum(e.kind == kind for e in events)} {kind}" for kind in kinds)
    print(f"events: {len(events)}" + (f" ({counts})" if counts else ""))
    shown = list(events[:_SHOWN_EVENTS])
    shown += [e for e in events[_SHOWN_EVENTS:] if e.kind in ("validity", "persistent_oscillation")]
    for event in shown:
        print(f"  {event.describe()}")
    if len(events) > len(shown):
        print(f"  ... {len(events) - len(shown)} more (all in the result's events)")


def _print_limits(result, plant) -> None:
    """Print the share of the run the pump (a valve's spool) spends at its limits, and how the
    run ends."""
    from loader_model.simulation.settling import limit_duty, settle_measure

    duty = limit_duty(result.columns, plant.command_limit(), plant.rate_limit())
    if plant.layout.circuit == "valve":
        print(
            f"valve at its limits: spool command at its stroke {duty.command:.1%} of the run, "
            f"spool rate at its limit {duty.rate:.1%}"
        )
    else:
        print(
            f"pump at its limits: command at V_p,max {duty.command:.1%} of the run, displacement "
            f"rate at its limit {duty.rate:.1%}"
        )
    settle = settle_measure(result.time_s, result.columns)
    if settle.judged:
        print(
            f"after the road ({settle.settle_s:.1f} s from {settle.excitation_end_s:.2f} s): "
            f"pitch acceleration {settle.tail_rms:.3f} rad/s² r.m.s. in the last second, "
            f"{settle.decay_ratio:.2f} of the second before"
            + (" (persistent oscillation)" if settle.persistent else "")
        )


def _stopped(error: ModelValidityError, output: str | None, plot: str | None, title: str) -> str:
    """For a run stopped outside the model's range of validity: print its events, write its time
    series and figure up to the stop where asked, and return the error message naming them."""
    from loader_model.simulation.seat_plot import plot_seat

    result = error.result
    _print_events(result.events)
    written = [] if output is None else [str(result.write(output))]
    written += [] if plot is None else [str(plot_seat(result, plot, title))]
    for path in written:
        print(f"wrote {path}")
    where = (
        f"wrote the run up to it: {', '.join(written)}"
        if written
        else "no time series written (give --output FILE.csv or FILE.npz to keep it)"
    )
    return f"{error}; no ISO 2631 evaluation of a run outside the model; {where}"
