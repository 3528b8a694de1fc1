"""LQ control with road preview: a_total against the preview length beside the non-causal bound.

Designs the preview LQ law on the linear bound's plant and cost (:mod:`loader_model.bound.preview`:
full-state feedback plus feedforward on the road previewed L metres ahead of the front axle, the
rear axle's road known a wheelbase further), evaluates it on the linear plant for each preview
length, optionally runs it in the 1 kHz simulation (``--simulate``: the controller holds the
course table and corrects the design with a Kalman filter on the plant's outputs,
:mod:`loader_model.bound.preview_report`), and prints a_total beside the non-causal LQ bound and
the simulated baseline and refined skyhook. With ``--output DIR`` writes ``preview.csv`` and
``preview.png``.

``--machine NAME|FILE`` and ``--params FILE`` choose the machine and its parameter file, as for
``simulate``: any described machine with two axles whose boom is driven by the pump's closed
circuit (a machine with a valve-controlled circuit is refused). On another machine than the
skid-steer the simulated reference beside the baseline is Table 3's skyhook (the refined gains
are the skid-steer's).
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import (
    add_model_arguments,
    add_progress_argument,
    layout_from_arguments,
)

__all__ = ["GUIDE", "HELP", "add_arguments", "run"]

HELP = "LQ control with road preview: a_total against the preview length beside the bound"
GUIDE = "bound.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register the arguments of ``loader-model preview``."""
    add_model_arguments(parser, machine=True)
    parser.add_argument(
        "--speed", type=float, default=9.0, metavar="KMH", help="speed in km/h: 9 or 18"
    )
    parser.add_argument(
        "--preview",
        default="0,0.5,1,2,4",
        metavar="LIST",
        help="comma-separated preview lengths in m",
    )
    parser.add_argument(
        "--simulate", action="store_true", help="also run each law in the 1 kHz simulation"
    )
    parser.add_argument(
        "--output", metavar="DIR", default=None, help="write preview.csv and preview.png into DIR"
    )
    add_progress_argument(parser)


def _lengths(text: str) -> list[float]:
    try:
        values = [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise ValueError(f"--preview {text!r}: a comma-separated list of lengths in m") from None
    if not values:
        raise ValueError(f"--preview {text!r}: give at least one length in m")
    return values


def run(args: argparse.Namespace) -> int:
    """Run the sweep, print it and write the files; an interrupt says what was written."""
    from loader_model.io.interrupts import files_note, keeping

    written: list[str] = []
    wanted = (None,) if args.output is None else (f"{args.output}/preview.csv",)
    with keeping(lambda: files_note(wanted, written)):
        return _run(args, written)


def _run(args: argparse.Namespace, written: list[str]) -> int:
    from pathlib import Path

    import numpy as np
    from tqdm import tqdm

    from loader_model.bound.preview import front_columns
    from loader_model.bound.problem import require_pump_circuit

    layout = layout_from_arguments(args)
    try:
        require_pump_circuit(layout, "the preview law")
        front_columns(layout)  # two axles
    except ValueError as error:
        raise ValueError(f"--machine {args.machine!r}: {error}") from None
    if args.speed not in (9.0, 18.0):
        raise ValueError(f"--speed {args.speed:g}: allowed: 9 or 18 km/h (the paper's course)")
    lengths = _lengths(args.preview)
    output = None if args.output is None else Path(args.output)
    if output is not None and output.exists() and not output.is_dir():
        raise ValueError(f"--output {args.output!r}: not a folder")
    from loader_model.bound.linear import solve_linear_bound
    from loader_model.bound.preview import evaluate_preview, preview_design, preview_intervals
    from loader_model.bound.preview_report import (
        PreviewSweep,
        plot_sweep,
        simulate_preview,
        write_csv,
    )
    from loader_model.bound.problem import bound_problem
    from loader_model.experiments.designed_gains import refined_settings
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import ride_scenario
    from loader_model.simulation.simulator import course_input, simulate
    from loader_model.simulation.validity_check import SimulationError

    plant = resolve_plant(args.params, args.load, PlantOptions(), machine=layout)
    course = paper_course(args.speed)
    road = course_input(course, plant)
    problem = bound_problem(plant, road)
    for length in lengths:  # bad lengths fail before the long loop
        try:
            preview_intervals(problem, length, road.speed_m_s, road.wheelbase_m)
        except ValueError as error:
            raise ValueError(f"--preview: {error}") from None
    references = {"baseline": ride_scenario(plant, "baseline")}
    if layout.machine.is_default:
        references["skyhook-refined"] = ride_scenario(plant, "skyhook", refined_settings())
    else:
        references["skyhook"] = ride_scenario(plant, "skyhook")
    steps = 2 + len(lengths) * (2 if args.simulate else 1) + len(references)
    linear, simulated, peaks, totals = [], [], [], {}
    with tqdm(total=steps, desc="preview", unit="step", disable=args.no_progress) as bar:
        bar.set_postfix_str("design")
        design = preview_design(problem)
        bar.update()
        bound = solve_linear_bound(problem).a_total_m_s2
        plain = preview_intervals(
            problem, 0.0, road.speed_m_s, road.wheelbase_m, wheelbase_preview=False
        )
        lqr = evaluate_preview(design, problem, plain).a_total_m_s2
        bar.update()
        for length in lengths:
            bar.set_postfix_str(f"L = {length:g} m")
            intervals = preview_intervals(problem, length, road.speed_m_s, road.wheelbase_m)
            result = evaluate_preview(design, problem, intervals, length)
            linear.append(result.a_total_m_s2)
            peaks.append(float(np.max(np.abs(result.command))) / problem.u_bounds[1])
            bar.update()
            if args.simulate:
                try:
                    run = simulate_preview(design, problem, result, road)
                    simulated.append(float(run.seat_evaluation().total_m_s2))
                except SimulationError as error:
                    bar.write(f"L = {length:g} m: the simulation failed ({error}); reported as NaN")
                    simulated.append(float("nan"))
                bar.update()
        for name, scenario in references.items():
            bar.set_postfix_str(name)
            run = simulate(road, scenario, duration_s=problem.duration_s)
            totals[name] = float(run.seat_evaluation().total_m_s2)
            bar.update()
    sweep = PreviewSweep(
        title=(
            f"{course.name}; load {args.load}"
            if layout.machine.is_default
            else f"{layout.name}: {course.name}; load {args.load}"
        ),
        preview_m=np.array(lengths),
        linear=np.array(linear),
        simulated=np.array(simulated) if simulated else np.full(len(lengths), np.nan),
        peak_command=np.array(peaks),
        bound_m_s2=bound,
        lqr_m_s2=lqr,
        references=totals,
    )
    print(sweep.format())
    if output is not None:
        output.mkdir(parents=True, exist_ok=True)
        for path in (
            write_csv(sweep, output / "preview.csv"),
            plot_sweep(sweep, output / "preview.png"),
        ):
            written.append(str(path))
            print(f"wrote {path}")
    return 0
