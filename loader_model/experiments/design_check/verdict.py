"""The check's verdict: every condition judged against its baseline, and the loop's margins.

A condition fails, and the verdict names it and why, when the design's run

- was stopped by the simulator (outside the model's range of validity, or a failed solve) where
  the baseline's was not;
- has an a_total (Eq. 50) more than :attr:`~.Envelope.worse_than_baseline` above the baseline's;
- has its pump command at V_p,max for more than :attr:`~.Envelope.command_duty` of the run, or
  its displacement rate at its limit for more than :attr:`~.Envelope.rate_duty`;
- does not come to rest after the road: a persistent oscillation
  (:func:`~loader_model.simulation.settling.settle_measure`), or a residual pitch acceleration
  at the end of the settle window above both the rest floor and
  :attr:`~.Envelope.tail_factor` times the baseline's. Either counts only above
  :data:`~loader_model.simulation.settling.REST_NOISE_FACTOR` times the level the design keeps
  at rest on flat ground with its sensors' noise alone
  (:func:`~loader_model.experiments.design_check.runs.rest_run`, one run per load): that
  much motion is the noise's, not the road's. The design fails when that run at rest drives
  the pump to a limit: noise alone sets off a limit cycle (measured on a tractor with a front
  loader: 6.2 rad/s² at rest with the full bucket), and its level then raises no floor.

A condition whose baseline the simulator stopped is not judged (the road is outside what the
model covers for this machine) and is listed as such. The design fails as well when the loop's
margin on a load's linearised plant is below :attr:`~.Envelope.margin_rad_s` (by more than
:data:`MARGIN_RTOL` of it), or when any
sampled plant's loop is unstable.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from loader_model.experiments.design_check.envelope import Condition, Envelope
from loader_model.experiments.design_check.margins import LinearMargin
from loader_model.experiments.design_check.runs import Design, RunOutcome

__all__ = ["MARGIN_RTOL", "ConditionCheck", "DesignCheck", "judge_condition"]

#: A loop margin short of the required σ by less than this fraction of σ passes: the gain
#: design places its optimum on the margin constraint σ itself, met to its solver's tolerance,
#: and a design for a user's machine read "margin 0.100 rad/s below 0.1" (measured); 0.1 % of
#: σ (1e-4 rad/s at the default) is a time constant change no ride could show.
MARGIN_RTOL = 1e-3


@dataclass(frozen=True)
class ConditionCheck:
    """One condition's runs and what fails in it (module notes).

    Attributes
    ----------
    condition : Condition
        The load, road and speed.
    runs : dict of str to RunOutcome
        ``design``, ``baseline`` and ``passive``.
    failures : tuple of str
        Why the design fails here (empty: it passes).
    judged : bool
        False when the baseline's run was stopped (the condition is outside the model's range).
    """

    condition: Condition
    runs: dict[str, RunOutcome]
    failures: tuple[str, ...]
    judged: bool = True

    @property
    def change(self) -> float:
        """The design's a_total against the baseline's, as a fraction (nan if either stopped)."""
        design, baseline = self.runs["design"].a_total, self.runs["baseline"].a_total
        return design / baseline - 1.0


@dataclass(frozen=True)
class DesignCheck:
    """The whole check: conditions, margins, and the verdict.

    Attributes
    ----------
    design : Design
        What was checked.
    envelope : Envelope
        Where and by which criteria.
    conditions : tuple of ConditionCheck
        Every condition, in the envelope's order.
    margins : dict of str to LinearMargin
        The loop's stability per load (skyhook designs; empty for another controller).
    rest : dict of str to RunOutcome
        The design at rest on flat ground with its sensors' noise alone, per load (module
        notes).
    """

    design: Design
    envelope: Envelope
    conditions: tuple[ConditionCheck, ...]
    margins: dict[str, LinearMargin]
    rest: dict[str, RunOutcome] = field(default_factory=dict)

    @property
    def rest_rms(self) -> dict[str, float]:
        """The pitch acceleration [rad/s²] r.m.s. the design keeps at rest, per load."""
        return {load: run.tail_rms for load, run in self.rest.items()}

    @property
    def failures(self) -> tuple[str, ...]:
        """Every failing condition or margin, named, with its reason."""
        found = []
        for load, margin in self.margins.items():
            required = self.envelope.margin_rad_s * (1.0 - MARGIN_RTOL)
            if margin.margin_rad_s < required:
                found.append(
                    f"{load}: linearised loop margin {margin.margin_rad_s:.4f} rad/s below "
                    f"{self.envelope.margin_rad_s:g} rad/s"
                )
            if margin.sampled_unstable:
                found.append(
                    f"{load}: loop unstable on {margin.sampled_unstable} of {margin.sampled} "
                    f"sampled plants (worst margin {margin.worst_sampled_rad_s:.3f} rad/s)"
                )
        for load, run in self.rest.items():
            if run.stopped:
                found.append(f"{load}, at rest with the sensors' noise alone: {run.stopped}")
            elif run.command_duty > 0.0 or run.rate_duty > 0.0:
                found.append(
                    f"{load}, at rest with the sensors' noise alone: the "
                    f"{ACTUATOR_NAMES[self.design.layout.machine.circuit]} at its limits "
                    f"(command {run.command_duty:.1%}, rate {run.rate_duty:.1%} of the run), "
                    f"pitch acceleration {run.tail_rms:.3f} rad/s² r.m.s.: the loop does not "
                    "hold still"
                )
        for check in self.conditions:
            found += [f"{check.condition.label}: {reason}" for reason in check.failures]
        return tuple(found)

    @property
    def passed(self) -> bool:
        """True when nothing fails."""
        return not self.failures

    @property
    def not_judged(self) -> tuple[str, ...]:
        """Conditions whose baseline run the simulator stopped, with its reason."""
        return tuple(
            f"{c.condition.label}: baseline {c.runs['baseline'].stopped}"
            for c in self.conditions
            if not c.judged
        )


#: Per lift circuit, how the findings name its command and its rate at their limits.
ACTUATOR_LIMITS: dict[str, tuple[str, str]] = {
    "pump": ("pump command at V_p,max", "pump displacement rate at its limit"),
    "valve": ("spool command at its stroke x_s,max", "spool velocity at its limit"),
}
#: Per lift circuit, the actuator whose limits the check judges.
ACTUATOR_NAMES: dict[str, str] = {"pump": "pump", "valve": "valve spool"}


def judge_condition(
    condition: Condition,
    runs: dict[str, RunOutcome],
    envelope: Envelope,
    rest_rms: float = 0.0,
    circuit: str = "pump",
) -> ConditionCheck:
    """The failures of the design's run against the baseline's (module notes); ``rest_rms``
    is the level [rad/s²] the design keeps at rest with its sensors' noise on this load;
    ``circuit`` (``"pump"`` or ``"valve"``) names the actuator in the findings."""
    from loader_model.simulation.settling import REST_FLOOR_RAD_S2, REST_NOISE_FACTOR

    design, baseline = runs["design"], runs["baseline"]
    if baseline.stopped:
        return ConditionCheck(condition, runs, (), judged=False)
    if design.stopped:
        return ConditionCheck(condition, runs, (f"run stopped: {design.stopped}",))
    failures = []
    limit = baseline.a_total * (1.0 + envelope.worse_than_baseline)
    if design.a_total > limit:
        failures.append(
            f"a_total {design.a_total:.3f} m/s² is {design.a_total / baseline.a_total - 1:+.1%} "
            f"against the baseline's {baseline.a_total:.3f} (allowed "
            f"{envelope.worse_than_baseline:+.0%})"
        )
    command, rate = ACTUATOR_LIMITS[circuit]
    if design.command_duty > envelope.command_duty:
        failures.append(
            f"{command} for {design.command_duty:.1%} of the run (allowed "
            f"{envelope.command_duty:.0%})"
        )
    if design.rate_duty > envelope.rate_duty:
        failures.append(
            f"{rate} for {design.rate_duty:.1%} of the run (allowed {envelope.rate_duty:.0%})"
        )
    floor = max(REST_FLOOR_RAD_S2, REST_NOISE_FACTOR * rest_rms)
    if design.persistent and design.tail_rms > floor:
        failures.append(
            f"persistent oscillation after the road: pitch acceleration {design.tail_rms:.3f} "
            f"rad/s² r.m.s. in the last second, {design.decay_ratio:.2f} of the second before"
        )
    elif design.tail_rms > max(floor, envelope.tail_factor * baseline.tail_rms):
        failures.append(
            f"slow decay after the road: pitch acceleration {design.tail_rms:.3f} rad/s² r.m.s. "
            f"in the last second against the baseline's {baseline.tail_rms:.3f}"
        )
    return ConditionCheck(condition, runs, tuple(failures))
