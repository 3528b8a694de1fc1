"""The nonlinear runs of a design check: each condition driven by the design, the baseline and
the passive accumulator, and what each run shows.

A condition (:class:`~loader_model.experiments.design_check.envelope.Condition`) is driven as the
Table 6 trials are (section 5.3): the closed loop at 1 kHz with the sensors' noise of
:data:`~loader_model.experiments.trials.TRIAL_SENSOR_NOISE`, seeded by the condition, from the
static equilibrium, with a settle window on flat ground after the road. The baseline holds the
pump's static command behind closed load-holding valves, the passive run connects the
accumulator (section 5.3, the commercial ride control). A run the simulator stops, outside the
model's range of validity or in a failed solve, is recorded as such with its reason, never as a
number.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.experiments.design_check.envelope import COURSE_PREFIX, Condition, Envelope

if TYPE_CHECKING:
    from loader_model.control.settings import ControllerSettings
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = [
    "COMPARED",
    "Design",
    "RunOutcome",
    "condition_course",
    "condition_plant",
    "condition_scenario",
    "run_condition",
]

#: The runs of every condition: the design first, then what it is judged against.
COMPARED: tuple[str, ...] = ("design", "baseline", "passive")


@dataclass(frozen=True)
class Design:
    """What is checked: a ride controller with its settings on a machine.

    Attributes
    ----------
    settings : ControllerSettings
        The controller's settings (for the skyhook its gains K_fb, Table 3).
    controller : str
        ``"skyhook"`` or ``"virtual-accumulator"`` (section 3).
    machine : str
        A machine name or description file (default the skid-steer), as given.
    params : str or None
        The machine's parameter file (default its shipped one).
    layout : PlantLayout
        The machine resolved once when the design is made (default: from ``machine``); a worker
        process that unpickles the design resolves it again through the verified registry.
    """

    settings: ControllerSettings
    controller: str = "skyhook"
    machine: str = "skid_steer"
    params: str | None = None
    layout: PlantLayout = field(default=None, compare=False, repr=False)  # type: ignore[assignment]

    def __post_init__(self) -> None:
        if self.layout is None:
            from loader_model.plant.layout import plant_layout

            object.__setattr__(self, "layout", plant_layout(self.machine))


@dataclass(frozen=True)
class RunOutcome:
    """What one run of one condition shows (nan where a stopped run has no value).

    Attributes
    ----------
    a_total : float
        ISO 2631-1 a_total at the seat [m/s²] (Eq. 50, k = 1, 1, 0.4 for x, y, pitch).
    weighted_rms : dict of str to float
        Frequency-weighted r.m.s. per axis [m/s² or rad/s²] (Eq. 49).
    command_duty, rate_duty : float
        Share of the run with the pump's command, and its displacement rate, at their limits
        (:func:`~loader_model.simulation.settling.limit_duty`).
    lift_offs : int
        Tyre lift-offs (events ``tyre_off_ground``).
    tail_rms, decay_ratio : float
        Residual pitch acceleration at the end of the settle window [rad/s²] and its ratio to the
        second before (:func:`~loader_model.simulation.settling.settle_measure`).
    persistent : bool
        The motion does not decay after the road (an event of the run).
    stopped : str
        Empty for a finished run, else why the simulator stopped it.
    """

    a_total: float
    weighted_rms: dict[str, float]
    command_duty: float
    rate_duty: float
    lift_offs: int
    tail_rms: float
    decay_ratio: float
    persistent: bool
    stopped: str = ""


def condition_plant(design: Design, load: str, controller: str) -> PlantScenario:
    """The plant of ``load`` on the circuit ``controller`` runs on, resolved once per process."""
    key = (design.layout, design.params, load, controller)
    if key not in _PLANTS:
        from loader_model.plant.plant_parameters import PlantOptions
        from loader_model.plant.scenario import resolve_plant

        options = PlantOptions.for_controller(controller)
        _PLANTS[key] = resolve_plant(design.params, load, options, machine=design.layout)
    return _PLANTS[key]


_PLANTS: dict[tuple[Any, ...], PlantScenario] = {}


def condition_scenario(design: Design, load: str, which: str) -> Any:
    from loader_model.simulation.scenario import ride_scenario

    controller = design.controller if which == "design" else which
    plant = condition_plant(design, load, controller)
    if which != "design":
        return ride_scenario(plant, which)
    norm = None
    if design.layout.machine.is_default and plant.load is not None:
        norm = plant.load.pressure_normalisation
    return ride_scenario(plant, controller, design.settings, pressure_norm_pa=norm)


def condition_course(condition: Condition, envelope: Envelope) -> Any:
    from loader_model.simulation.courses import boards_at_speed, iso8608_course, kmh_to_m_s
    from loader_model.simulation.obstacles import load_course_file

    if condition.road.startswith(COURSE_PREFIX):
        return load_course_file(
            condition.road[len(COURSE_PREFIX) :], condition.speed_kmh, settle_s=envelope.settle_s
        )

    if condition.road == "boards":
        jitter = 0.05 if condition.seed else 0.0  # boards laid by hand, as in Table 6's trials
        return boards_at_speed(
            condition.speed_kmh,
            position_jitter_m=jitter,
            seed=condition.seed,
            settle_s=envelope.settle_s,
        )
    length_m = kmh_to_m_s(condition.speed_kmh) * envelope.road_seconds
    return iso8608_course(
        condition.road,
        condition.speed_kmh,
        length_m=length_m,
        seed=condition.seed,
        settle_s=envelope.settle_s,
    )


def rest_run(design: Design, envelope: Envelope, load: str) -> RunOutcome:
    """The design at rest: on flat ground, driven only by the Table 6 trials' sensor noise
    (seed 0), for the settle window and 2 s more, at 5 km/h or at the speed above which its
    ride control acts (the settings' ``ride_control_min_speed``) when that is higher; its tail
    is the pitch acceleration [rad/s²] r.m.s. it keeps at rest
    (:func:`~loader_model.simulation.settling.settle_measure`)."""
    from loader_model.control.sensors import SensorModel
    from loader_model.experiments.trials import TRIAL_SENSOR_NOISE
    from loader_model.simulation.courses import LEAD_IN_M, Course, kmh_to_m_s
    from loader_model.simulation.roads import RoadProfile
    from loader_model.simulation.simulator import course_input, simulate

    flat = RoadProfile(np.array([0.0, 1.0]), np.zeros(2), "flat ground")
    speed_m_s = max(kmh_to_m_s(5.0), design.settings.ride_control_min_speed)  # control on
    course = Course(flat, speed_m_s, -LEAD_IN_M, envelope.settle_s + 2.0, "flat ground")
    scenario = condition_scenario(design, load, "design")
    result = simulate(
        course_input(course, scenario),
        scenario,
        sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=0),
    )
    return _outcome(result, scenario.plant)


def holds_still(rest: RunOutcome) -> bool:
    """True when the design at rest (:func:`rest_run`) never drives the pump to a limit: its
    motion is the noise's stationary response, not a limit cycle the noise set off."""
    return not rest.stopped and rest.command_duty == 0.0 and rest.rate_duty == 0.0


def rest_level(design: Design, envelope: Envelope, load: str) -> float:
    """The level [rad/s²] a persistence is judged against: the tail of :func:`rest_run` when
    the design holds still at rest, else 0 (an oscillation at rest raises no floor)."""
    rest = rest_run(design, envelope, load)
    return float(rest.tail_rms) if holds_still(rest) else 0.0


def _outcome(result: Any, plant: PlantScenario, stopped: str = "") -> RunOutcome:
    from loader_model.simulation.settling import limit_duty, settle_measure

    evaluation = result.seat_evaluation()
    duty = limit_duty(result.columns, plant.command_limit(), plant.rate_limit())
    settle = settle_measure(result.time_s, result.columns)
    return RunOutcome(
        a_total=float(evaluation.total_m_s2),
        weighted_rms={axis.axis: float(axis.weighted_rms) for axis in evaluation.axes},
        command_duty=duty.command,
        rate_duty=duty.rate,
        lift_offs=sum(event.kind == "tyre_off_ground" for event in result.events),
        tail_rms=settle.tail_rms,
        decay_ratio=settle.decay_ratio,
        persistent=any(event.kind == "persistent_oscillation" for event in result.events),
        stopped=stopped,
    )


def _stopped(reason: str) -> RunOutcome:
    nan = float("nan")
    return RunOutcome(nan, {}, nan, nan, 0, nan, nan, False, reason)


def run_condition(
    design: Design, envelope: Envelope, condition: Condition
) -> dict[str, RunOutcome]:
    """Drive ``condition`` with the design, the baseline and the passive accumulator
    (:data:`COMPARED`, module notes)."""
    from loader_model.control.sensors import SensorModel
    from loader_model.experiments.trials import TRIAL_SENSOR_NOISE
    from loader_model.simulation.simulator import course_input, simulate
    from loader_model.simulation.validity_check import ModelValidityError, SimulationError

    course = condition_course(condition, envelope)
    outcomes: dict[str, RunOutcome] = {}
    gated = False  # the design's ride control is off at this speed: its run is the baseline's
    for which in COMPARED:
        if which == "baseline" and gated:
            outcomes[which] = outcomes["design"]
            continue
        scenario = condition_scenario(design, condition.load, which)
        gated = which == "design" and scenario.at_speed(course.speed_m_s) is not scenario
        try:
            result = simulate(
                course_input(course, scenario),
                scenario,
                sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=condition.seed),
            )
        except ModelValidityError as error:
            outcomes[which] = _stopped(f"outside the model's validity: {error}".splitlines()[0])
            continue
        except SimulationError as error:
            outcomes[which] = _stopped(f"failed solve: {error}".splitlines()[0])
            continue
        outcomes[which] = _outcome(result, scenario.plant)
    return outcomes
