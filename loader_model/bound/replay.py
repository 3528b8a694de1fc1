"""The optimal command played back open-loop through the simulator (the bound's replay check).

:func:`playback_controller` is a controller like those of :mod:`~loader_model.simulation.
controllers`: ``(z, y, settings) -> (z_next, u)`` with z the period counter k and settings
(M, u_0 … u_{N−1}); it ignores y and returns u_j for k in [jM, (j + 1) M), the last value after
the table. :func:`replay` runs it with the simulator (same ROS2 scheme, 1 ms step and 1 kHz
zero-order hold as every controller, the rollout's fixed substeps
:data:`~loader_model.bound.trajectory.BOUND_SUBSTEPS`) from the static equilibrium and
returns the result, whose
:meth:`~loader_model.simulation.result.SimulationResult.seat_evaluation` is the report's a_total.
"""

from __future__ import annotations

from functools import cache

import casadi as ca
import numpy as np

from loader_model.bound.trajectory import BOUND_SUBSTEPS
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.scenario import PlantScenario
from loader_model.simulation.result import SimulationResult
from loader_model.simulation.scenario import closed_loop
from loader_model.simulation.simulator import simulate
from loader_model.simulation.travel import RoadInput

__all__ = ["playback_controller", "replay"]


@cache
def playback_controller(count: int, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """The controller that plays back a table of ``count`` commands (module notes) on the plant
    of the machine ``layout`` (it reads none of the outputs)."""
    z = ca.SX.sym("z", 1)
    y = ca.SX.sym("y", len(layout.output_names))
    settings = ca.SX.sym("settings", count + 1)
    index = ca.floor((z[0] + 0.5) / settings[0])
    u = settings[count]
    for j in range(count - 1, -1, -1):
        u = ca.if_else(index <= j, settings[1 + j], u)
    return ca.Function(
        f"playback_{count}", [z, y, settings], [z + 1.0, u], ["z", "y", "settings"], ["z_next", "u"]
    )


def replay(
    plant: PlantScenario,
    road: RoadInput,
    command: np.ndarray,
    hold_periods: int,
    period_s: float = 1e-3,
) -> SimulationResult:
    """Simulate ``plant`` over ``road`` with ``command`` held ``hold_periods`` periods each."""
    table = np.asarray(command, dtype=float).ravel()
    controller = playback_controller(table.size, plant.layout)
    scenario = closed_loop(plant, controller, np.concatenate([[hold_periods], table]), [0.0])
    duration_s = table.size * hold_periods * period_s
    return simulate(road, scenario, duration_s=duration_s, substeps=BOUND_SUBSTEPS)
