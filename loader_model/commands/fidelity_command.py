"""The fidelity budget of Table 6 and the uncertainty of its signs.

Runs the Table 6 matrix once per modelling step (as it was; circuit states; seat pad and occupant;
tyre enveloping; k_φ sign; calibrated to 9 km/h; calibrated to 18 km/h:
:mod:`loader_model.experiments.fidelity`), then the robustness study of the estimated parameters
(``data/table6_estimates.toml``): per cell the share of plausible machines with the paper's sign,
and the share whose mean and trial scatter both agree with the paper's
(:mod:`loader_model.experiments.machine_agreement`). Writes one JSON file with the command that
made it; ``make fidelity`` ships it for the report. ``--update`` recomputes only what the
calibration changes (the calibrated steps) and the machines' mean-and-scatter study in an
existing file, keeping its other steps and its sign study.
"""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_jobs_argument, add_progress_argument

HELP = "measure the fidelity budget of Table 6 step by step and the uncertainty of its signs"
GUIDE = "reproduction.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--trials", type=int, default=4, metavar="N", help="trials per cell")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="seed of the trials")
    add_jobs_argument(parser, 2, "simulating the trials")
    parser.add_argument(
        "--samples", type=int, default=None, metavar="N",
        help="machines of the uncertainty study (default: the study file's, 96)",
    )  # fmt: skip
    parser.add_argument(
        "--machines", type=int, default=16, metavar="N",
        help="machines of the mean-and-scatter study, each on every cell (default: 16)",
    )  # fmt: skip
    parser.add_argument(
        "--machine-trials", type=int, default=6, metavar="N",
        help="trials per group and machine of the mean-and-scatter study (default: 6)",
    )  # fmt: skip
    parser.add_argument(
        "--update", nargs="?", const="calibrated,machines", default=None, metavar="PARTS",
        help="recompute only PARTS of an existing --output file (its --trials and --seed): "
        "calibrated (the calibrated steps; calibrated-9 or calibrated-18 for one of them), "
        "machines (the mean-and-scatter study), comma-separated (default: "
        "calibrated,machines); the other steps and the sign study are kept",
    )  # fmt: skip
    parser.add_argument("--output", metavar="FILE.json", required=True, help="the budget (JSON)")
    add_progress_argument(parser)


def run(args: argparse.Namespace) -> int:
    import datetime
    import time

    from loader_model.experiments.calibration_table6 import shipped_calibration
    from loader_model.experiments.fidelity import (
        budget_steps,
        run_budget,
        uncertainty_shares,
        write_budget,
    )
    from loader_model.experiments.machine_agreement import run_machines
    from loader_model.io.export import check_output_path

    check_output_path(args.output, (".json",), "--output")
    for name in ("trials", "jobs"):
        if getattr(args, name) < 1:
            raise ValueError(f"--{name} {getattr(args, name)}: allowed: an integer >= 1")
    if args.trials < 2:
        raise ValueError(f"--trials {args.trials}: allowed: >= 2 (the 95 % intervals need two)")
    if args.samples is not None and args.samples < 4:
        raise ValueError(f"--samples {args.samples}: allowed: an integer >= 4")
    for name in ("machines", "machine_trials"):
        if getattr(args, name) < 2:
            flag = "--" + name.replace("_", "-")
            raise ValueError(f"{flag} {getattr(args, name)}: allowed: an integer >= 2")
    parts = _parts(args.update)
    previous = _previous(args) if args.update is not None else None
    start = time.perf_counter()
    calibrated = {speed: shipped_calibration(speed) for speed in (9.0, 18.0)}
    steps = budget_steps(calibrated)
    if previous is not None:
        steps = [s for s in steps if s.held_out_kmh is not None and _chosen(s.label, parts)]
    summaries = run_budget(
        steps, trials=args.trials, seed=args.seed, jobs=args.jobs, progress=not args.no_progress
    )
    for summary in summaries:
        held = (
            f", held-out {summary['held_out_within']}/{summary['held_out_count']}"
            f" (scatter {summary['held_out_scatter_within']})"
            if summary["held_out_count"]
            else ""
        )
        print(
            f"  {summary['label']:<28} {summary['within']:2d}/{summary['count']} within 10 pp"
            f"{held}; scatter within a factor 2 {summary['scatter_within']}/{summary['count']}, "
            f"both {summary['both_within']}; significant findings in sign "
            f"{summary['significant_in_sign']}/{summary['significant_count']}"
        )
    machines = previous.get("machines") if previous is not None else None
    if "machines" in parts:
        machines = run_machines(
            args.machines, args.machine_trials, args.seed, args.jobs, not args.no_progress
        )
        both = [cell["both_share"] for cell in machines["cells"].values()]
        print(
            f"  mean and scatter of {args.machines} plausible machines ({args.machine_trials} "
            f"trials per group): share agreeing per cell {min(both):.0%}-{max(both):.0%}"
        )
    date = datetime.date.today().isoformat()
    if previous is not None:
        fresh = {summary["label"]: summary for summary in summaries}
        summaries = [fresh.get(step["label"], step) for step in previous["steps"]]
        update = {
            "command": _command(args),
            "date": date,
            "wall_time_s": round(time.perf_counter() - start, 1),
            "recomputed": [*fresh, *(["machines"] if "machines" in parts else [])],
        }
        results = {
            "steps": summaries,
            "uncertainty": previous["uncertainty"],
            "updates": [*previous.get("updates", []), update],
        }
        if machines is not None:
            results["machines"] = machines
        write_budget(
            args.output, results, previous["command"], previous["date"], previous["wall_time_s"]
        )
    else:
        uncertainty = uncertainty_shares(
            args.samples, workers=args.jobs, progress=not args.no_progress
        )
        results = {"steps": summaries, "uncertainty": uncertainty, "machines": machines}
        write_budget(args.output, results, _command(args), date, time.perf_counter() - start)
    print(f"wrote {args.output} in {time.perf_counter() - start:.0f} s")
    return 0


#: What ``--update`` can recompute.
_PARTS = ("calibrated", "calibrated-9", "calibrated-18", "machines")


def _parts(update: str | None) -> set[str]:
    """What ``--update`` recomputes (everything without it)."""
    if update is None:
        return {"calibrated", "machines"}
    parts = {part.strip() for part in update.split(",")}
    if not parts <= set(_PARTS):
        raise ValueError(f"--update {update!r}: allowed: {', '.join(_PARTS)}, comma-separated")
    return parts


def _chosen(label: str, parts: set[str]) -> bool:
    """Whether the calibrated step ``label`` ("+ calibrated to 9 km/h") is among ``parts``."""
    speed = label.removeprefix("+ calibrated to ").removesuffix(" km/h")
    return "calibrated" in parts or f"calibrated-{speed}" in parts


def _previous(args: argparse.Namespace) -> dict:
    """The budget that ``--update`` starts from; its trials and seed must be the ones given."""
    from pathlib import Path

    from loader_model.experiments.fidelity import read_budget
    from loader_model.experiments.fidelity_report import trial_count

    if not Path(args.output).is_file():
        raise ValueError(f"--update: {args.output} does not exist; run without --update first")
    previous = read_budget(args.output)
    trials = trial_count(previous)
    if trials != args.trials or f"--seed {args.seed} " not in previous["command"] + " ":
        raise ValueError(
            f"--update: {args.output} was made by {previous['command']!r}; allowed: the same "
            f"--trials {trials} and --seed"
        )
    return previous


def _command(args: argparse.Namespace) -> str:
    return (
        f"loader-model fidelity --trials {args.trials} --seed {args.seed} --jobs {args.jobs}"
        f"{'' if args.samples is None else f' --samples {args.samples}'}"
        f" --machines {args.machines} --machine-trials {args.machine_trials}"
        f"{'' if args.update is None else f' --update {args.update}'}"
    )
