"""One sample of a study: build its plant and road, run every controller, one row per controller.

Composes what exists: the parameter files' validated :func:`~loader_model.parameters.sets.replace`,
one :class:`~loader_model.plant.scenario.PlantScenario` per sample (vector and static equilibrium,
resolved once and shared by the road input and every controller; ``passive`` connects the
accumulator, a second equilibrium), the courses, the simulator and the ride controllers. Nothing
here stops a study: a sample whose plant fails the parameter checks, or a run that raises
(:class:`~loader_model.simulation.simulator.SimulationError` when the integration leaves the
finite numbers, e.g. an unstable closed loop), gives rows with ``failed`` true and the reason.
CasADi Functions are built once per worker process (module-level caches here and in
:mod:`~loader_model.simulation.stepper`), never per sample.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.robustness.gains import Gains, max_pole_real
from loader_model.robustness.outcomes import settle_columns
from loader_model.robustness.sampling import SampleSpec, sample_plant
from loader_model.robustness.sensors import (
    corrupted_fixed_point,
    sensor_controller,
    sensor_errors,
    sensor_model,
)
from loader_model.robustness.study import Study
from loader_model.simulation.result import command_column
from loader_model.simulation.settling import COMMAND_AT_LIMIT
from loader_model.simulation.simulator import course_input, simulate

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = ["AXES", "run_batch", "run_sample"]

#: ISO 2631-1 axes of the seat evaluation (x = fore-aft, z = vertical, pitch).
AXES: tuple[str, ...] = ("x", "z", "pitch")
_CONTROLLERS: dict[str, Any] = {}
_IDEAL = np.array([1.0] * 5 + [0.0] * 5)
#: Controllers in which the pump holds its static command (no sensors read).
_HOLDING = ("baseline", "passive")


def _hold_controller(layout: PlantLayout) -> Any:
    """The baseline's constant command as its one setting, built once per process and machine
    ``layout`` (one compiled period for every sampled plant)."""
    from loader_model.simulation.controllers import hold_command_controller

    key = "hold" if layout.machine.is_default else ("hold", layout)
    if key not in _CONTROLLERS:
        _CONTROLLERS[key] = hold_command_controller(layout)
    return _CONTROLLERS[key]


def _course(study: Study, spec: SampleSpec) -> Any:
    from loader_model.simulation.courses import iso8608_course, paper_course

    if study.road == "course":
        course = paper_course(
            spec.speed_kmh, position_jitter_m=study.position_jitter_m, seed=spec.road_seed
        )
        return dataclasses.replace(course, speed_m_s=course.speed_m_s * spec.speed_factor)
    speed = spec.speed_kmh * spec.speed_factor
    return iso8608_course(
        study.road_class, speed, length_m=study.road_length_m, seed=spec.road_seed
    )


def _metrics(result: Any, max_displacement: float) -> dict[str, float]:
    """Seat values (Eq. 49, 50), pressure peaks, events. Pump saturation: the time the command
    is at or beyond V_p,max (the controllers clip at the limit, so the simulator's
    ``pump_saturation`` event, strictly beyond it, does not see them)."""
    evaluation = result.seat_evaluation()
    rms = {axis.axis: float(axis.weighted_rms) for axis in evaluation.axes}
    period = float(result.metadata["period_s"])
    at_limit = np.abs(result[command_column(result.columns)]) >= max_displacement * COMMAND_AT_LIMIT
    saturated = period * np.count_nonzero(at_limit)
    return {
        **{f"a_w_{axis}": rms.get(axis, math.nan) for axis in AXES},
        "a_total": float(evaluation.total_m_s2),
        "p_A_max_Pa": float(np.max(result["p_A"])),
        "p_A_min_Pa": float(np.min(result["p_A"])),
        "p_B_max_Pa": float(np.max(result["p_B"])),
        "pump_saturation_s": float(saturated),
        "tyre_lift_offs": float(sum(e.kind == "tyre_off_ground" for e in result.events)),
        # decay after the road's excitation, for the persistent-oscillation category
        **settle_columns(result),
    }


_EMPTY = dict.fromkeys(
    [
        *(f"a_w_{a}" for a in AXES),
        *("a_total", "p_A_max_Pa", "p_A_min_Pa", "p_B_max_Pa"),
        *("pump_saturation_s", "tyre_lift_offs", "settle_ratio", "settle_tail_rms"),
    ],
    math.nan,
)


def _pressure_norm(plant: PlantScenario) -> float:
    """‖p_A‖∞ of the controllers' normalisation: the load's (skid-steer) or the machine's."""
    if plant.is_default_machine:
        return float(plant.load.pressure_normalisation)
    from loader_model.plant.machine_parameters import pressure_norm

    return pressure_norm(plant.output("p_A"))


def _reason(error: BaseException) -> str:
    return f"{type(error).__name__}: {error}"[:500]


def _run(
    study: Study,
    gains: Gains,
    name: str,
    plant: PlantScenario,
    load: tuple[str, float],
    road: Any,
    errors: np.ndarray,
    sensors: Any = None,
) -> dict:
    """Simulate controller ``name`` on one plant; ``load`` is (case, pressure norm ‖p_A‖ in Pa),
    ``errors`` the sensors' gains and offsets (:func:`~loader_model.robustness.sensors.sensor_errors`),
    ``sensors`` their noise (:func:`~loader_model.robustness.sensors.sensor_model`). The plant's
    equilibrium is taken from ``plant``, on the circuit of the controller
    (:meth:`~loader_model.plant.plant_parameters.PlantOptions.with_controller`: baseline and
    passive on closed load-holding valves, passive with the accumulator; a new equilibrium)."""
    from loader_model.control.settings import default_settings
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.simulation.ride_control import plant_controller_setup
    from loader_model.simulation.scenario import Scenario, closed_loop

    plant = plant.with_options((plant.options or PlantOptions()).with_controller(name))
    if name in _HOLDING:
        scenario = closed_loop(plant, _hold_controller(plant.layout), [plant.u0], name=name)
    else:
        kind = "virtual-accumulator" if name == "virtual-accumulator" else "skyhook"
        settings = default_settings()
        if name in gains:
            settings = dataclasses.replace(settings, k_fb=gains[name][load[0]])
        vector, state = plant_controller_setup(kind, plant, load[1], settings)
        if np.any(errors != _IDEAL):
            state = corrupted_fixed_point(kind, vector, plant, errors)
        controller = sensor_controller(kind, plant.layout)
        scenario = Scenario(plant, controller, np.concatenate([vector, errors]), state, name)
    result = simulate(
        road, scenario, duration_s=study.duration_s, sensors=None if name in _HOLDING else sensors
    )
    return _metrics(result, plant.command_limit())


def run_sample(study: Study, gains: Gains, spec: SampleSpec) -> list[dict[str, Any]]:
    """Rows of one sample, one per controller of the study (module notes).

    Parameters
    ----------
    study : Study
        The study (road, duration, controllers).
    gains : Gains
        K_fb per gain-based controller and load (:func:`~loader_model.robustness.gains.resolve_gains`).
    spec : SampleSpec
        The sample.

    Returns
    -------
    list of dict
        Baseline first; columns of :func:`~loader_model.robustness.table.result_schema`. A failure
        gives ``failed`` True and ``reason``; it never raises for a bad plant or run.
    """
    head = {
        "sample": spec.index,
        "speed_kmh": spec.speed_kmh,
        "speed_factor": spec.speed_factor,
        "load": spec.load,
        "road_seed": spec.road_seed,
        **dict(spec.values),
    }
    rows = []
    errors = sensor_errors(dict(spec.values))
    noise = sensor_model(dict(spec.values), spec.road_seed)
    try:
        plant = sample_plant(spec, study.layout, study.params)
        road = course_input(_course(study, spec), plant)
        setup_error = None
    except Exception as error:  # a failed sample never stops the study
        setup_error = _reason(error)
    poles: dict[str, float] = {}
    if setup_error is None and gains:
        try:
            speed = spec.speed_kmh * spec.speed_factor
            gain_list = [gains[n][spec.load] for n in gains]
            reals = max_pole_real(plant, spec.load, speed, study.road_class, gain_list)
            poles = dict(zip(gains, reals, strict=True))
        except Exception:  # the margin is then reported as missing (NaN)
            poles = {}
    for name in study.controllers:
        row = {**head, "controller": name, **_EMPTY, "max_pole_real": poles.get(name, math.nan)}
        if setup_error is not None:
            row |= {"failed": True, "reason": setup_error}
        else:
            try:
                case = (spec.load, _pressure_norm(plant))
                row |= _run(study, gains, name, plant, case, road, errors, noise)
                row |= {"failed": False, "reason": ""}
            except Exception as error:  # a failed run never stops the study
                row |= {"failed": True, "reason": _reason(error)}
        rows.append(row)
    baseline = rows[0]["a_total"]
    for row in rows:
        row["change_percent"] = 100.0 * (row["a_total"] - baseline) / baseline
    return rows


def run_batch(study: Study, gains: Gains, specs: list[SampleSpec]) -> list[dict[str, Any]]:
    """Rows of several samples, in order (one engine task)."""
    return [row for spec in specs for row in run_sample(study, gains, spec)]
