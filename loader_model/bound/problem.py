r"""The optimal-control problem behind the bound: grid, road samples, limits, end conditions.

The command is piecewise constant on a control grid of ``hold_periods`` controller periods
(M × 1 ms): u_j = V_p,ref over periods jM … jM + M − 1, so that a controller that plays the
table back (:func:`~loader_model.bound.replay.playback_controller`) reproduces it exactly in the
simulator. The run has K_s = N M periods (the course's duration rounded down to whole control
intervals) with the road input w_k = w(k h) of :func:`~loader_model.simulation.simulator.
exogenous_table`, the table the simulator reads.

Constraints (Table 2, section 2.4): the command |u_j| ≤ 0.99 V_p,max and the displacement rate
|V̇_p| ≤ 0.99 V̇_p,max (the plant's C¹ saturations are exact below 99 % of their limits, so the
optimal trajectory stays where the model is exact), the chamber pressures between cavitation
(absolute 0 Pa) and the relief setting p_relief, and the piston inside its stroke [0, stroke].
Start: the static equilibrium (x0, u0; :mod:`~loader_model.plant.equilibrium`), filters at rest.
End: the boom back at its static stroke position, the pump at its static displacement and at
rest (V_p = V_p0, V̇_p = 0); the chassis and the oil settle by themselves during the course's
settle time (their end values are reported, not imposed: the tyre anchors are not controllable).

Every index comes from the plant's machine (:class:`~loader_model.plant.layout.PlantLayout` of
the scenario): its states, outputs and limits, so the problem is the same for any described
machine whose boom is driven by the pump's closed circuit. A machine with a valve-controlled
circuit (a spool command, no pump displacement) is refused.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.plant.components import ATMOSPHERIC_PRESSURE_PA
from loader_model.plant.layout import CIRCUITS, PlantLayout
from loader_model.plant.scenario import PlantScenario
from loader_model.simulation.controllers import CONTROLLER_PERIOD_S
from loader_model.simulation.simulator import exogenous_table
from loader_model.simulation.travel import RoadInput

__all__ = [
    "DEFAULT_HOLD_PERIODS",
    "LIMIT_FRACTION",
    "MAX_INTERVALS",
    "PATH_SIGNALS",
    "BoundProblem",
    "bound_problem",
    "pump_states",
    "require_pump_circuit",
]

#: Controller periods per command value (10 ms: 50 Hz command bandwidth, above Fig. 9's pump).
DEFAULT_HOLD_PERIODS = 10
#: Fraction of the pump's limits the optimum may use (the saturations are exact below it).
LIMIT_FRACTION = 0.99
#: Most control intervals one problem may have (60 s at 10 ms; memory and time grow with it).
MAX_INTERVALS = 6000
#: Plant outputs bounded along the trajectory, at every controller period.
PATH_SIGNALS: tuple[str, ...] = ("p_A", "p_B", "x_piston")


@dataclass(frozen=True, eq=False)
class BoundProblem:
    """One bound problem: plant, road samples, grid and limits (module notes).

    Attributes
    ----------
    plant : PlantScenario
        The plant and its static equilibrium.
    exogenous : numpy.ndarray
        (K_s + 1, 11) plant exogenous input w_k at t_k = k h.
    hold_periods : int
        M, controller periods per command value.
    intervals : int
        N, command values.
    period_s : float
        h in s.
    u_bounds : tuple of float
        Command bounds in m³/rev.
    rate_limit : float
        Bound on |V̇_p| in m³/(rev s).
    path_lower, path_upper : numpy.ndarray
        Bounds of :data:`PATH_SIGNALS` (Pa, Pa, m).
    name : str
        The course's label.
    """

    plant: PlantScenario
    exogenous: np.ndarray
    hold_periods: int
    intervals: int
    period_s: float
    u_bounds: tuple[float, float]
    rate_limit: float
    path_lower: np.ndarray
    path_upper: np.ndarray
    name: str = ""

    @property
    def periods(self) -> int:
        """K_s = N M controller periods."""
        return self.intervals * self.hold_periods

    @property
    def duration_s(self) -> float:
        """K_s h in s."""
        return self.periods * self.period_s

    @property
    def layout(self) -> PlantLayout:
        """The plant's machine (its states, outputs and limits)."""
        return self.plant.layout

    @property
    def end_targets(self) -> dict[str, float]:
        """The end conditions: plant signal name -> static value (module notes)."""
        x0, layout = self.plant.x0, self.plant.layout
        displacement, rate = pump_states(layout)
        return {
            "x_piston": self.plant.output("x_piston"),
            displacement: float(x0[layout.index(displacement)]),
            rate: float(x0[layout.index(rate)]),
        }


def require_pump_circuit(layout: PlantLayout, what: str = "the bound") -> None:
    """Refuse a machine whose boom is not driven by the pump's closed circuit.

    Raises
    ------
    ValueError
        In one line naming the machine, its circuit and what is allowed.
    """
    if layout.circuit != "pump":
        raise ValueError(
            f"machine {layout.name!r} has the {layout.circuit} circuit; {what} is built on the "
            "pump's displacement and its limits: allowed: a machine with the pump circuit "
            '([circuit] kind = "pump")'
        )


def pump_states(layout: PlantLayout) -> tuple[str, str]:
    """The names of the pump's displacement and its rate among ``layout``'s states."""
    state, rate, *_ = CIRCUITS[layout.circuit]
    return state, rate


def _positive_parameter(plant: PlantScenario, name: str) -> float:
    value = plant.parameter(name)
    if not value > 0.0:
        raise ValueError(f"plant parameter {name} must be > 0 for a bound; got {value!r}")
    return value


def bound_problem(
    plant: PlantScenario,
    road: RoadInput,
    *,
    hold_periods: int = DEFAULT_HOLD_PERIODS,
    duration_s: float | None = None,
    max_intervals: int = MAX_INTERVALS,
    name: str = "",
) -> BoundProblem:
    """The bound problem of ``plant`` over ``road`` (module notes).

    Parameters
    ----------
    plant : PlantScenario
        Plant and equilibrium (:func:`~loader_model.plant.scenario.resolve_plant`).
    road : RoadInput
        Road table (:func:`~loader_model.simulation.simulator.course_input`).
    hold_periods : int
        M, controller periods per command value, 1 … 100.
    duration_s : float, optional
        Horizon (default: the road table's), rounded down to whole control intervals.
    max_intervals : int
        Largest N accepted.

    Raises
    ------
    ValueError
        Naming the argument: a horizon too long for ``max_intervals`` or shorter than two
        intervals, ``hold_periods`` out of range, a pump limit (V_p,max, V̇_p,max) of zero, a
        machine without the pump circuit (:func:`require_pump_circuit`).
    """
    require_pump_circuit(plant.layout)
    if isinstance(hold_periods, bool) or not isinstance(hold_periods, int | np.integer):
        raise ValueError(f"hold_periods must be an integer; got {hold_periods!r}")
    if not 1 <= hold_periods <= 100:
        raise ValueError(f"hold_periods must be in [1, 100]; got {hold_periods}")
    v_max = _positive_parameter(plant, plant.layout.command_limit)
    vd_max = _positive_parameter(plant, plant.layout.rate_limit)
    _positive_parameter(plant, "omega_p")
    period_s = CONTROLLER_PERIOD_S
    total_s = road.duration_s if duration_s is None else float(duration_s)
    intervals = int(np.floor(total_s / (period_s * hold_periods) + 1e-9))
    if intervals > max_intervals:
        raise ValueError(
            f"duration: {total_s:g} s is {intervals} control intervals of {hold_periods} ms; "
            f"at most {max_intervals} fit one problem (max_intervals): shorten the course or "
            "lengthen hold_periods"
        )
    if intervals < 2:
        raise ValueError(
            f"duration: {total_s:g} s must hold at least 2 control intervals of "
            f"{hold_periods * period_s:g} s"
        )
    periods = intervals * hold_periods
    time_s = np.arange(periods + 1) * period_s
    stroke = plant.parameter("stroke")
    relief = plant.parameter("p_relief")
    lower = {"p_A": -ATMOSPHERIC_PRESSURE_PA, "p_B": -ATMOSPHERIC_PRESSURE_PA, "x_piston": 0.0}
    upper = {"p_A": relief, "p_B": relief, "x_piston": stroke}
    outputs = plant.layout.output_names
    for signal in PATH_SIGNALS:
        if signal not in outputs:  # pragma: no cover - a plant without the signal
            raise ValueError(f"plant output {signal!r} is missing; outputs: {outputs}")
    return BoundProblem(
        plant=plant,
        exogenous=exogenous_table(road, time_s),
        hold_periods=int(hold_periods),
        intervals=intervals,
        period_s=period_s,
        u_bounds=(-LIMIT_FRACTION * v_max, LIMIT_FRACTION * v_max),
        rate_limit=LIMIT_FRACTION * vd_max,
        path_lower=np.array([lower[s] for s in PATH_SIGNALS]),
        path_upper=np.array([upper[s] for s in PATH_SIGNALS]),
        name=name,
    )
