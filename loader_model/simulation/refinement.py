"""Failed ROS2 periods integrated again finer (the simulator's and the bound's rollout's step).

Each period of :func:`~loader_model.simulation.stepper.period_function` reports the largest
error estimate of its substeps, ½ h (k_1 + k_2) in units of
:func:`~loader_model.simulation.stepper.step_error_scales`. Where a substep straddles the tyres'
stick-slip switch the linearly implicit step can fail (the stepper's notes: on an AMD EPYC the
rear anchor jumped 2 cm in one period, 461 J in the energy balance, 600 m/s² on the seat in
another run): those periods read 150 to 11 600, every other period of the 16 paper-course runs
below 3 and up to 18 right after a failed step. A period above :data:`STEP_ERROR_LIMIT` has its
plant integrated again with :data:`REFINEMENT` times the substeps (:func:`refine_period`); its
controller step (z and the command held over it) is the coarse period's. The simulator and the
bound's rollout both call it, so the bound's trajectory stays the simulator's.
"""

from __future__ import annotations

import numpy as np

from loader_model.simulation.stepper import plant_steps

__all__ = ["REFINEMENT", "STEP_ERROR_LIMIT", "refine_period"]

#: Largest error estimate of a period's substeps, in units of the states' scales, above which
#: its plant is integrated again (module notes).
STEP_ERROR_LIMIT = 30.0
#: Substeps of a refined period, as a multiple of the run's.
REFINEMENT = 4


def refine_period(
    period_s: float,
    substeps: int,
    machine: str,
    carry: np.ndarray,
    coarse_next: np.ndarray,
    w0: np.ndarray,
    w1: np.ndarray,
    params: np.ndarray,
) -> np.ndarray:
    """The carry after a period whose error estimate passed :data:`STEP_ERROR_LIMIT` (module
    notes), its plant integrated again with :data:`REFINEMENT` times ``substeps`` ROS2 steps:
    :data:`REFINEMENT` parts of the period of ``substeps`` steps each
    (:func:`~loader_model.simulation.stepper.plant_steps`, the exogenous input linear over the
    period as in the period Function). The controller's part, z and the command u held over
    the period, is the coarse period's ``coarse_next`` (the carry it returned)."""
    steps = plant_steps(period_s / REFINEMENT, substeps, machine)
    nx = steps.size1_in(0)
    state, command = carry[:nx], coarse_next[-1]
    for part in range(REFINEMENT):
        start = w0 + (w1 - w0) * (part / REFINEMENT)
        end = w1 if part == REFINEMENT - 1 else w0 + (w1 - w0) * ((part + 1) / REFINEMENT)
        state = np.asarray(steps(state, command, start, end, params), dtype=float).ravel()
    return np.concatenate([state, coarse_next[nx:]])
