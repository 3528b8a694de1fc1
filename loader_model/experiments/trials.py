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

Which model a trial runs on is its :attr:`TrialSpec.variant`
(:class:`~loader_model.experiments.variant.ModelVariant`: circuit states, seat pad and occupant,
the tyres' envelope, Table 3's gains, parameter values; default the model as built). It draws
nothing, so every variant sees the same speeds, boards and noise.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.experiments.variant import AS_BUILT, ENVELOPES, ModelVariant

if TYPE_CHECKING:
    from loader_model.plant.scenario import PlantScenario
    from loader_model.simulation.scenario import Scenario

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
    "controller_arguments",
    "controller_scenario",
    "plant_for",
    "plant_scenario",
    "run_trial",
    "trial_scenario",
    "trial_specs",
]

#: Nominal speeds of section 5.3 in km/h ("low", "high").
SPEEDS_KMH: tuple[float, ...] = (9.0, 18.0)
#: Bucket load cases ("low" 340 kg, "high" 770 kg).
LOADS: tuple[str, ...] = ("empty", "full")
#: The four control conditions of section 5.3, baseline first.
CONTROLLERS: tuple[str, ...] = ("baseline", "passive", "virtual-accumulator", "skyhook")
#: The skyhook with other gains (:mod:`~loader_model.experiments.designed_gains`): Table 3 as
#: printed (k_φ = −0.22, unstable: errata 12) and the designed ones, run as more rows of the
#: matrix; their trials carry the gains in :attr:`TrialSpec.k_fb`.
DESIGNED_CONTROLLERS: tuple[str, ...] = (
    "skyhook-printed",
    "skyhook-lqr",
    "skyhook-optimised",
    "skyhook-refined",
)
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
    variant : ModelVariant
        The model the trial runs on (module notes).
    """

    speed_kmh: float
    load: str
    controller: str
    trial: int
    speed_factor: float
    course_seed: int
    duration_s: float | None = None
    k_fb: tuple[float, ...] | None = None
    variant: ModelVariant = AS_BUILT

    @property
    def envelope(self) -> str:
        """The tyres' enveloping model of the trial's variant."""
        return self.variant.envelope


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
    envelope: str | None = None,
    variant: ModelVariant = AS_BUILT,
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
    envelope : str, optional
        The tyres' enveloping model of every trial (``"tandem-cam"`` or ``"rigid"``), replacing
        the variant's.
    variant : ModelVariant
        The model of every trial (default: as built).

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
    if envelope is not None:
        if envelope not in ENVELOPES:
            raise ValueError(f"envelope must be one of {list(ENVELOPES)}; got {envelope!r}")
        variant = dataclasses.replace(variant, envelope=envelope)
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
                            speed,
                            load,
                            controller,
                            trial,
                            factor,
                            course_seed,
                            duration_s,
                            gains,
                            variant,
                        )
                    )
    return specs


_PLANTS: dict[tuple[Any, ...], PlantScenario] = {}
_SCENARIOS: dict[tuple[Any, ...], Scenario] = {}


def plant_scenario(load: str, controller: str, variant: ModelVariant = AS_BUILT) -> PlantScenario:
    """The experiment's plant per load and the circuit ``controller`` runs on in ``variant``
    (:meth:`~loader_model.experiments.variant.ModelVariant.plant_options`; the shipped loader
    with the variant's values), resolved once per process
    (:func:`~loader_model.plant.scenario.resolve_plant`)."""
    from loader_model.plant.scenario import resolve_plant

    options = variant.plant_options(controller)
    key = (load, options, variant.values)
    if key not in _PLANTS:
        loader, bucket = variant.parameter_sets(load)
        _PLANTS[key] = resolve_plant(loader, bucket, options)
    return _PLANTS[key]


def _check_controller(controller: str, k_fb: tuple[float, ...] | None) -> None:
    if controller not in (*CONTROLLERS, *DESIGNED_CONTROLLERS):
        allowed = [*CONTROLLERS, *DESIGNED_CONTROLLERS]
        raise ValueError(f"controller {controller!r} is unknown; allowed: {allowed}")
    if controller in DESIGNED_CONTROLLERS and k_fb is None:
        raise ValueError(f"controller {controller!r} needs its gains k_fb")


def controller_scenario(
    controller: str,
    plant: PlantScenario,
    pressure_norm_pa: float,
    k_fb: tuple[float, ...] | None = None,
) -> Scenario:
    """``controller`` on ``plant`` (baseline and passive: the pump holds its static command; the
    designed controllers: the skyhook with gains ``k_fb``); ``pressure_norm_pa`` is ‖p_A‖∞ of the
    bucket load (section 3.3)."""
    from loader_model.control.settings import default_settings, with_gains
    from loader_model.simulation.scenario import ride_scenario

    _check_controller(controller, k_fb)
    if controller in ("baseline", "passive"):
        return ride_scenario(plant, controller)
    law, settings = controller, None
    if controller in DESIGNED_CONTROLLERS:
        law, settings = "skyhook", with_gains(default_settings(), k_fb, controller)
    return ride_scenario(plant, law, settings, pressure_norm_pa=pressure_norm_pa)


def controller_arguments(
    controller: str, load: str, params: np.ndarray, k_fb: tuple[float, ...] | None = None
) -> dict[str, Any]:
    """Keyword arguments of :func:`~loader_model.simulation.simulator.simulate` for ``controller``
    on the plant ``params`` (:func:`controller_scenario`; baseline and passive: none, the pump
    holds its static command)."""
    from loader_model.parameters.sets import bucket_load
    from loader_model.plant.scenario import PlantScenario

    _check_controller(controller, k_fb)
    if controller in ("baseline", "passive"):
        return {}
    plant = PlantScenario.from_vector(params)
    scenario = controller_scenario(
        controller, plant, bucket_load(load).pressure_normalisation, k_fb
    )
    return {
        "controller": scenario.controller,
        "settings": scenario.settings,
        "controller_state": scenario.controller_state,
    }


def plant_for(controller: str, load: str, variant: ModelVariant = AS_BUILT) -> np.ndarray:
    """Plant parameters of ``load`` on the circuit of ``controller`` (:func:`plant_scenario`)."""
    return plant_scenario(load, controller, variant).params


def trial_scenario(
    controller: str,
    load: str,
    k_fb: tuple[float, ...] | None = None,
    variant: ModelVariant = AS_BUILT,
) -> Scenario:
    """The scenario of one condition (:func:`controller_scenario` on :func:`plant_scenario`),
    built once per process, condition and variant: every trial of the condition shares the
    plant's equilibrium and the controller's fixed point (a matrix logarithm). The ``skyhook``
    row runs the variant's Table 3 gains."""
    gains = None if k_fb is None else tuple(float(k) for k in k_fb)
    key = (controller, load, gains, variant)
    if key not in _SCENARIOS:
        plant = plant_scenario(load, controller, variant)
        norm = plant.load.pressure_normalisation
        if controller == "skyhook" and variant.table3_gain != AS_BUILT.table3_gain:
            scenario = controller_scenario("skyhook-printed", plant, norm, variant.table3_gain)
        else:
            scenario = controller_scenario(controller, plant, norm, gains)
        _SCENARIOS[key] = scenario
    return _SCENARIOS[key]


def run_trial(spec: TrialSpec) -> TrialOutcome:
    """Simulate one trial over the paper's course and evaluate the seat (section 5.3)."""
    from loader_model.control.sensors import SensorModel
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input, simulate

    scenario = trial_scenario(spec.controller, spec.load, spec.k_fb, spec.variant)
    course = paper_course(
        spec.speed_kmh, position_jitter_m=POSITION_JITTER_M, seed=spec.course_seed
    )
    course = dataclasses.replace(course, speed_m_s=course.speed_m_s * spec.speed_factor)
    result = simulate(
        course_input(course, scenario, envelope=spec.variant.envelope),
        scenario,
        sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=spec.course_seed),
        duration_s=spec.duration_s,
    )
    evaluation = result.seat_evaluation()
    return TrialOutcome(
        spec,
        float(evaluation.total_m_s2),
        {axis.axis: float(axis.weighted_rms) for axis in evaluation.axes},
        sum(event.kind == "tyre_off_ground" for event in result.events),
    )
