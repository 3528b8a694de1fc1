"""The four ride controllers of one machine over one course: a_total and its change.

For any machine of :mod:`loader_model.machines` (the skid-steer's Table 6 comparison has its own
trials in the experiments): the baseline, the passive accumulator, the virtual accumulator and
the skyhook (Table 3's settings, or a designed settings file) each drive the course from their
static equilibrium; a row per controller holds the ISO 2631-1 total value at the seat pad
(Eq. 50, with the paper's k factors) and its change against the baseline's.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from loader_model.plant.layout import SKID_STEER, PlantLayout

__all__ = ["COMPARED_CONTROLLERS", "ComparisonRow", "compare_controllers", "format_comparison"]

#: The controllers compared, in the order of the rows.
COMPARED_CONTROLLERS: tuple[str, ...] = ("baseline", "passive", "virtual-accumulator", "skyhook")


@dataclass(frozen=True)
class ComparisonRow:
    """One controller's run over the course.

    Attributes
    ----------
    controller : str
        Its name (``skyhook (designed)`` for a settings file).
    a_total : float
        ISO 2631-1 total value at the seat, m/s² (Eq. 50).
    change_percent : float
        100 (a_total / a_total,baseline − 1); 0 for the baseline.
    valid : bool
        True when the run stayed in the model's range of validity (else a_total is NaN).
    """

    controller: str
    a_total: float
    change_percent: float
    valid: bool = True


def _a_total(scenario: Any, course: Any, substeps: int | None) -> float:
    from loader_model.simulation.simulator import ModelValidityError, course_input, simulate

    steps = {} if substeps is None else {"substeps": substeps}
    try:
        result = simulate(course_input(course, scenario), scenario, **steps)
    except ModelValidityError:
        return float("nan")
    return float(result.seat_evaluation().total_m_s2)


def compare_controllers(
    layout: PlantLayout = SKID_STEER,
    params: Any = None,
    load: str | None = "empty",
    *,
    speed_kmh: float = 9.0,
    course: Any = None,
    settings: str | Path | Any = None,
    substeps: int | None = None,
) -> list[ComparisonRow]:
    """Run the four controllers over ``course`` (default the paper's at ``speed_kmh``).

    Parameters
    ----------
    layout : PlantLayout
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`).
    params, load
        Its parameter file (None: the shipped one) and load case
        (:func:`~loader_model.plant.scenario.resolve_plant`).
    speed_kmh : float
        Speed of the paper's course when ``course`` is None.
    course : Course, optional
        Another course (:mod:`~loader_model.simulation.courses`).
    settings : ControllerSettings, str or pathlib.Path, optional
        The skyhook's settings (default Table 3's); with them the row is ``skyhook (designed)``.
    substeps : int, optional
        ROS2 steps per period (default the simulator's).

    Returns
    -------
    list of ComparisonRow
        In the order of :data:`COMPARED_CONTROLLERS`.
    """
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import resolve_scenario

    course = paper_course(speed_kmh) if course is None else course
    values: list[tuple[str, float]] = []
    for name in COMPARED_CONTROLLERS:
        given = settings if name == "skyhook" else None
        scenario = resolve_scenario(params, load, controller=name, settings=given, machine=layout)
        label = f"{name} (designed)" if given is not None else name
        values.append((label, _a_total(scenario, course, substeps)))
    base = values[0][1]
    return [
        ComparisonRow(name, value, 100.0 * (value / base - 1.0), value == value)
        for name, value in values
    ]


def format_comparison(rows: list[ComparisonRow], title: str = "") -> str:
    """The rows as a plain-text table (a_total in m/s², change against the baseline in %)."""
    lines = [title] if title else []
    lines.append(f"{'controller':<24} {'a_total [m/s^2]':>16} {'vs baseline':>12}")
    for row in rows:
        value = f"{row.a_total:16.4f}" if row.valid else f"{'outside model':>16}"
        change = f"{row.change_percent:+11.1f}%" if row.valid else f"{'-':>12}"
        lines.append(f"{row.controller:<24} {value} {change}")
    return "\n".join(lines)
