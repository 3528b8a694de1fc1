"""The best any controller could do on a known course, beside the baseline and every controller.

Simulates the baseline and the controllers (``passive``, ``virtual-accumulator``, ``skyhook``
with Table 3 gains, ``skyhook-lqr`` and ``skyhook-optimised`` designed on the linear plant,
``skyhook-refined`` from the shipped refined settings) over the course and prints a_total
(ISO 2631-1, Eq. 49, 50) of each beside the bound, with each controller's share of the
achievable reduction, (baseline − controller) / (baseline − bound). The bound printed is the
non-causal LQ bound on the linearised plant (the road known in advance, no pump limits:
:mod:`loader_model.bound.linear`). With ``--output DIR`` writes ``bound.csv`` (the optimal
command and seat trace beside the best controller's) and ``bound.png``. ``--bound constrained``
prints the LQ bound with the pump's, pressure and stroke limits instead
(:mod:`loader_model.bound.constrained`; minutes on the whole course); ``--bound nonlinear`` the
machine's own bound on the simulator's discretisation (:mod:`loader_model.bound.nonlinear`,
warm-started from the best controller's run; give ``--duration``). ``--pump-sizing`` runs
the pump-sizing study instead of the comparison (:mod:`loader_model.bound.pump_sizing`: the
constrained bound and the refined skyhook against V_p_max, ω_p and V̇_p,max, Table 2) and writes
``pump_sizing.csv`` and ``pump_sizing.png`` to ``--output``.

``--machine NAME|FILE`` and ``--params FILE`` choose the machine and its parameter file, as for
``simulate``: any described machine whose boom is driven by the pump's closed circuit (a machine
with a valve-controlled circuit is refused). On another machine than the skid-steer the
controllers are those ``simulate --compare`` runs (``baseline``, ``passive``,
``virtual-accumulator`` and ``skyhook`` with Table 3's settings: the designed and refined gains
are the skid-steer's), and the pump sizing simulates Table 3's skyhook.
"""

from __future__ import annotations

import argparse
from typing import Any

from loader_model.commands.common import (
    add_model_arguments,
    add_progress_argument,
    layout_from_arguments,
)

__all__ = ["CONTROLLERS", "GUIDE", "HELP", "MACHINE_CONTROLLERS", "add_arguments", "run"]

HELP = "the clairvoyant bound on a course beside the baseline and every controller"
GUIDE = "bound.md"  # its page of the user guide (docs/guide/)

#: Controllers the command runs by default (baseline always).
CONTROLLERS = (
    "baseline",
    "passive",
    "virtual-accumulator",
    "skyhook",
    "skyhook-lqr",
    "skyhook-optimised",
    "skyhook-refined",
)
#: Controllers on another machine than the skid-steer (the others' gains are the skid-steer's).
MACHINE_CONTROLLERS = ("baseline", "passive", "virtual-accumulator", "skyhook")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register the arguments of ``loader-model bound``."""
    add_model_arguments(parser, machine=True)
    parser.add_argument("--course", default="paper", metavar="COURSE", help="'paper'")
    parser.add_argument(
        "--speed", type=float, default=9.0, metavar="KMH", help="speed in km/h: 9 or 18"
    )
    parser.add_argument(
        "--controllers",
        default=None,
        metavar="LIST",
        help=f"comma-separated, from {', '.join(CONTROLLERS)} (default: all of them); on "
        f"another machine from {', '.join(MACHINE_CONTROLLERS)} (default: these four)",
    )
    parser.add_argument("--hold-ms", type=int, default=10, metavar="MS", help="command grid in ms")
    parser.add_argument(
        "--max-intervals",
        type=int,
        default=6000,
        metavar="N",
        help="largest number of command values one problem may have",
    )
    parser.add_argument(
        "--bound",
        default="linear",
        metavar="KIND",
        help="'linear' (no limits, under a second), 'constrained' (the pump's, "
        "pressure and stroke limits on the linear plant; minutes on the 15 s course) or "
        "'nonlinear' (the machine's own bound in the simulator; use --duration: minutes for "
        "a few seconds of course)",
    )
    parser.add_argument(
        "--pump-sizing",
        action="store_true",
        help="instead of the comparison: the constrained bound and the refined skyhook against "
        "the pump's V_p_max, omega_p and Vd_p_max (writes pump_sizing.csv, .png to --output)",
    )
    parser.add_argument(
        "--factors",
        default=None,
        metavar="LIST",
        help="with --pump-sizing: comma-separated scale factors of each pump parameter "
        "(default: 0.5,0.75,1,1.5,2)",
    )
    parser.add_argument(
        "--duration",
        type=float,
        default=None,
        metavar="S",
        help="horizon in s (default: the whole course)",
    )
    parser.add_argument(
        "--output", metavar="DIR", default=None, help="write bound.csv and bound.png into DIR"
    )
    add_progress_argument(parser)


def _controllers(text: str | None, layout: Any) -> tuple[str, ...]:
    allowed = CONTROLLERS if layout.machine.is_default else MACHINE_CONTROLLERS
    if text is None:
        return allowed
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    unknown = [name for name in names if name not in allowed]
    if unknown or not names:
        note = "" if layout.machine.is_default else f" on machine {layout.name!r}"
        raise ValueError(
            f"--controllers {text!r}: unknown{note} {unknown}; allowed: {', '.join(allowed)}"
        )
    return ("baseline", *(name for name in names if name != "baseline"))


def run(args: argparse.Namespace) -> int:
    """Run the comparison, print it and write the files; an interrupt says what was written."""
    from loader_model.io.interrupts import files_note, keeping

    written: list[str] = []
    wanted = (None,) if args.output is None else (f"{args.output}/bound.csv",)
    with keeping(lambda: files_note(wanted, written)):
        return _run(args, written)


def _run(args: argparse.Namespace, written: list[str]) -> int:
    import math
    from pathlib import Path

    from loader_model.bound.problem import require_pump_circuit

    layout = layout_from_arguments(args)
    try:
        require_pump_circuit(layout, "the bound")
    except ValueError as error:
        raise ValueError(f"--machine {args.machine!r}: {error}") from None
    if args.course != "paper":
        raise ValueError(f"--course {args.course!r}: allowed: paper")
    if args.speed not in (9.0, 18.0):
        raise ValueError(f"--speed {args.speed:g}: allowed: 9 or 18 km/h (the paper's course)")
    if not 1 <= args.hold_ms <= 100:
        raise ValueError(f"--hold-ms {args.hold_ms}: allowed: 1 to 100")
    if args.max_intervals < 2:
        raise ValueError(f"--max-intervals {args.max_intervals}: allowed: an integer >= 2")
    from loader_model.bound.comparison import BOUND_KINDS

    if args.bound not in BOUND_KINDS:
        raise ValueError(f"--bound {args.bound!r}: allowed: {', '.join(BOUND_KINDS)}")
    if args.duration is not None and not 0 < args.duration < float("inf"):
        raise ValueError(f"--duration {args.duration!r}: allowed: a finite time > 0 s")
    if args.duration is not None:
        from loader_model.iso2631.weightings import settling_time_s

        settle = max(settling_time_s(name) for name in ("Wd", "Wk", "We"))
        hold_s = args.hold_ms * 1e-3  # the horizon is rounded down to whole intervals
        shortest = math.ceil(settle / hold_s - 1e-9) * hold_s
        if args.duration < shortest - 1e-9:
            raise ValueError(
                f"--duration {args.duration:g}: allowed: at least {shortest:g} s (whole "
                f"--hold-ms intervals over the {settle:.3f} s the ISO 2631-1 weightings of "
                "a_total settle in, Eq. 49, 50)"
            )
    if args.factors is not None and not args.pump_sizing:
        raise ValueError(f"--factors {args.factors!r}: allowed only with --pump-sizing")
    if args.pump_sizing:
        return _pump_sizing(args, layout, written)
    names = _controllers(args.controllers, layout)
    output = None
    if args.output is not None:
        output = Path(args.output)
        if output.exists() and not output.is_dir():
            raise ValueError(f"--output {args.output!r}: not a folder")
    from loader_model.bound.comparison import (
        compare,
        format_comparison,
        plot_comparison,
        write_csv,
    )
    from loader_model.bound.problem import bound_problem
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input

    scenarios = _scenarios(names, args.params, args.load, layout)
    plant = scenarios["baseline"].plant
    course = paper_course(args.speed)
    road = course_input(course, plant)
    try:
        problem = bound_problem(
            plant,
            road,
            hold_periods=args.hold_ms,
            duration_s=args.duration,
            max_intervals=args.max_intervals,
        )
    except ValueError as error:
        raise ValueError(f"--course/--speed/--hold-ms: {error}") from None
    title = _title(layout, f"{course.name}; load {args.load}")
    comparison = compare(
        problem,
        road,
        scenarios,
        title=title,
        bound=args.bound,
        progress=not args.no_progress,
    )
    print(format_comparison(comparison))
    solved = comparison.bound
    detail = ""
    if args.bound == "constrained":
        detail = (
            f" ({solved.rounds} rounds, {solved.iterations} interior-point iterations, "
            f"{len(solved.working_set)} path rows, converged: {solved.converged})"
        )
    if args.bound == "nonlinear":
        detail = (
            f" ({solved.iterations} SQP iterations, {solved.time_per_iteration_s:.1f} s each, "
            f"{solved.qp_iterations} interior-point iterations, {solved.status}; "
            f"warm start a_total {solved.warm_a_total_m_s2:.4f})"
        )
    print(f"{args.bound} bound solved in {solved.solve_s:.2f} s{detail}")
    if args.bound == "nonlinear" and solved.noise_floor is not None:
        spread, violation = solved.noise_floor
        print(
            f"not converged: round-off-sized changes of its command spread the simulated "
            f"a_total by {spread:.1e} (relative) and the largest violation by {violation:.1e} "
            "of a limit (docs/guide/bound.md)"
        )
    if args.bound == "constrained":
        print(
            "the constrained bound is the linear plant's: beside controllers in the nonlinear "
            "simulator it is a reference, not a strict bound (docs/guide/bound.md)"
        )
    if output is not None:
        output.mkdir(parents=True, exist_ok=True)
        for path in (write_csv(comparison, output / "bound.csv"),):
            written.append(str(path))
            print(f"wrote {path}")
        path = plot_comparison(comparison, output / "bound.png")
        written.append(str(path))
        print(f"wrote {path}")
    return 0


def _title(layout: Any, title: str) -> str:
    """``title``, prefixed with the machine's name on another machine than the skid-steer."""
    return title if layout.machine.is_default else f"{layout.name}: {title}"


def _scenarios(names: tuple[str, ...], params: str | None, load: str, layout: Any) -> dict:
    """The closed loops of ``names`` on the machine ``layout``, its ``params`` and ``load``."""
    from loader_model.control.settings import default_settings, with_gains
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.scenario import ride_scenario

    plants = {False: resolve_plant(params, load, PlantOptions(), machine=layout)}
    if "passive" in names:
        plants[True] = plants[False].with_options(PlantOptions(accumulator=True))
    designed = {}
    if {"skyhook-lqr", "skyhook-optimised"} & set(names):
        from loader_model.experiments.designed_gains import designed_gains

        designed = {name: gain.k_fb for name, gain in designed_gains().items()}
    scenarios = {}
    for name in names:
        plant = plants[name == "passive"]
        if name in ("baseline", "passive", "virtual-accumulator", "skyhook"):
            scenarios[name] = ride_scenario(plant, name)
        elif name == "skyhook-refined":
            from loader_model.experiments.designed_gains import refined_settings

            scenarios[name] = ride_scenario(plant, "skyhook", refined_settings())
        else:
            settings = with_gains(default_settings(), designed[name], name)
            scenarios[name] = ride_scenario(plant, "skyhook", settings)
    return scenarios


def _factors(text: str | None) -> tuple[float, ...]:
    from loader_model.bound.pump_sizing import DEFAULT_FACTORS

    if text is None:
        return DEFAULT_FACTORS
    try:
        values = tuple(float(v) for v in text.split(",") if v.strip())
    except ValueError:
        values = ()
    if not values or not all(v > 0 for v in values):
        raise ValueError(f"--factors {text!r}: allowed: comma-separated numbers > 0")
    return values


def _pump_sizing(args: argparse.Namespace, layout: Any, written: list[str]) -> int:
    """``--pump-sizing``: the constrained bound and the refined skyhook (on another machine
    Table 3's skyhook) against pump size."""
    from pathlib import Path

    from loader_model.bound.pump_sizing import plot_pump_sizing, pump_sizing, write_csv
    from loader_model.experiments.designed_gains import refined_settings
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import ride_scenario
    from loader_model.simulation.simulator import course_input

    factors = _factors(args.factors)
    if args.output is None:
        raise ValueError("--output DIR is required with --pump-sizing (pump_sizing.csv, .png)")
    output = Path(args.output)
    if output.exists() and not output.is_dir():
        raise ValueError(f"--output {args.output!r}: not a folder")
    plant = resolve_plant(args.params, args.load, machine=layout)
    course = paper_course(args.speed)
    road = course_input(course, plant)
    default = layout.machine.is_default
    settings, label = (refined_settings(), "refined") if default else (None, "skyhook")
    rows = pump_sizing(
        plant,
        road,
        factors=factors,
        controller=lambda sized: ride_scenario(sized, "skyhook", settings),
        hold_periods=args.hold_ms,
        duration_s=args.duration,
        progress=not args.no_progress,
    )
    print(
        f"{'parameter':<10}{'factor':>8}{'baseline':>10}{'(linear)':>10}{'bound':>10}"
        f"{label:>10}{'rounds':>8}"
    )
    for row in rows:
        print(
            f"{row.parameter:<10}{row.factor:>8.2f}{row.baseline_a_total_m_s2:>10.4f}"
            f"{row.linear_baseline_a_total_m_s2:>10.4f}{row.bound_a_total_m_s2:>10.4f}{row.controller_a_total_m_s2:>10.4f}"
            f"{row.bound_rounds:>8d}"
        )
    output.mkdir(parents=True, exist_ok=True)
    title = _title(
        layout, f"{course.name}; load {args.load}: a_total against pump size (one parameter scaled)"
    )
    for path in (
        write_csv(rows, output / "pump_sizing.csv"),
        plot_pump_sizing(
            rows,
            output / "pump_sizing.png",
            title=title,
            controller="skyhook-refined" if default else "skyhook",
        ),
    ):
        written.append(str(path))
        print(f"wrote {path}")
    return 0
