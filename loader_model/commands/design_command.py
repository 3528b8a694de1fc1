"""Ride-comfort gain design: K_fb minimising the ISO 2631-1 a_total (Eq. 50) on an
ISO 8608 road, beside Table 3 and the output-feedback LQR (Eq. 41, 42); writes Fig. 12."""

from __future__ import annotations

import argparse

from loader_model.commands.common import (
    add_jobs_argument,
    add_machine_argument,
    add_progress_argument,
)
from loader_model.commands.course_options import (
    add_course_arguments,
    course_from_arguments,
    course_options_given,
)
from loader_model.commands.design_steps import (
    check_step,
    designed_settings,
    machine_step,
    refine_step,
    start_base,
)

HELP = "design the skyhook gains K_fb (LQR or ISO 2631 optimisation); Fig. 12"
GUIDE = "controllers.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--params``, ``--load``, ``--method``, ``--solver``, ``--road``, ``--speed``,
    ``--margin``, ``--plot`` and ``--output``."""
    add_machine_argument(parser, "; every method for every machine")
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="parameter file (TOML; for another machine than the skid-steer its flat file) "
        "(default: the shipped values of the machine)",
    )
    parser.add_argument(
        "--load",
        choices=("empty", "full", "both"),
        default="both",
        help="bucket load the gains are designed for; both: gains robust over the empty and the "
        "full bucket",
    )
    parser.add_argument(
        "--method",
        choices=("lqr", "optimise", "refine", "machine"),
        default="optimise",
        help="lqr: output-feedback LQR (Eq. 41, 42); optimise: ISO 2631 a_total on the linear "
        "plant; machine: optimise, then minimise a_total relative to the baseline on "
        "the nonlinear machine over both loads, boards at 9 and 18 km/h and an ISO 8608 class C "
        "road at 15 km/h, with exact gradients and the design check's criteria as constraints; "
        "refine: optimise, then a derivative-free (Nelder-Mead) refinement on --course "
        "at --speed",
    )
    parser.add_argument(
        "--solver",
        choices=("bfgs", "ipopt"),
        default="bfgs",
        help="optimise/refine: bfgs: certified BFGS with adjoint gradients; ipopt: "
        "IPOPT through CasADi on the same cost (every iterate stable, same optimum)",
    )
    parser.add_argument(
        "--iterations",
        type=int,
        default=12,
        metavar="N",
        help="machine: quasi-Newton steps at most (default: 12)",
    )
    parser.add_argument(
        "--start",
        metavar="SETTINGS.toml",
        default=None,
        help="machine: start from the gains of this controller settings file (e.g. gains "
        "refined on the course) instead of the linear design; its other settings (the pressure "
        "loop's k_p, the filters, the speed below which the ride control is off) are kept in "
        "the designed settings (default: the linear design, on the shipped settings)",
    )
    parser.add_argument(
        "--evaluations",
        type=int,
        default=120,
        metavar="N",
        help="refine: budget of course evaluations",
    )
    parser.add_argument("--road", default="C", metavar="CLASS", help="ISO 8608 road class, A-H")
    parser.add_argument("--speed", type=float, default=9.0, metavar="KMH", help="speed in km/h")
    add_course_arguments(parser, "; the course --method refine drives at --speed")
    parser.add_argument(
        "--margin", type=float, default=0.1, metavar="RAD_S", help="stability margin σ in rad/s"
    )
    parser.add_argument("--plot", metavar="FILE.png", default=None, help="write Fig. 12 here (PNG)")
    parser.add_argument(
        "--output",
        metavar="FILE.toml",
        default=None,
        help="write a controller settings file with the designed gains "
        "(for loader-model simulate --controller FILE.toml); only when they pass the design "
        "check, unless --force",
    )
    parser.add_argument(
        "--conditions",
        metavar="FILE.toml",
        default=None,
        help="conditions and criteria of the design check (default: the default envelope, "
        "see loader-model check-design --help)",
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="write the gains even when they fail the design check (the file says so)",
    )
    parser.add_argument(
        "--no-check",
        action="store_true",
        help="skip the design check on the nonlinear machine (nothing is written without it "
        "unless --force)",
    )
    add_jobs_argument(parser, 2, "of the design check and the machine method")
    add_progress_argument(parser)


def _row(label: str, gain, evaluations) -> str:
    import numpy as np

    gains = " ".join(f"{g:8.3f}" for g in gain.ravel())
    costs = "  ".join(
        f"{e.load}: {'unstable' if not np.isfinite(e.a_total) else f'{e.a_total:.4f}'}"
        for e in evaluations
    )
    total = sum(e.a_total**2 for e in evaluations)
    return f"  {label:<22} [{gains}]  a_total {costs}  Σa² {total:.4f}"


def run(args: argparse.Namespace) -> int:
    """Design, print gains / costs / poles / margins, write the figure atomically; an interrupt
    (Ctrl-C, SIGTERM) says which of the files were written."""
    from loader_model.io.interrupts import files_note, keeping

    written: list[str] = []
    with keeping(lambda: files_note((args.output, args.plot), written)):
        return _design(args, written)


def _design(args: argparse.Namespace, written: list[str]) -> int:
    """:func:`run`; appends each file it writes to ``written``."""
    import numpy as np

    from loader_model.io.export import check_output_path, write_atomically

    if args.plot is not None:
        check_output_path(args.plot, (".png",), "plot file")  # before any work
    if args.output is not None:
        check_output_path(args.output, (".toml",), "--output")
    if not (np.isfinite(args.speed) and 0.36 <= args.speed <= 108):
        raise ValueError(f"--speed {args.speed!r}: allowed: 0.36 to 108 km/h")
    if not (np.isfinite(args.margin) and args.margin >= 0):
        raise ValueError(f"--margin {args.margin!r}: allowed: a number >= 0 (rad/s)")
    given = course_options_given(args)
    if given and args.method != "refine":
        raise ValueError(
            f"{', '.join(given)} with --method {args.method}: allowed only with --method refine"
        )
    course = course_from_arguments(args) if args.method == "refine" else None
    if args.evaluations < 1:
        raise ValueError(f"--evaluations {args.evaluations}: allowed: an integer >= 1")
    if args.start is not None and args.method != "machine":
        raise ValueError(
            f"--start {args.start} with --method {args.method}: allowed only with --method machine"
        )
    if args.jobs < 1:
        raise ValueError(f"--jobs {args.jobs}: allowed: an integer >= 1")
    if args.no_check and args.output is not None and not args.force:
        raise ValueError(
            "--output with --no-check: gains are written only after the design check; drop "
            "--no-check, or add --force to write unchecked gains"
        )
    envelope = None
    if not args.no_check:
        from loader_model.experiments.design_check import DEFAULT_ENVELOPE, load_envelope

        envelope = DEFAULT_ENVELOPE if args.conditions is None else load_envelope(args.conditions)
    from loader_model.machines import resolve_machine_name

    machine = resolve_machine_name(getattr(args, "machine", "skid_steer"))
    from loader_model.control.comfort_design import (
        TABLE3_GAIN,
        TABLE3_PRINTED_GAIN,
        comfort_plants,
        evaluate_gain,
    )
    from loader_model.control.comfort_plant import comfort_case
    from loader_model.control.gain_design import design_gains

    course_note = ""
    loads = ("empty", "full") if args.load == "both" else (args.load,)
    params = None
    if machine != "skid_steer":
        from loader_model.plant.scenario import resolve_plant

        params = {
            load: resolve_plant(args.params, load, machine=machine) for load in ("empty", "full")
        }
    elif args.params is not None:
        from loader_model.plant.plant_parameters import plant_parameter_vector

        params = {load: plant_parameter_vector(args.params, load) for load in ("empty", "full")}
    every = comfort_plants(("empty", "full"), args.road, args.speed, params)
    design = [p for p in every if p.name in loads]
    lqr = design_gains(design, "lqr").gains
    if args.method in ("optimise", "refine", "machine"):
        optimised = design_gains(design, "optimise", margin=args.margin, solver=args.solver)
        designed, label, note = optimised.gain, "optimised (ISO 2631)", optimised.summary
    else:
        designed = lqr[loads[0]] if len(loads) == 1 else None
        label, note = "output-feedback LQR", "Q = C_zᵀC_z, R = 1e-2, X0 = B_w B_wᵀ"
    if machine != "skid_steer":
        print(f"machine {machine} (φ: the boom's angle to the chassis; the bucket is not fed back)")
    print(
        f"Skyhook gains K_fb on (ẋ_H, ẏ_H, θ̇1, φ), road ISO 8608 class {args.road.upper()} at "
        f"{args.speed:g} km/h, designed for: {', '.join(loads)}; margin σ = {args.margin:g} rad/s"
    )
    print("  a_total [m/s²] (Eq. 50, k = 1, 1, 0.4) on both loads:")
    rows = [
        ("Table 3 (k_φ = +0.22)", TABLE3_GAIN),
        ("Table 3 printed (−0.22)", TABLE3_PRINTED_GAIN),
    ]
    rows += [(f"LQR ({name})", gain) for name, gain in lqr.items()]
    if designed is not None and args.method in ("optimise", "refine", "machine"):
        rows.append((label, designed))
    for name, gain in rows:
        print(_row(name, gain, evaluate_gain(every, gain)))
    print(f"  {label}: {note}")
    if args.method == "refine":
        designed, course_note = refine_step(args, designed, loads, params, machine, course)
        label = "refined on the course"
    check = None
    if args.method == "machine":
        designed, course_note, check = machine_step(args, designed, machine, envelope)
        label = "designed on the machine"
    final = designed if designed is not None else next(iter(lqr.values()))
    print(
        "Closed loop with the designed gains (margin over all poles incl. the fixed road and"
        " ISO filter poles; loop = plant + skyhook: its margin, min damping, slowest 6 poles rad/s):"
    )
    for e in evaluate_gain(every, final):
        slow = sorted(e.loop_poles, key=lambda p: -p.real)[:6]
        listed = ", ".join(f"{p.real:.3f}{p.imag:+.2f}j" for p in slow)
        weak = e.loop_poles[np.argmin(-e.loop_poles.real / np.abs(e.loop_poles))]
        listed += (
            f"; least damped {weak.real:.3f}{weak.imag:+.2f}j ({abs(weak) / (2 * np.pi):.2f} Hz)"
        )
        print(
            f"  {e.load}: margin {e.margin:.4f} rad/s, loop margin {e.loop_margin:.4f}, "
            f"min ζ {e.min_damping:.4f}, "
            f"σ_Vp {e.v_p_rms * 1e6:.3f} cm³/rev, σ_pA {e.p_a_rms / 1e5:.2f} bar, "
            f"within limits: {e.within_limits}\n    {listed}"
        )
    base = start_base(args)  # --start's pressure loop, filters and ride-control speed
    settings = designed_settings(final, machine, base=base)
    verdict, code = check_step(args, settings, machine, envelope, check)
    if args.output is not None and (code == 0 or args.force):
        import datetime

        from loader_model.control.settings import save_settings

        source = (
            f"loader-model design --method {args.method}"
            f"{'' if args.method == 'lqr' else f' --solver {args.solver}'} --load {args.load} --road "
            f"{args.road.upper()} --speed {args.speed:g} --margin {args.margin:g}"
            f"{'' if machine == 'skid_steer' else f' --machine {machine}'}"
            f"{'' if args.params is None else f' --params {args.params}'}"
            f"{f' --evaluations {args.evaluations}' if args.method == 'refine' else ''}"
            f"{f' --iterations {args.iterations}' if args.method == 'machine' else ''}"
            f"{f' --start {args.start}' if args.method == 'machine' and args.start else ''} "
            f"on {datetime.date.today().isoformat()}{course_note}; {verdict}"
        )
        header = "Controller settings with designed skyhook gains (loader-model design)."
        if code != 0:
            header += " WRITTEN WITH --force: " + verdict
        written_settings = designed_settings(final, machine, source, base=base)
        save_settings(written_settings, args.output, header=header)
        written.append(args.output)
        print(f"wrote {args.output}")
    elif args.output is not None:
        print(f"not written: {args.output} (the gains fail the design check; --force writes them)")
    if args.plot is not None:
        from loader_model.control.comfort_figure import pitch_responses, plot_pitch_responses

        frequency = np.geomspace(0.3, 30.0, 400)
        gains = {"Table 3 with k_φ = +0.22": TABLE3_GAIN, label: final}
        curves = {
            load: pitch_responses(
                comfort_case(load, None if params is None else params[load]), gains, frequency
            )
            for load in ("empty", "full")
        }
        write_atomically(
            args.plot,
            lambda path: plot_pitch_responses(path, curves, frequency),
            (".png",),
            "plot file",
        )
        written.append(args.plot)
        print(f"wrote {args.plot}")
    return code
