"""The bound for the four Table 6 conditions as a shipped result file, and its report section.

``make bound`` runs ``python -m loader_model.bound.table6`` and writes
``loader_model/data/bound_table6.toml``: per condition (9 and 18 km/h, empty and full bucket, the
paper's course without board jitter, one trial), the baseline's a_total (Eq. 50) over the bound's
horizon, the linear bound's with the peak of its command over the pump's limit, and the
constrained linear bound's (:mod:`~loader_model.bound.constrained`: the same LQ problem with the
pump's command and rate limits, the chamber pressures and the stroke; about two minutes per
condition).
:func:`render_markdown` gives the reproduce report a section from that file (a slow test checks
that the file is current). The bound is the non-causal LQ bound of the linearised plant
(:mod:`~loader_model.bound.linear`), without the pump's limits (see its peak command), and
with them.
"""

from __future__ import annotations

import argparse
import tomllib
from collections.abc import Mapping
from importlib import resources
from pathlib import Path

from loader_model.io.export import write_atomically

__all__ = ["COMMAND", "CONDITIONS", "compute_table", "load_table", "render_markdown", "write_table"]

#: The Table 6 conditions: speed in km/h and bucket load.
CONDITIONS: tuple[tuple[float, str], ...] = (
    (9.0, "empty"),
    (9.0, "full"),
    (18.0, "empty"),
    (18.0, "full"),
)
#: The command that writes the shipped file.
COMMAND = "python -m loader_model.bound.table6 --output loader_model/data/bound_table6.toml"


def compute_table() -> dict[str, dict[str, float]]:
    """Baseline and linear-bound a_total per condition (module notes)."""
    import numpy as np

    from loader_model.bound.constrained import solve_constrained_bound
    from loader_model.bound.linear import linear_quadratic, solve_linear_bound
    from loader_model.bound.problem import bound_problem
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import closed_loop
    from loader_model.simulation.simulator import course_input, simulate

    table = {}
    for speed, load in CONDITIONS:
        plant = resolve_plant(None, load)
        road = course_input(paper_course(speed), plant)
        problem = bound_problem(plant, road)
        baseline = simulate(road, closed_loop(plant), duration_s=problem.duration_s)
        bound = solve_linear_bound(problem)
        constrained = solve_constrained_bound(problem, linear_quadratic(problem))
        table[f"{speed:g} km/h {load}"] = {
            "speed_kmh": speed,
            "load": load,
            "baseline_a_total_m_s2": float(baseline.seat_evaluation().total_m_s2),
            "linear_bound_a_total_m_s2": float(bound.a_total_m_s2),
            "linear_bound_peak_command_over_limit": float(
                np.max(np.abs(plant.u0 + bound.command)) / problem.u_bounds[1]
            ),
            "constrained_bound_a_total_m_s2": float(constrained.a_total_m_s2),
            "constrained_bound_converged": bool(constrained.converged),
        }
    return table


def write_table(path: str | Path) -> Path:
    """Compute the table and write it as TOML (atomically) with the command that made it."""
    table = compute_table()

    def write(temporary: Path) -> None:
        lines = [
            "# The bound for the four Table 6 conditions (loader_model.bound.table6).",
            f"# Written by `make bound`: {COMMAND}",
            "# Linear bound: non-causal LQ on the linearised plant, no pump limits; constrained:",
            "# the same with the pump's command and rate limits, pressures and stroke.",
        ]
        for name, row in table.items():
            lines.append(f'\n["{name}"]')
            for key, value in row.items():
                if isinstance(value, bool):
                    lines.append(f"{key} = {str(value).lower()}")
                elif isinstance(value, str):
                    lines.append(f'{key} = "{value}"')
                else:
                    lines.append(f"{key} = {value!r}")
        temporary.write_text("\n".join(lines) + "\n", encoding="utf-8")

    return write_atomically(path, write, (".toml",), "bound table")


def load_table(path: str | Path | None = None) -> dict[str, dict[str, float]]:
    """The shipped (or given) table."""
    if path is None:
        with resources.as_file(
            resources.files("loader_model").joinpath("data", "bound_table6.toml")
        ) as shipped:
            return tomllib.loads(shipped.read_text(encoding="utf-8"))
    return tomllib.loads(Path(path).read_text(encoding="utf-8"))


def render_markdown(
    path: str | Path | None = None,
    reductions: Mapping[str, Mapping[str, tuple[str, float]]] | None = None,
) -> str:
    """The report section: baseline and bounds per condition, from the result file.

    Parameters
    ----------
    path : str or Path, optional
        The result file (default the shipped ``data/bound_table6.toml``).
    reductions : mapping, optional
        Per condition name (``"9 km/h empty"``, as in the file) the best reductions to set
        beside the bound: ``"measured"`` (the paper's Table 6) and ``"simulated"`` (the model's
        trials), each as (controller, change of a_total against the baseline in %). Without
        it the section has the bounds alone.
    """
    table = load_table(path)
    beside = reductions is not None
    extra_head = " best measured Δ [%] (paper) | best simulated Δ [%] (model) |" if beside else ""
    lines = [
        "## The bound: what the pump could do with the course known in advance",
        "",
        "| speed / load | baseline a_total [m/s²] | linear bound [m/s²] | reduction [%] | "
        "bound's peak command / pump limit | constrained bound [m/s²] | reduction [%] |"
        + extra_head,
        "|---|---|---|---|---|---|---|" + ("---|---|" if beside else ""),
    ]
    for name, row in table.items():
        baseline, bound = row["baseline_a_total_m_s2"], row["linear_bound_a_total_m_s2"]
        constrained = row.get("constrained_bound_a_total_m_s2", float("nan"))
        cells = ""
        if beside:
            found = reductions.get(name, {})
            cells = "".join(
                f" {found[key][1]:+.1f} ({found[key][0]}) |" if key in found else " — |"
                for key in ("measured", "simulated")
            )
        lines.append(
            f"| {name} | {baseline:.3f} | {bound:.3f} | {100 * (bound / baseline - 1):+.1f} | "
            f"{row['linear_bound_peak_command_over_limit']:.1f} | {constrained:.3f} | "
            f"{100 * (constrained / baseline - 1):+.1f} |" + cells
        )
    lines += [
        "",
        "The linear bound is the non-causal LQ optimum of the linearised plant (one trial per "
        "condition, the paper's course without jitter). It has no pump limits and asks for "
        "several times the pump's displacement, so it bounds the linear plant, not the machine. "
        "The constrained bound is the same problem with the pump's command and rate limits, the "
        "chamber pressures between cavitation and relief and the stroke, still on the linear "
        "plant (a controller in the nonlinear simulator can come close to it or below it); "
        f"the file comes from `{COMMAND}` (`make bound`).",
    ]
    if beside:
        below = {key: 0 for key in ("measured", "simulated")}
        for name, row in table.items():
            constrained = row.get("constrained_bound_a_total_m_s2", float("nan"))
            change = 100 * (constrained / row["baseline_a_total_m_s2"] - 1)
            for key in below:
                found = reductions.get(name, {}).get(key)
                below[key] += found is not None and found[1] < change
        lines += [
            "",
            "Beside it, the largest reduction per condition: measured, among the paper's three "
            "controllers (Table 6); simulated, among every controller of this report's trials "
            "(Table 6's and the designed gains, the mean over the jittered trials against the "
            "baseline's). The bounds are of one nominal drive, the trials of jittered ones, so "
            "read the columns side by side, not as one sample. The best simulated controller "
            f"reduces a_total further than the constrained linear bound in {below['simulated']} "
            f"of {len(table)} conditions, the paper's measured best in {below['measured']}: "
            "the linear plant's bound is not the machine's.",
        ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Write the table where ``--output`` says."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", required=True)
    args = parser.parse_args(argv)
    print(f"wrote {write_table(args.output)}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
