"""How a simulated trajectory of the bound meets its limits, and how far round-off moves that.

The nonlinear bound (:mod:`~loader_model.bound.nonlinear`) measures every trial trajectory by
the largest violation of the path limits relative to each limit (:func:`path_violation`) and
by its end values against the end condition (:func:`end_residual`, in units of
:func:`end_scale`). :func:`merit_noise_floor` measures how far these and a_total move when the
command changes by round-off: the simulator is deterministic, but over the 40 mm boards it
amplifies such differences (measured along the 12 s optimum of the paper course, 9 km/h,
empty: a_total by 5.2e-5, and ``docs/guide/bound.md``), and no optimiser can confirm a
decrease of its merit below that.
"""

from __future__ import annotations

import numpy as np

from loader_model.bound.constrained import path_limits
from loader_model.bound.problem import BoundProblem
from loader_model.bound.stage_model import end_values
from loader_model.bound.trajectory import Trajectory, rollout
from loader_model.bound.weighting import SeatWeighting

__all__ = [
    "NOISE_RELATIVE",
    "NOISE_SAMPLES",
    "end_residual",
    "end_scale",
    "merit_noise_floor",
    "path_violation",
]

#: Round-off-sized perturbations of the final command measuring the merit's noise floor.
NOISE_SAMPLES = 4
#: Their size relative to each command value.
NOISE_RELATIVE = 1e-15


def path_violation(problem: BoundProblem, trajectory: Trajectory) -> float:
    """Largest violation of the path limits on ``trajectory`` relative to each limit."""
    static, lower, upper, scale = path_limits(problem)
    deviation = trajectory.path() - static
    return float(np.max(np.maximum(deviation - upper, lower - deviation) / scale))


def end_residual(problem: BoundProblem, trajectory: Trajectory) -> np.ndarray:
    """End values of ``trajectory`` minus the end targets (boom position, V_p, V̇_p)."""
    return end_values(problem, trajectory) - np.array(list(problem.end_targets.values()))


def merit_noise_floor(
    problem: BoundProblem,
    command: np.ndarray,
    weighting: SeatWeighting,
    *,
    samples: int = NOISE_SAMPLES,
    relative: float = NOISE_RELATIVE,
    seed: int = 0,
) -> tuple[float, float]:
    """The spread of the simulated a_total (relative to its value) and of the largest path
    violation (in units of the limits) when each value of ``command`` (absolute, m³/rev) is
    perturbed by ``relative`` of itself, ``samples`` times (Gaussian, seeded).

    The simulator is deterministic, but over the 40 mm boards it amplifies differences of
    round-off size (``docs/guide/bound.md``: the touchdowns and the stick-slip contact), so
    two command tables that differ in the last digit give trajectories that differ by this
    much; no optimiser can confirm a decrease of its merit below it.
    """
    rng = np.random.default_rng(seed)
    a_values, violations = [], []
    for _ in range(samples):
        run = rollout(problem, command * (1.0 + relative * rng.standard_normal(command.size)))
        a_values.append(weighting.a_total(run.seat()))
        violations.append(path_violation(problem, run))
    return float(np.ptp(a_values) / np.mean(a_values)), float(np.ptp(violations))


def end_scale(problem: BoundProblem) -> np.ndarray:
    """The end condition's units: the stroke, V_p,max and V̇_p,max (within the limit fraction)."""
    stroke = problem.plant.parameter("stroke")
    return np.array([stroke, problem.u_bounds[1], problem.rate_limit])
