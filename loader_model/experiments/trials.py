"""Trials of the Table 6 experiment (section 5.3): the design, seeded randomisation, one run.

The paper's design: 2 speeds (9 km/h with boards 6 m apart, 18 km/h with 9 m) × 2 bucket loads
(340 kg "empty", 770 kg "full") × 4 controllers × 4 trials over five 4 cm boards.

What varies between simulated trials (each drawn from its own seed, module :func:`trial_specs`):

- the driven speed: normal, standard deviation :data:`SPEED_STD_FRACTION` of the nominal speed,
  clipped to ±:data:`SPEED_LIMIT_FRACTION` (a driver holding 9 or 18 km/h by the speedometer);
- the board positions: each board shifted by a normal of standard deviation
  :data:`POSITION_JITTER_M` (boards laid by hand).

- the sensors' noise: white noise of :data:`TRIAL_SENSOR_NOISE` on the controller's five
  readings (:class:`~loader_model.control.sensors.SensorModel`, applied inside the compiled 1 kHz
  loop), a fresh draw per trial. The paper names no sensor types or noise levels; the values
  are assumptions stated beside the constant.

Every (speed, load, controller, trial) draws independently (the real trials were separate
drives), from ``numpy.random.SeedSequence([seed, speed index, load index, controller index,
trial])``: the same seed gives the same trials whatever the order or the worker that runs them.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "CONTROLLERS",
    "DESIGNED_CONTROLLERS",
    "LOADS",
    "POSITION_JITTER_M",
    "SPEEDS_KMH",
    "SPEED_LIMIT_FRACTION",
    "SPEED_STD_FRACTION",
    "TRIAL_SENSOR_NOISE",
    "TrialOutcome",
    "TrialSpec",
    "run_trial",
    "trial_specs",
]

#: Nominal speeds of section 5.3 in km/h ("low", "high").
SPEEDS_KMH: tuple[float, ...] = (9.0, 18.0)
#: Bucket load cases ("low" 340 kg, "high" 770 kg).
LOADS: tuple[str, ...] = ("empty", "full")
#: The four control conditions of section 5.3, baseline first.
CONTROLLERS: tuple[str, ...] = ("baseline", "passive", "virtual-accumulator", "skyhook")
#: The skyhook with designed gains (:mod:`~loader_model.experiments.designed_gains`), run as two
#: more rows of the matrix; their trials carry the gains in :attr:`TrialSpec.k_fb`.
DESIGNED_CONTROLLERS: tuple[str, ...] = ("skyhook-lqr", "skyhook-optimised", "skyhook-refined")
#: Standard deviation of the driven speed as a fraction of the nominal speed (assumed).
SPEED_STD_FRACTION = 0.02
#: Largest deviation of the driven speed from the nominal speed, as a fraction (assumed).
SPEED_LIMIT_FRACTION = 0.05
#: Standard deviation of each board's position in m (assumed: boards laid by hand).
POSITION_JITTER_M = 0.05
#: Per-sample noise of the sensors f_Hx, f_Hy, f_Ny [m/s^2], phi [rad], p_A [Pa] at 1 kHz
#: (assumed, the paper gives none): a MEMS accelerometer of 150 ug/sqrt(Hz) over 500 Hz is
#: 0.033 m/s^2; a boom-angle encoder of 0.05 deg; a pressure transmitter of 0.1 % of 400 bar.
TRIAL_SENSOR_NOISE: tuple[float, ...] = (0.033, 0.033, 0.033, 8.7e-4, 4.0e4)


@dataclass(frozen=True)
class TrialSpec:
    """One simulated drive: condition, controller and what the seed drew.

    Attributes
    ----------
    speed_kmh : float
        Nominal speed (9 or 18 km/h).
    load : str
        ``"empty"`` or ``"full"``.
    controller : str
        One of :data:`CONTROLLERS`.
    trial : int
        Trial number from 0.
    speed_factor : float
        Driven speed over nominal speed.
    course_seed : int
        Seed of the board-position jitter.
    duration_s : float or None
        Simulated time (None: the whole course).
    k_fb : tuple of 4 float or None
        Skyhook gains of a designed controller (None: the settings file's, Table 3).
    """

    speed_kmh: float
    load: str
    controller: str
    trial: int
    speed_factor: float
    course_seed: int
    duration_s: float | None = None
    k_fb: tuple[float, ...] | None = None


@dataclass(frozen=True)
class TrialOutcome:
    """ISO 2631-1 result of one trial: a_total (Eq. 50) and the weighted r.m.s. per axis."""

    spec: TrialSpec
    a_total_m_s2: float
    weighted_rms: dict[str, float]
    lift_offs: int


def trial_specs(
    seed: int,
    trials: int,
    *,
    speeds_kmh: tuple[float, ...] = SPEEDS_KMH,
    loads: tuple[str, ...] = LOADS,
    controllers: tuple[str, ...] = CONTROLLERS,
    duration_s: float | None = None,
    designed: dict[str, tuple[float, ...]] | None = None,
) -> list[TrialSpec]:
    """All trials of the experiment, each drawn from its own seed (module notes).

    Parameters
    ----------
    seed : int
        Base seed, >= 0.
    trials : int
        Trials per speed, load and controller, >= 1.
    speeds_kmh, loads, controllers : tuple
        The factors (default: the paper's).
    duration_s : float, optional
        Simulated time of each trial (default: the whole course).
    designed : dict, optional
        :data:`DESIGNED_CONTROLLERS` name -> skyhook gains, run after ``controllers``.

    Returns
    -------
    list of TrialSpec
        In the order speed, load, controller, trial.
    """
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0; got {seed!r}")
    if isinstance(trials, bool) or not isinstance(trials, int | np.integer) or trials < 1:
        raise ValueError(f"trials must be an integer >= 1; got {trials!r}")
    designed = dict(designed or {})
    unknown = sorted(set(designed) - set(DESIGNED_CONTROLLERS))
    if unknown:
        raise ValueError(f"designed controllers {unknown}; allowed: {list(DESIGNED_CONTROLLERS)}")
    every = (*CONTROLLERS, *DESIGNED_CONTROLLERS)
    specs = []
    for i, speed in enumerate(speeds_kmh):
        for j, load in enumerate(loads):
            for k, controller in enumerate((*controllers, *designed)):
                index = every.index(controller) if controller in every else k
                gains = designed.get(controller)
                for trial in range(int(trials)):
                    sequence = np.random.SeedSequence([int(seed), i, j, index, trial])
                    rng = np.random.default_rng(sequence)
                    factor = 1.0 + float(
                        np.clip(
                            rng.normal(0.0, SPEED_STD_FRACTION),
                            -SPEED_LIMIT_FRACTION,
                            SPEED_LIMIT_FRACTION,
                        )
                    )
                    course_seed = int(rng.integers(0, 2**31 - 1))
                    specs.append(
                        TrialSpec(
                            speed, load, controller, trial, factor, course_seed, duration_s, gains
                        )
                    )
    return specs


_PLANTS: dict[tuple[str, bool], np.ndarray] = {}


def _plant(load: str, accumulator: bool) -> np.ndarray:
    """Plant parameters per load and accumulator, built once per process."""
    from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector

    key = (load, accumulator)
    if key not in _PLANTS:
        _PLANTS[key] = plant_parameter_vector(None, load, PlantOptions(accumulator=accumulator))
    return _PLANTS[key]


def controller_arguments(
    controller: str, load: str, params: np.ndarray, k_fb: tuple[float, ...] | None = None
) -> dict[str, Any]:
    """Keyword arguments of :func:`~loader_model.simulation.simulator.simulate` for ``controller``
    (baseline and passive: the pump holds its static command; the designed controllers: the
    skyhook with gains ``k_fb``)."""
    from loader_model.control.settings import default_settings, with_gains
    from loader_model.parameters.sets import bucket_load
    from loader_model.simulation.ride_control import controller_setup, plant_controller

    if controller not in (*CONTROLLERS, *DESIGNED_CONTROLLERS):
        allowed = [*CONTROLLERS, *DESIGNED_CONTROLLERS]
        raise ValueError(f"controller {controller!r} is unknown; allowed: {allowed}")
    if controller in ("baseline", "passive"):
        return {}
    law, settings = controller, None
    if controller in DESIGNED_CONTROLLERS:
        if k_fb is None:
            raise ValueError(f"controller {controller!r} needs its gains k_fb")
        law, settings = "skyhook", with_gains(default_settings(), k_fb, controller)
    vector, state = controller_setup(
        law, params, bucket_load(load).pressure_normalisation, settings=settings
    )
    return {
        "controller": plant_controller(law),
        "settings": vector,
        "controller_state": state,
    }


def plant_for(controller: str, load: str) -> np.ndarray:
    """Plant parameters of ``load`` with the accumulator connected only for ``passive``."""
    return _plant(load, controller == "passive")


@functools.cache
def _trial_arguments(controller: str, load: str, k_fb: tuple[float, ...] | None) -> dict[str, Any]:
    """:func:`controller_arguments` on :func:`plant_for`, once per process and condition (the
    controller's fixed point takes a matrix logarithm; every trial of a condition shares it)."""
    return controller_arguments(controller, load, plant_for(controller, load), k_fb)


def run_trial(spec: TrialSpec) -> TrialOutcome:
    """Simulate one trial over the paper's course and evaluate the seat (section 5.3)."""
    from loader_model.control.sensors import SensorModel
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input, simulate

    params = plant_for(spec.controller, spec.load)
    course = paper_course(
        spec.speed_kmh, position_jitter_m=POSITION_JITTER_M, seed=spec.course_seed
    )
    course = dataclasses.replace(course, speed_m_s=course.speed_m_s * spec.speed_factor)
    result = simulate(
        course_input(course, params),
        params,
        sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=spec.course_seed),
        duration_s=spec.duration_s,
        **_trial_arguments(spec.controller, spec.load, spec.k_fb),
    )
    evaluation = result.seat_evaluation()
    return TrialOutcome(
        spec,
        float(evaluation.total_m_s2),
        {axis.axis: float(axis.weighted_rms) for axis in evaluation.axes},
        sum(event.kind == "tyre_off_ground" for event in result.events),
    )
