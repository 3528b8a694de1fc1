r"""Skyhook gains optimised on the nonlinear machine with exact derivatives, under the check's
criteria.

The linear comfort design (:mod:`loader_model.control.comfort_design`) minimises a_total on a
random road through the linearised plant; on 40 mm boards the tyres leave the ground and the
linear plant misjudges the ride. Here the cost is the nonlinear closed loop's, over a set of
scenarios S (loads × roads × speeds × seeds, :class:`~loader_model.experiments.design_check.
Envelope`), each relative to the baseline's a_total on the same road,

.. math::

    J(K) = \frac{1}{|S|} \sum_{s \in S} \left(\frac{a_{total,s}(K)}{a_{total,s}^{base}}\right)^2
    \quad (\text{Eq. } 50),

with its gradient exact along each run: CasADi's sensitivities through the simulator's own
period (:func:`~loader_model.simulation.gain_sensitivity.gain_gradient`), not finite
differences. The search is a quasi-Newton (BFGS) descent with an Armijo backtracking line
search, started from the linear comfort design (or gains of the user's), first moved to the
nearest gains whose loop keeps the margin σ on every nominal and sampled plant
(:mod:`~loader_model.experiments.stable_start`; with room, :data:`START_MARGIN_FACTOR` σ), and
scaled toward zero by
:data:`START_SHRINK` while its runs break a constraint below. The check's criteria are constraints that no
accepted step may break (an exact penalty of infinite weight): a candidate is rejected, and the
step shortened, when

- the loop's margin on a load's linearised plant, or on a plant drawn from the robustness
  study's parameter distributions, falls below σ
  (:func:`~loader_model.control.comfort_design.evaluate_gain`; the check asks only for a stable
  loop on the drawn plants, the margin keeps the design off that edge), or K leaves the
  settings' range;
- a scenario's run has a persistent oscillation after the road (above twice the level the
  gains keep at rest with the sensors' noise, as the check judges it), or its pump command or
  displacement rate at their limits for longer than the envelope allows
  (:mod:`~loader_model.simulation.settling`);
- a scenario's a_total exceeds the baseline's by more than the envelope allows, unless the start
  did so too and the candidate improves it.

The result is then checked over the whole envelope by
:func:`~loader_model.experiments.design_check.check_design` before it is written.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from loader_model.experiments.design_check import Condition, Design, Envelope
from loader_model.experiments.design_check.runs import (
    condition_course,
    condition_plant,
    condition_scenario,
    rest_level,
)
from loader_model.experiments.design_check.verdict import ACTUATOR_NAMES, MARGIN_RTOL
from loader_model.experiments.stable_start import START_MARGIN_FACTOR, stable_start
from loader_model.plant.layout import SKID_STEER, PlantLayout

__all__ = [
    "START_MARGIN_FACTOR",
    "START_SHRINK",
    "START_SHRINKS",
    "TRAINING_ENVELOPE",
    "MachineDesign",
    "design_on_machine",
]

#: Factor by which a start whose runs break a constraint (the pump at its limits, a persistent
#: oscillation, a failed run) is scaled toward zero, and how often at most (to 0.7⁶ = 0.12 of
#: it): the linear comfort design of the compact wheel loader rides the pump's limits on the
#: empty bucket's boards at 18 km/h (command 8.2 %, rate 10.6 % of the run, measured).
START_SHRINK = 0.7
START_SHRINKS = 6
#: The scenarios the gains are optimised over by default: both loads, the paper's boards at 9
#: and 18 km/h and an ISO 8608 class C road at 15 km/h.
TRAINING_ENVELOPE = Envelope(
    board_speeds_kmh=(9.0, 18.0), road_classes=("C",), road_speeds_kmh=(15.0,), road_seconds=8.0
)


@dataclass(frozen=True)
class MachineDesign:
    """The gains found on the machine and how.

    Attributes
    ----------
    gain : numpy.ndarray
        K_fb (1 × 4) on the shipped norms.
    start_gain : numpy.ndarray
        K_fb (1 × 4) the descent started from: the given start, or the nearest gain to it that
        keeps the margin on every nominal and sampled plant when the given one does not
        (:func:`~loader_model.experiments.stable_start.nearest_stable_gain`), scaled by
        :data:`START_SHRINK` while its runs break a constraint.
    cost, start_cost : float
        J at the result and at the start (module notes).
    a_total, baseline : dict of str to float
        a_total [m/s²] per scenario at the result, and the baseline's.
    iterations, simulations : int
        Accepted steps, and closed-loop runs with sensitivities.
    rejected : int
        Candidates rejected by a constraint (module notes).
    wall_s : float
        Wall time.
    """

    gain: np.ndarray
    start_gain: np.ndarray
    cost: float
    start_cost: float
    a_total: dict[str, float]
    baseline: dict[str, float]
    iterations: int
    simulations: int
    rejected: int
    wall_s: float


def _settings(gain: np.ndarray, layout: PlantLayout, base: Any = None) -> Any:
    """``base`` (default the shipped settings, on the shipped norms) with the gains ``gain``."""
    from loader_model.control.settings import default_settings, with_gains, with_scaled_gains

    scaled = with_gains if layout.machine.is_default else with_scaled_gains
    return scaled(base or default_settings(), gain, "loader-model design --method machine")


def _baselines(design: Design, envelope: Envelope, conditions: list[Condition]) -> list[float]:
    from loader_model.control.sensors import SensorModel
    from loader_model.experiments.trials import TRIAL_SENSOR_NOISE
    from loader_model.simulation.simulator import course_input, simulate

    values = []
    for condition in conditions:
        scenario = condition_scenario(design, condition.load, "baseline")
        result = simulate(
            course_input(condition_course(condition, envelope), scenario),
            scenario,
            sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=condition.seed),
        )
        values.append(float(result.seat_evaluation().total_m_s2))
    return values


class _Problem:
    """J, its gradient and the constraints at a gain (module notes)."""

    def __init__(
        self,
        layout: PlantLayout,
        params: str | None,
        envelope: Envelope,
        margin: float,
        sampled: int,
        study: str | None,
        extra_conditions: tuple[Condition, ...] = (),
        base: Any = None,
    ):
        from loader_model.control.comfort_design import comfort_plants
        from loader_model.experiments.design_check.margins import sampled_plants

        self.layout, self.params, self.envelope, self.margin = layout, params, envelope, margin
        self.base = base
        self.conditions = list(envelope.conditions())
        self.conditions += [c for c in extra_conditions if c not in self.conditions]
        probe = self._design(_settings(np.zeros(4), layout, base))
        self.baseline = _baselines(probe, envelope, self.conditions)
        nominal = None
        if not layout.machine.is_default or params is not None:
            nominal = {load: condition_plant(probe, load, "skyhook") for load in envelope.loads}
        self.plants = comfort_plants(envelope.loads, params=nominal)
        self.sampled = sampled_plants(probe, sampled, study)
        self.simulations = 0
        self.start_ratio: list[float] | None = None

    def _design(self, settings: Any) -> Design:
        return Design(settings, "skyhook", self.layout.name, self.params, layout=self.layout)

    def evaluate(self, gain: np.ndarray) -> tuple[float, np.ndarray, list[float]] | str:
        """(J, ∂J/∂K, a_total per scenario), or the reason a constraint rejects ``gain``."""
        from loader_model.control.comfort_design import evaluate_gain
        from loader_model.control.sensors import SensorModel
        from loader_model.control.settings import gain_norm_factors
        from loader_model.experiments.trials import TRIAL_SENSOR_NOISE
        from loader_model.simulation.gain_sensitivity import gain_gradient
        from loader_model.simulation.settling import limit_duty, settle_measure
        from loader_model.simulation.simulator import course_input
        from loader_model.simulation.validity_check import SimulationError

        try:
            settings = _settings(gain, self.layout, self.base)
        except ValueError as error:  # outside the settings' range
            return f"outside the settings' range: {error}"
        worst = min(e.loop_margin for e in evaluate_gain(self.plants, gain.reshape(1, 4)))
        if worst < self.margin * (1.0 - MARGIN_RTOL):  # as the check judges it
            return f"linearised loop margin {worst:.3f} rad/s below {self.margin:g}"
        if self.sampled:
            sampled = min(e.loop_margin for e in evaluate_gain(self.sampled, gain.reshape(1, 4)))
            if sampled < self.margin:  # the check asks > 0: σ keeps the design off its edge
                return f"loop margin {sampled:.3f} rad/s on a sampled plant, below {self.margin:g}"
        design = self._design(settings)
        factors = gain_norm_factors(settings)  # ∂a/∂K = c ∂a/∂k_settings (same control law)
        ratios, gradient, totals = [], np.zeros(4), []
        for index, condition in enumerate(self.conditions):
            scenario = condition_scenario(design, condition.load, "design")
            try:
                run = gain_gradient(
                    scenario,
                    course_input(condition_course(condition, self.envelope), scenario),
                    sensors=SensorModel(noise_std=TRIAL_SENSOR_NOISE, seed=condition.seed),
                )
            except SimulationError as error:
                return f"{condition.label}: failed run: {error}"
            self.simulations += 1
            plant = scenario.plant
            duty = limit_duty(run.columns, plant.command_limit(), plant.rate_limit())
            settle = settle_measure(run.time_s, run.columns)
            if settle.persistent and settle.persistent_above(
                rest_level(design, self.envelope, condition.load)  # only where it matters
            ):
                return f"{condition.label}: persistent oscillation after the road"
            if duty.command > self.envelope.command_duty or duty.rate > self.envelope.rate_duty:
                return (
                    f"{condition.label}: {ACTUATOR_NAMES[self.layout.machine.circuit]} at its "
                    f"limits (command {duty.command:.1%}, rate "
                    f"{duty.rate:.1%} of the run)"
                )
            ratio = run.a_total / self.baseline[index]
            allowed = 1.0 + self.envelope.worse_than_baseline
            if self.start_ratio is not None and ratio > max(allowed, self.start_ratio[index]):
                return f"{condition.label}: a_total {ratio - 1:+.1%} against the baseline"
            ratios.append(ratio)
            totals.append(run.a_total)
            gradient += 2.0 * ratio * factors * run.gradient / self.baseline[index]
        count = len(self.conditions)
        return float(np.mean(np.square(ratios))), gradient / count, totals


def design_on_machine(
    start_gain: Any,
    *,
    layout: PlantLayout = SKID_STEER,
    params: str | None = None,
    envelope: Envelope = TRAINING_ENVELOPE,
    margin: float = 0.1,
    max_iterations: int = 12,
    progress: bool = True,
    sampled_plants: int = 16,
    study: str | None = None,
    extra_conditions: tuple[Condition, ...] = (),
    base_settings: Any = None,
) -> MachineDesign:
    """Minimise J over ``envelope``'s scenarios from ``start_gain`` (module notes).

    Parameters
    ----------
    start_gain : array_like
        K_fb (4) to start from, e.g. the linear comfort design's or gains refined on a course;
        moved first to the nearest gain whose loop keeps ``margin`` on each load's linearised
        plant and on every sampled plant when it does not, then scaled toward zero while its
        runs break the other constraints (persistence, pump limits).
    layout : PlantLayout
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`; default the
        skid-steer).
    params : str
        Its parameter file (default the machine's shipped values).
    envelope : Envelope
        The scenarios and the criteria (default :data:`TRAINING_ENVELOPE`).
    margin : float
        Stability margin σ [rad/s] of the loop on each load's linearised plant.
    max_iterations : int
        Accepted quasi-Newton steps at most.
    progress : bool
        Show a progress bar over the iterations.
    sampled_plants : int
        Plants drawn from a robustness study on whose linearised plant the loop must keep
        ``margin`` (:func:`~loader_model.experiments.design_check.margins.sampled_plants`; the
        design check demands a stable loop on them).
    study : str, optional
        The study file they are drawn from (default: the shipped example for the skid-steer).
    extra_conditions : tuple of Condition
        Scenarios added to ``envelope``'s (for example the conditions a design check found
        failing), driven with ``envelope``'s settle window and road length.
    base_settings : ControllerSettings, optional
        The settings the gains are designed in, on the shipped norms
        (:func:`~loader_model.control.settings.without_gains`): their pressure loop, filters
        and the speed below which the ride control is off are kept (default the shipped
        settings, Table 3).

    Raises
    ------
    ValueError
        For a start that breaks a constraint (named) or a bad argument.
    """
    from tqdm import tqdm

    if (
        isinstance(max_iterations, bool)
        or not isinstance(max_iterations, int)
        or max_iterations < 1
    ):
        raise ValueError(f"max_iterations = {max_iterations!r}; allowed: an integer >= 1")
    start_wall = time.perf_counter()
    problem = _Problem(
        layout, params, envelope, float(margin), sampled_plants, study, extra_conditions,
        base_settings,
    )  # fmt: skip
    given = np.asarray(start_gain, dtype=float).ravel()
    if given.size != 4 or not np.all(np.isfinite(given)):
        raise ValueError(f"start_gain = {given.tolist()}; allowed: 4 finite gains")
    # a start unstable on a sampled plant (or short of σ on a nominal one) is moved to the
    # nearest gain that keeps σ on all of them (module notes of stable_start)
    gain = stable_start(given, [*problem.plants, *problem.sampled], float(margin))
    first = problem.evaluate(gain)
    for _ in range(START_SHRINKS):  # a smaller gain asks less of the pump (module notes)
        if not isinstance(first, str):
            break
        gain = START_SHRINK * gain
        first = problem.evaluate(gain)
    if isinstance(first, str):
        raise ValueError(
            f"start_gain {given.tolist()} breaks a constraint on machine {layout.name!r}, also "
            f"scaled by {START_SHRINK:g} {START_SHRINKS} times: {first}; start from a design "
            "that meets it"
        )
    cost, grad, totals = first
    start_cost = cost
    problem.start_ratio = [a / b for a, b in zip(totals, problem.baseline, strict=True)]
    scale = np.maximum(np.abs(gain), 1.0)
    x, g = gain / scale, grad * scale
    inverse = np.eye(4) * (0.1 / max(float(np.linalg.norm(g)), 1e-12))
    iterations = rejected = 0
    bar = tqdm(
        total=max_iterations, desc="design on the machine", unit="step", disable=not progress
    )
    try:
        for _ in range(max_iterations):
            direction = -inverse @ g
            slope = float(g @ direction)
            if slope >= 0.0:
                direction, slope = (
                    -g * (0.1 / max(float(np.linalg.norm(g)), 1e-12)),
                    -0.1 * float(np.linalg.norm(g)),
                )
            step, accepted = 1.0, None
            for _ in range(8):
                candidate = x + step * direction
                found = problem.evaluate(candidate * scale)
                if isinstance(found, str):
                    rejected += 1
                elif found[0] <= cost + 1e-4 * step * slope:
                    accepted = (candidate, found)
                    break
                step *= 0.5
            if accepted is None:
                break
            x_new, (cost_new, grad_new, totals) = accepted
            g_new = grad_new * scale
            s, y = x_new - x, g_new - g
            if float(s @ y) > 1e-16:
                if iterations == 0:
                    inverse = np.eye(4) * float(s @ y) / float(y @ y)
                rho = 1.0 / float(s @ y)
                eye = np.eye(4)
                inverse = (eye - rho * np.outer(s, y)) @ inverse @ (
                    eye - rho * np.outer(y, s)
                ) + rho * np.outer(s, s)
            improvement = cost - cost_new
            x, g, cost = x_new, g_new, cost_new
            iterations += 1
            bar.update(1)
            bar.set_postfix(J=f"{cost:.4f}")
            if improvement < 1e-5 * cost:
                break
    finally:
        bar.close()
    labels = [c.label for c in problem.conditions]
    return MachineDesign(
        gain=(x * scale).reshape(1, 4),
        start_gain=gain.reshape(1, 4),
        cost=cost,
        start_cost=start_cost,
        a_total=dict(zip(labels, totals, strict=True)),
        baseline=dict(zip(labels, problem.baseline, strict=True)),
        iterations=iterations,
        simulations=problem.simulations,
        rejected=rejected,
        wall_s=time.perf_counter() - start_wall,
    )
