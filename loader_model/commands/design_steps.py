"""The steps of ``loader-model design`` beyond the linear design: the refinement on the course,
the design on the machine, the settings written and the design check of what is written."""

from __future__ import annotations

import argparse

__all__ = [
    "CHECK_ROUNDS",
    "check_step",
    "designed_settings",
    "machine_step",
    "refine_step",
    "start_base",
]

#: Rounds of the design on the machine: after each, the design check runs over the whole
#: envelope, and the conditions it finds failing join the scenarios of the next round (the
#: design on the compact wheel loader's six scenarios made the 13.5 km/h boards 5.5 % worse than
#: the baseline and rode the pump's limit on the class D road at 30 km/h, neither of which it
#: drove).
CHECK_ROUNDS = 3


def refine_step(args: argparse.Namespace, start, loads, params, machine: str, course):
    """Refine ``start`` on the nonlinear ``course`` and print the course a_total before/after."""
    from loader_model.experiments.course_refinement import course_cost, refine_on_course

    print(f"Refining on the nonlinear course: {course.name} ({', '.join(loads)}):")
    from loader_model.control.comfort_design import TABLE3_GAIN

    table3 = course_cost(
        tuple(TABLE3_GAIN.ravel()), loads, args.speed, params, machine=machine, course=course
    )
    result = refine_on_course(
        start,
        loads=loads,
        speed_kmh=args.speed,
        margin=args.margin,
        params=params,
        max_evaluations=args.evaluations,
        machine=machine,
        progress=not args.no_progress,
        course=course,
    )
    for name, totals in (
        ("Table 3", table3),
        ("optimised (linear)", result["start_a_total"]),
        ("refined (course)", result["a_total"]),
    ):
        shown = "  ".join(f"{load}: {value:.4f}" for load, value in totals.items())
        print(f"  {name:<22} course a_total [m/s²]  {shown}")
    gains = " ".join(f"{g:8.3f}" for g in result["gain"].ravel())
    print(
        f"  refined gains [{gains}]  ({result['evaluations']} evaluations, "
        f"{result['refused']} refused: unstable, failed or outside the settings' range)"
    )
    totals = "/".join(f"{value:.3f}" for value in result["a_total"].values())
    note = (
        f"; course a_total {totals} m/s² ({'/'.join(loads)}), {result['evaluations']} evaluations"
    )
    return result["gain"], note


def _gains(gain) -> str:
    import numpy as np

    return " ".join(f"{g:8.3f}" for g in np.ravel(gain))


def machine_step(args: argparse.Namespace, start, machine: str, envelope=None):
    """Optimise ``start`` (or ``--start``'s gains) on the nonlinear machine, in up to
    :data:`CHECK_ROUNDS` rounds with the design check over ``envelope`` between them; print the
    scenarios beside the baseline. Returns the gains, a note for the settings file's source, and
    the last check (None when ``envelope`` is None: --no-check)."""
    import numpy as np

    from loader_model.experiments.machine_design import design_on_machine
    from loader_model.plant.layout import plant_layout

    layout = plant_layout(machine)
    if args.iterations < 1:
        raise ValueError(f"--iterations {args.iterations}: allowed: an integer >= 1")
    base = start_base(args)
    if args.start is not None:
        from loader_model.control.settings import gain_norm_factors, load_settings

        given = load_settings(args.start)
        start = np.asarray(given.k_fb, dtype=float) / gain_norm_factors(given)
        print(f"Start: the gains of {args.start} [{_gains(start)}]")
    check, extra = None, ()
    for round_ in range(1, CHECK_ROUNDS + 1):
        print(
            "Optimising on the nonlinear machine (exact gradients; relative to the baseline)"
            + (
                f", round {round_} with {len(extra)} scenarios the check found failing:"
                if extra
                else ":"
            )
        )
        result = design_on_machine(
            start,
            layout=layout,
            params=args.params,
            margin=args.margin,
            max_iterations=args.iterations,
            progress=not args.no_progress,
            extra_conditions=extra,
            base_settings=base,
        )
        _print_result(args, start, result)
        if envelope is None:
            break
        settings = designed_settings(result.gain, machine, base=base)
        check = _run_check(args, settings, machine, envelope)
        failing = tuple(c.condition for c in check.conditions if c.failures)
        if check.passed or not failing or round_ == CHECK_ROUNDS:
            break
        print(
            f"  the design check fails in {len(failing)} condition(s) "
            f"({'; '.join(c.label for c in failing)}): they join the scenarios, and the "
            "design goes on from these gains"
        )
        extra, start = extra + failing, result.gain
    note = f"; J {result.start_cost:.4f} -> {result.cost:.4f} over {len(result.a_total)} scenarios"
    if round_ > 1:
        note += f" ({round_} rounds with the design check's failing conditions)"
    return result.gain, note, check


def _print_result(args: argparse.Namespace, start, result) -> None:
    import numpy as np

    from loader_model.experiments.machine_design import START_MARGIN_FACTOR

    if not np.allclose(result.start_gain.ravel(), np.ravel(start), rtol=0.0, atol=0.0):
        print(
            f"  start moved to [{_gains(result.start_gain)}]: the nearest gains whose loop keeps "
            f"{START_MARGIN_FACTOR:g}σ = {START_MARGIN_FACTOR * args.margin:g} rad/s (σ where "
            "that is out of reach) on each load's linearised plant and on every sampled plant, "
            "or, where its runs broke a constraint (pump limits, persistence), scaled toward zero"
        )
    for label, value in result.a_total.items():
        base = result.baseline[label]
        print(
            f"  {label:<26} a_total {value:.3f} m/s², baseline {base:.3f} ({value / base - 1:+.1%})"
        )
    print(
        f"  gains [{_gains(result.gain)}]  J {result.start_cost:.4f} -> {result.cost:.4f} in "
        f"{result.iterations} steps, {result.simulations} runs with sensitivities, "
        f"{result.rejected} candidates rejected by a constraint, {result.wall_s:.0f} s"
    )


def _run_check(args: argparse.Namespace, settings, machine: str, envelope):
    from loader_model.experiments.design_check import Design, check_design
    from loader_model.plant.layout import plant_layout

    return check_design(
        Design(settings, "skyhook", machine, args.params, layout=plant_layout(machine)),
        envelope,
        jobs=args.jobs,
        progress=not args.no_progress,
    )


def start_base(args: argparse.Namespace):
    """``--start``'s settings without their gains, every other setting kept for the design
    (:func:`~loader_model.control.settings.without_gains`), or None."""
    if args.start is None:
        return None
    from loader_model.control.settings import load_settings, without_gains

    return without_gains(load_settings(args.start))


def designed_settings(gain, machine: str, source: str = "loader-model design", base=None):
    """``base`` (default the shipped settings) with the designed gains (norms scaled for
    another machine)."""
    from loader_model.control.settings import default_settings, with_gains, with_scaled_gains

    scaled = with_scaled_gains if machine != "skid_steer" else with_gains
    return scaled(base or default_settings(), gain, source)


def check_step(
    args: argparse.Namespace, settings, machine: str, envelope, check=None
) -> tuple[str, int]:
    """Run the design check (unless --no-check) on ``settings``, or take ``check`` (the
    machine design's last, of the same gains), print it; (verdict, code)."""
    from loader_model.commands.check_design_command import EXIT_CHECK_FAILED

    if envelope is None:
        print("Design check skipped (--no-check): not checked on the nonlinear machine")
        return "not checked on the nonlinear machine", 0
    from loader_model.experiments.design_check.report import check_text

    print("Checking the designed gains on the nonlinear machine:")
    if check is None:
        check = _run_check(args, settings, machine, envelope)
    print(check_text(check))
    judged = sum(c.judged for c in check.conditions)
    if check.passed:
        return f"passed its design check ({judged} conditions, {envelope.source})", 0
    reasons = "; ".join(check.failures)
    return f"FAILED its design check ({envelope.source}): {reasons}", EXIT_CHECK_FAILED
