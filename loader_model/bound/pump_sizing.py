r"""What pump a machine needs: the constrained bound and a causal controller against pump size.

For each pump parameter of Table 2 (Fig. 9's second-order pump: the maximum displacement
V_p,max, the bandwidth ω_p and the displacement-rate limit V̇_p,max; plant parameter names
``V_p_max``, ``omega_p``, ``Vd_p_max``) and each scale factor, the plant is rebuilt with that one
parameter scaled (:meth:`~loader_model.plant.scenario.PlantScenario.from_vector`, its own
equilibrium) and these are computed on the same course and horizon: the baseline's a_total
(Eq. 49, 50; it holds the pump still, so it does not depend on the pump) in the simulator and
on the linearised plant (the bound's own reference: on the 40 mm boards the linear plant
misses the nonlinear one's behaviour and reads far higher), the
constrained linear bound's (:mod:`~loader_model.bound.constrained`, the limits scaled with the
pump) and, if given, a causal controller's simulated with the scaled pump (the command passes
the shipped refined skyhook). Each constrained solve starts from the previous one's working set
of path rows (:func:`~loader_model.bound.constrained.solve_constrained_bound`), so neighbouring
sizes need few rounds. :func:`write_csv` and :func:`plot_pump_sizing` write the table and a
figure of a_total against each parameter's value; both are written atomically.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from loader_model.bound.constrained import solve_constrained_bound
from loader_model.bound.linear import evaluate, linear_quadratic
from loader_model.bound.problem import bound_problem
from loader_model.io.export import write_atomically
from loader_model.plant.scenario import PlantScenario
from loader_model.simulation.scenario import Scenario, closed_loop
from loader_model.simulation.simulator import simulate
from loader_model.simulation.travel import RoadInput

__all__ = [
    "DEFAULT_FACTORS",
    "PUMP_PARAMETERS",
    "PumpSizingRow",
    "plot_pump_sizing",
    "pump_sizing",
    "scaled_plant",
    "write_csv",
]

#: The pump parameters of the study (Table 2, Fig. 9) and their units.
PUMP_PARAMETERS: dict[str, str] = {
    "V_p_max": "m^3/rev",
    "omega_p": "rad/s",
    "Vd_p_max": "m^3/(rev s)",
}
#: Scale factors of each parameter (0.5 … 2 × the shipped pump).
DEFAULT_FACTORS: tuple[float, ...] = (0.5, 0.75, 1.0, 1.5, 2.0)


@dataclass(frozen=True)
class PumpSizingRow:
    """One pump size: the parameter scaled, its value and the a_total (m/s²) of the baseline in
    the simulator and on the linear plant (the bound's own reference), the bound and the
    controller."""

    parameter: str
    factor: float
    value: float
    baseline_a_total_m_s2: float
    linear_baseline_a_total_m_s2: float
    bound_a_total_m_s2: float
    controller_a_total_m_s2: float
    bound_peak_command_over_limit: float
    bound_max_violation: float
    bound_rounds: int
    bound_converged: bool
    bound_solve_s: float


def scaled_plant(plant: PlantScenario, parameter: str, factor: float) -> PlantScenario:
    """``plant`` with pump parameter ``parameter`` times ``factor`` (> 0), its equilibrium anew."""
    if parameter not in PUMP_PARAMETERS:
        raise ValueError(f"parameter {parameter!r}: allowed: {', '.join(PUMP_PARAMETERS)}")
    if not (np.isfinite(factor) and factor > 0.0):
        raise ValueError(f"factor of {parameter} must be a finite number > 0; got {factor!r}")
    vector = plant.params.copy()
    vector[plant.layout.parameter_names.index(parameter)] *= factor
    return PlantScenario.from_vector(vector, plant.loader, plant.load, plant.options, plant.layout)


def pump_sizing(
    plant: PlantScenario,
    road: RoadInput,
    *,
    factors: Sequence[float] = DEFAULT_FACTORS,
    parameters: Sequence[str] = tuple(PUMP_PARAMETERS),
    controller: Callable[[PlantScenario], Scenario] | None = None,
    hold_periods: int = 10,
    duration_s: float | None = None,
    progress: bool = False,
) -> list[PumpSizingRow]:
    """The study of the module notes: one row per parameter and factor.

    Raises
    ------
    ValueError
        Naming the argument: an empty ``factors``, a factor ≤ 0, an unknown parameter.
    """
    factors = [float(f) for f in factors]
    if not factors:
        raise ValueError("factors must hold at least one scale factor")
    for name in parameters:
        for factor in factors:
            scaled_plant(plant, name, factor)  # validates before the long loop
    from tqdm import tqdm

    base = bound_problem(plant, road, hold_periods=hold_periods, duration_s=duration_s)
    baseline = simulate(road, closed_loop(plant), duration_s=base.duration_s)
    baseline_a = float(baseline.seat_evaluation().total_m_s2)
    rows, working = [], None
    total = len(parameters) * len(factors)
    with tqdm(total=total, desc="pump sizing", unit="size", disable=not progress) as bar:
        for name in parameters:
            for factor in factors:
                bar.set_postfix_str(f"{name} × {factor:g}")
                sized = scaled_plant(plant, name, factor)
                problem = bound_problem(
                    sized, road, hold_periods=hold_periods, duration_s=base.duration_s
                )
                lq = linear_quadratic(problem)
                linear_baseline = evaluate(lq, np.zeros(problem.intervals), problem)[0]
                bound = solve_constrained_bound(problem, lq, working_set=working)
                working = bound.working_set
                causal = np.nan
                if controller is not None:
                    run = simulate(road, controller(sized), duration_s=problem.duration_s)
                    causal = float(run.seat_evaluation().total_m_s2)
                peak = np.max(np.abs(sized.u0 + bound.command)) / problem.u_bounds[1]
                rows.append(
                    PumpSizingRow(
                        name, factor, sized.parameter(name), baseline_a, linear_baseline,
                        bound.a_total_m_s2,
                        causal, float(peak), bound.max_violation, bound.rounds,
                        bound.converged, bound.solve_s,
                    )
                )  # fmt: skip
                bar.update()
    return rows


def write_csv(rows: Sequence[PumpSizingRow], path: str | Path) -> Path:
    """The study as CSV, one row per pump size (atomically)."""
    fields = list(PumpSizingRow.__dataclass_fields__)

    def write(temporary: Path) -> None:
        lines = [",".join(fields)]
        for row in rows:
            values = [getattr(row, f) for f in fields]
            lines.append(",".join(v if isinstance(v, str) else f"{v:.9g}" for v in values))
        temporary.write_text("\n".join(lines) + "\n", encoding="utf-8")

    return write_atomically(path, write, (".csv",), "pump-sizing CSV")


def plot_pump_sizing(
    rows: Sequence[PumpSizingRow], path: str | Path, *, title: str = "", controller: str = ""
) -> Path:
    """Figure: a_total of the baseline, the bound and the controller against each parameter."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    names = list(dict.fromkeys(row.parameter for row in rows))
    figure = Figure(figsize=(4.0 * len(names), 4.0), layout="constrained")
    FigureCanvasAgg(figure)
    panels = np.atleast_1d(figure.subplots(1, len(names), sharey=True))
    for panel, name in zip(panels, names, strict=True):
        mine = sorted((r for r in rows if r.parameter == name), key=lambda r: r.factor)
        factor = np.array([r.factor for r in mine])
        nominal = mine[0].value / mine[0].factor
        panel.plot(factor, [r.baseline_a_total_m_s2 for r in mine], "k--", lw=1, label="baseline")
        linear = max(r.linear_baseline_a_total_m_s2 for r in mine)  # off scale: in the legend
        panel.plot([], [], " ", label=f"baseline on the linear plant: {linear:.2f}")
        panel.plot(factor, [r.bound_a_total_m_s2 for r in mine], "o-", label="constrained bound")
        causal = [r.controller_a_total_m_s2 for r in mine]
        if np.any(np.isfinite(causal)):
            panel.plot(factor, causal, "s-", label=controller or "controller")
        panel.axvline(1.0, color="grey", lw=0.6, ls=":")
        panel.set_xlabel(f"{name} / shipped ({nominal:.3g} {PUMP_PARAMETERS[name]})")
        panel.grid(alpha=0.3)
    panels[0].set_ylabel("a_total [m/s²]")
    panels[0].legend(fontsize=8)
    figure.suptitle(title, fontsize=10)

    def write(temporary: Path) -> None:
        figure.savefig(temporary, format="png", dpi=110)

    return write_atomically(path, write, (".png",), "pump-sizing figure")
