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

from loader_model.plant.layout import PlantLayout
from loader_model.simulation.stepper import plant_steps

__all__ = ["PART_SUBSTEPS", "REFINEMENT", "STEP_ERROR_LIMIT", "refine_period"]

#: Largest error estimate of a period's substeps, in units of the states' scales, above which
#: its plant is integrated again (module notes).
STEP_ERROR_LIMIT = 30.0
#: Substeps of a refined period, as a multiple of the run's (of the largest count where the
#: substeps are chosen by their error, :data:`~loader_model.simulation.adaptive.SUBSTEP_COUNTS`).
REFINEMENT = 4
#: Most ROS2 steps of one part of a refined period: more substeps are more parts.
PART_SUBSTEPS = 4


def refine_period(
    period_s: float,
    substeps: int,
    layout: PlantLayout,
    carry: np.ndarray,
    coarse_next: np.ndarray,
    w0: np.ndarray,
    w1: np.ndarray,
    params: np.ndarray,
) -> np.ndarray:
    """The carry after a period whose error estimate passed :data:`STEP_ERROR_LIMIT` (module
    notes), its plant integrated again with :data:`REFINEMENT` times ``substeps`` ROS2 steps:
    :data:`REFINEMENT` parts of the period of ``substeps`` steps each, or of
    :data:`PART_SUBSTEPS` steps each and as many more parts
    (:func:`~loader_model.simulation.stepper.plant_steps`, the exogenous input linear over the
    period as in the period Function). The controller's part, z and the command u held over
    the period (the carry's last entry), is the coarse period's ``coarse_next`` (the carry it
    returned)."""
    parts = REFINEMENT * max(1, substeps // PART_SUBSTEPS)
    steps = plant_steps(period_s / parts, min(substeps, PART_SUBSTEPS), layout)
    nx = steps.size1_in(0)
    state, command = carry[:nx], coarse_next[-1]
    for part in range(parts):
        start = w0 + (w1 - w0) * (part / parts)
        end = w1 if part == parts - 1 else w0 + (w1 - w0) * ((part + 1) / parts)
        state = np.asarray(steps(state, command, start, end, params), dtype=float).ravel()
    return np.concatenate([state, coarse_next[nx:]])
