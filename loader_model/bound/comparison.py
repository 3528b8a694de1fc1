"""Every controller beside the bound on one course: a_total and each one's share of the reduction.

:func:`compare` simulates each given closed loop (:class:`~loader_model.simulation.scenario.
Scenario`) over the bound problem's horizon, evaluates the seat as the report does
(:meth:`~loader_model.simulation.result.SimulationResult.seat_evaluation`, Eq. 49, 50), solves the
bound and gives each controller's share of the achievable reduction,
(a_baseline − a_controller) / (a_baseline − a_bound): 1 is the bound, 0 the baseline, negative
worse than the baseline. :func:`write_csv` and :func:`plot_comparison` write the optimal command
and seat trace beside the best controller's.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from loader_model.bound.constrained import ConstrainedBound, solve_constrained_bound
from loader_model.bound.linear import LinearBound, solve_linear_bound
from loader_model.bound.nonlinear import NonlinearBound, solve_nonlinear_bound
from loader_model.bound.problem import BoundProblem
from loader_model.io.export import write_atomically
from loader_model.simulation.result import SimulationResult, seat_signal_names
from loader_model.simulation.scenario import Scenario
from loader_model.simulation.simulator import simulate
from loader_model.simulation.travel import RoadInput

__all__ = [
    "BOUND_KINDS",
    "BoundComparison",
    "compare",
    "format_comparison",
    "plot_comparison",
    "solve_bound",
    "write_csv",
]

#: The bounds :func:`compare` can solve: the LQ bound without limits, with the pump's, and the
#: machine's own (:mod:`~loader_model.bound.nonlinear`, warm-started from the best controller).
BOUND_KINDS = ("linear", "constrained", "nonlinear")


@dataclass(frozen=True)
class BoundComparison:
    """Controllers and the bound on one course (module notes).

    Attributes
    ----------
    title : str
        Course, speed and load.
    a_total : dict
        Controller name -> a_total (Eq. 50) in m/s², the baseline first.
    bound : LinearBound or ConstrainedBound
        The bound (its command deviation from u0 and a_total).
    bound_kind : str
        Which bound (:data:`BOUND_KINDS`): ``"linear"`` the non-causal LQ bound on the
        linearised plant, ``"constrained"`` the same with the pump's, pressure and stroke limits
        (:mod:`~loader_model.bound.constrained`).
    runs : dict
        Controller name -> its simulation result.
    problem : BoundProblem
        Grid and road of the bound.
    """

    title: str
    a_total: dict[str, float]
    bound: LinearBound | ConstrainedBound | NonlinearBound
    bound_kind: str
    runs: dict[str, SimulationResult] = field(repr=False)
    problem: BoundProblem = field(repr=False)

    def share(self, name: str) -> float:
        """(baseline − controller) / (baseline − bound) of controller ``name``."""
        baseline = self.a_total["baseline"]
        return (baseline - self.a_total[name]) / (baseline - self.bound.a_total_m_s2)

    @property
    def best(self) -> str:
        """The controller with the lowest a_total."""
        return min(self.a_total, key=self.a_total.__getitem__)


def solve_bound(
    problem: BoundProblem,
    kind: str = "linear",
    *,
    progress: bool = False,
    warm: SimulationResult | None = None,
) -> LinearBound | ConstrainedBound | NonlinearBound:
    """The bound ``kind`` (:data:`BOUND_KINDS`) of ``problem``; ``"nonlinear"`` starts from the
    run ``warm`` (default: the static command)."""
    if kind not in BOUND_KINDS:
        raise ValueError(f"bound must be one of {', '.join(BOUND_KINDS)}; got {kind!r}")
    if kind == "linear":
        return solve_linear_bound(problem)
    if kind == "nonlinear":
        start = np.full(problem.intervals, problem.plant.u0) if warm is None else warm
        return solve_nonlinear_bound(problem, start, progress=progress)
    return solve_constrained_bound(problem, progress=progress)


def compare(
    problem: BoundProblem,
    road: RoadInput,
    scenarios: dict[str, Scenario],
    *,
    title: str = "",
    bound: str = "linear",
    progress: bool = False,
) -> BoundComparison:
    """Simulate ``scenarios`` (must hold ``"baseline"``) over ``problem``'s horizon, solve the
    bound of kind ``bound`` (:data:`BOUND_KINDS`) and collect a_total (module notes)."""
    if "baseline" not in scenarios:
        raise ValueError(f"scenarios must hold 'baseline'; got {list(scenarios)}")
    if bound not in BOUND_KINDS:
        raise ValueError(f"bound must be one of {', '.join(BOUND_KINDS)}; got {bound!r}")
    from tqdm import tqdm

    runs, totals = {}, {}
    bar = tqdm(total=len(scenarios) + 1, desc="bound", unit="step", disable=not progress)
    with bar:
        for name, scenario in scenarios.items():
            bar.set_postfix_str(name)
            runs[name] = simulate(road, scenario, duration_s=problem.duration_s)
            totals[name] = float(runs[name].seat_evaluation().total_m_s2)
            bar.update()
        bar.set_postfix_str(f"{bound} bound")
        best = min(totals, key=totals.__getitem__)
        solved = solve_bound(problem, bound, progress=progress, warm=runs[best])
        bar.update()
    return BoundComparison(title, totals, solved, bound, runs, problem)


def format_comparison(comparison: BoundComparison) -> str:
    """The table: controller, a_total, change against the baseline, share of the reduction."""
    baseline = comparison.a_total["baseline"]
    lines = [comparison.title, f"{'controller':<22}{'a_total [m/s²]':>16}{'Δ [%]':>9}{'share':>8}"]
    for name, value in comparison.a_total.items():
        change = 100.0 * (value / baseline - 1.0)
        lines.append(f"{name:<22}{value:>16.4f}{change:>+9.1f}{comparison.share(name):>8.2f}")
    bound = comparison.bound.a_total_m_s2
    lines.append(
        f"{'bound (' + comparison.bound_kind + ')':<22}{bound:>16.4f}"
        f"{100.0 * (bound / baseline - 1.0):>+9.1f}{1.0:>8.2f}"
    )
    problem = comparison.problem
    peak = np.max(np.abs(problem.plant.u0 + comparison.bound.command)) / problem.u_bounds[1]
    if comparison.bound_kind == "linear":
        note = "no limits in the LQ problem"
    else:
        note = (
            "largest excess over the pump, pressure and stroke limits "
            f"{comparison.bound.max_violation:.1e} of each limit, negative inside"
        )
    lines.append(
        f"share = (baseline − controller) / (baseline − bound); the {comparison.bound_kind} "
        f"bound's command peaks at {peak:.2f} × the pump's limit ({note})"
    )
    return "\n".join(lines)


def _columns(comparison: BoundComparison) -> dict[str, np.ndarray]:
    problem = comparison.problem
    run = comparison.runs[comparison.best]
    time_s = np.arange(problem.periods) * problem.period_s
    command = problem.plant.u0 + np.repeat(comparison.bound.command, problem.hold_periods)
    columns = {"time [s]": time_s, "bound V_p_ref [m^3/rev]": command}
    for index, (axis, signal) in enumerate(seat_signal_names().items()):
        columns[f"bound seat {axis} [{run.unit(signal)}]"] = comparison.bound.seat[:, index]
    columns[f"{comparison.best} V_p_ref [m^3/rev]"] = run["V_p_ref"]
    for axis, signal in seat_signal_names().items():
        values = run[signal]
        columns[f"{comparison.best} seat {axis} [{run.unit(signal)}]"] = values - values[0]
    return columns


def write_csv(comparison: BoundComparison, path: str | Path) -> Path:
    """The bound's command and seat trace beside the best controller's, as CSV (atomically)."""
    columns = _columns(comparison)

    def write(temporary: Path) -> None:
        table = np.column_stack(list(columns.values()))
        header = ",".join(columns)
        np.savetxt(temporary, table, delimiter=",", header=header, comments="", fmt="%.9g")

    return write_atomically(path, write, (".csv",), "bound CSV")


def plot_comparison(comparison: BoundComparison, path: str | Path) -> Path:
    """Figure: pump command and seat accelerations, the bound beside the best controller."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    columns = _columns(comparison)
    time_s = columns.pop("time [s]")
    axes_names = list(seat_signal_names())
    figure = Figure(figsize=(9.0, 8.0), layout="constrained")
    FigureCanvasAgg(figure)
    panels = figure.subplots(1 + len(axes_names), 1, sharex=True)
    best = comparison.best
    panels[0].plot(time_s, columns[f"{best} V_p_ref [m^3/rev]"] * 1e6, lw=0.8, label=best)
    panels[0].plot(time_s, columns["bound V_p_ref [m^3/rev]"] * 1e6, lw=0.8, label="bound")
    limit = comparison.problem.u_bounds[1] * 1e6
    for sign in (-1, 1):
        panels[0].axhline(sign * limit, color="grey", lw=0.6, ls="--")
    panels[0].set_ylabel("V_p,ref [cm³/rev]")
    panels[0].legend(loc="upper right", fontsize=8)
    for panel, axis in zip(panels[1:], axes_names, strict=True):
        for label in (best, "bound"):
            key = next(k for k in columns if k.startswith(f"{label} seat {axis} "))
            panel.plot(time_s, columns[key], lw=0.7, label=label)
        panel.set_ylabel(f"seat {axis} [{key.split('[')[1]}")
    panels[-1].set_xlabel("time [s]")
    figure.suptitle(
        f"{comparison.title}: a_total {best} {comparison.a_total[best]:.3f}, bound "
        f"({comparison.bound_kind}) {comparison.bound.a_total_m_s2:.3f} m/s²",
        fontsize=10,
    )

    def write(temporary: Path) -> None:
        figure.savefig(temporary, format="png", dpi=110)

    return write_atomically(path, write, (".png",), "bound figure")
