"""Where the time goes: one closed-loop period's size, the Table 6 matrix and a design check.

Run from the repository's root::

    .venv/bin/python docs/measurements/profile_time.py > docs/measurements/profile_time.txt

It prints the CasADi instruction counts of the parts of one 1 ms period of the skid-steer (the
plant's right-hand side, with its Jacobian, the sparse LU and its two solves, the whole period
with four ROS2 substeps, and with one Jacobian for the period's four substeps), then profiles
(cProfile, one process) the 64 runs of the Table 6 matrix and ``loader-model check-design
default`` and splits their time by what it is spent on. Its first line says when, where and
under what load it ran: the seconds are that machine's, the shares hold elsewhere to a few
percent.
"""

from __future__ import annotations

import contextlib
import cProfile
import io
import os
import pstats
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "docs" / "measurements"))

#: The parts a profile is split into: label -> (function names whose cumulative time counts,
#: True when the function's own time is the part: the compiled periods run inside simulate).
PARTS: dict[str, tuple[tuple[str, ...], bool]] = {
    "compiled periods (integration)": (("simulate",), True),
    "road tables (tyre envelopes)": (("course_input",), False),
    "ISO 2631-1 evaluation": (("seat_evaluation",), False),
    "validity checks and events": (("check", "find_events"), False),
    "linearised loop margins": (("linear_margins", "sampled_plants", "sampled_margins"), False),
}


def period_sizes() -> None:
    """Instruction counts of one period's parts (SX, before code generation)."""
    import casadi as ca

    from loader_model.plant.layout import plant_layout
    from loader_model.plant.plant import plant_function
    from loader_model.simulation.controllers import hold_command_controller
    from loader_model.simulation.stepper import lu_solver, period_function

    layout, plant = plant_layout(), plant_function()
    nx, nw = len(layout.state_names), len(layout.exogenous_names)
    x, u, w = ca.SX.sym("x", nx), ca.SX.sym("u"), ca.SX.sym("w", nw)
    p = ca.SX.sym("p", plant.size1_in(3))
    rate = plant(x, u, w, p)[0]
    jacobian = ca.jacobian(rate, x)
    rhs = ca.Function("rhs", [x, u, w, p], [rate]).n_instructions()
    with_jacobian = ca.Function("rhs_jac", [x, u, w, p], [rate, jacobian]).n_instructions()
    matrix, b = ca.SX.sym("J", jacobian.sparsity()), ca.SX.sym("b", nx)
    solve = lu_solver(ca.SX.eye(nx) - 0.1 * matrix)
    lu = ca.Function("lu", [matrix, b], [solve(b), solve(2.0 * b + 1.0)]).n_instructions()
    period = period_function(hold_command_controller(), substeps=4).n_instructions()
    shared = period_function(hold_command_controller(), substeps=4, jacobian="period")
    print(f"one period of the skid-steer: {nx} states, Jacobian {jacobian.nnz()} non-zeros")
    print(f"  plant right-hand side              {rhs:6d} instructions")
    print(f"  right-hand side and its Jacobian   {with_jacobian:6d} instructions")
    print(f"  sparse LU and two solves           {lu:6d} instructions")
    print(f"  period, 4 ROS2 substeps, hold      {period:6d} instructions")
    print(f"  the same, one Jacobian a period    {shared.n_instructions():6d} instructions")


def split(profile: cProfile.Profile, label: str) -> None:
    """Print the profile's total and each part's seconds and share."""
    stats = pstats.Stats(profile, stream=io.StringIO()).stats  # type: ignore[attr-defined]
    total = max(entry[3] for entry in stats.values())
    print(f"{label}: {total:.2f} s in one process")
    counted = 0.0
    for part, (names, own) in PARTS.items():
        seconds = sum(
            entry[2] if own else entry[3]
            for (path, _, name), entry in stats.items()
            if name in names and "loader_model" in path
        )
        if seconds > 0.0:
            counted += seconds
            print(f"  {part:<34} {seconds:7.2f} s  {100.0 * seconds / total:5.1f} %")
    rest = total - counted
    print(f"  {'everything else':<34} {rest:7.2f} s  {100.0 * rest / total:5.1f} %")


def main() -> int:
    """Print the period's size and the two profiles after a header line."""
    from bench_quick import header

    from loader_model.cli import main as cli
    from loader_model.experiments.table6 import run_trials
    from loader_model.experiments.trials import trial_specs

    print(header("profile_time.py"))
    period_sizes()
    specs = trial_specs(seed=0, trials=4)
    run_trials(specs, jobs=1, progress=False)  # every period compiled and loaded: warm
    profile = cProfile.Profile()
    profile.runcall(run_trials, specs, jobs=1, progress=False)
    split(profile, "Table 6 matrix, 64 runs, 1 job, warm")
    import control  # noqa: F401  (imported before the profile: the check's linear margins use it)

    profile = cProfile.Profile()
    with contextlib.redirect_stdout(io.StringIO()):
        profile.runcall(cli, ["check-design", "default", "--jobs", "1", "--no-progress"])
    split(profile, "check-design default (26 conditions, 80 runs), 1 job, warm")
    print(f"# load average at the end {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
