"""Second mode of the gain design (issue 11): refine K_fb on the nonlinear obstacle course.

The linear design (:mod:`~loader_model.control.comfort_design`) minimises a_total on a random
road through the linearised plant. On the paper's course the tyres leave the ground and the
pump saturates, which the linear model cannot show. Here the cost is the nonlinear one,

.. math::

    J(K) = \\sum_{\\text{loads}} a_{total}(K)^2 \\quad (\\text{Eq. } 50),

each a_total from one nominal drive over the paper's course (section 5.3; no board jitter, exact
sensors) by the closed-loop simulator with the skyhook at 1 kHz. The drive contains lift-off and
landing, so J is not smooth in K; it is minimised by Nelder-Mead (SciPy), not by gradients.
Stability is kept as a constraint: a K whose linearised closed loop has a margin below σ on any
load (:func:`~loader_model.control.comfort_design.evaluate_gain`), whose drive fails, or that
leaves the controller settings' validated range of k_fb costs +inf, so the search never ends at
an unstable gain.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["course_cost", "refine_on_course"]


def _drive(k_fb: np.ndarray, load: str, speed_kmh: float, params: np.ndarray | None) -> float:
    from loader_model.experiments.trials import controller_scenario, plant_scenario
    from loader_model.parameters.sets import bucket_load
    from loader_model.plant.scenario import PlantScenario
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input, simulate

    plant = (
        plant_scenario(load, "skyhook-optimised")
        if params is None
        else PlantScenario.from_vector(params)
    )
    norm = bucket_load(load).pressure_normalisation
    scenario = controller_scenario("skyhook-optimised", plant, norm, tuple(k_fb))
    result = simulate(course_input(paper_course(speed_kmh), scenario), scenario)
    return float(result.seat_evaluation().total_m_s2)


def course_cost(
    k_fb: Any,
    loads: Sequence[str] = ("empty", "full"),
    speed_kmh: float = 9.0,
    params: dict[str, np.ndarray] | None = None,
) -> dict[str, float]:
    """a_total [m/s²] per load of one nominal drive over the paper's course with gains ``k_fb``
    (``params``: plant parameter vector per load, default the shipped loader's)."""
    gain = np.asarray(k_fb, dtype=float).ravel()
    return {
        load: _drive(gain, load, speed_kmh, None if params is None else params[load])
        for load in loads
    }


def refine_on_course(
    gain0: Any,
    *,
    loads: Sequence[str] = ("empty", "full"),
    speed_kmh: float = 9.0,
    margin: float | None = None,
    params: dict[str, np.ndarray] | None = None,
    max_evaluations: int = 120,
    progress: bool = True,
) -> dict[str, Any]:
    """Minimise Σ a_total² over ``loads`` on the paper's course from ``gain0`` (module notes).

    Parameters
    ----------
    gain0 : array_like
        Starting gains (4), e.g. the linear design's; must be stable with the margin.
    loads : sequence of str
        Bucket loads driven per evaluation.
    speed_kmh : float
        The course's speed, 9 or 18 km/h.
    margin : float, optional
        Linear stability margin σ [rad/s] (default: the linear design's).
    params : dict, optional
        Plant parameter vector per load (default: the shipped loader's).
    max_evaluations : int
        Budget of cost evaluations (each drives every load once).
    progress : bool
        Show a progress bar.

    Returns
    -------
    dict
        ``gain`` (1 x 4), ``cost`` (Σ a_total²), ``a_total`` per load, ``start_cost``,
        ``start_a_total``, ``evaluations``, ``refused`` (unstable or failed evaluations).
    """
    from scipy.optimize import minimize
    from tqdm import tqdm

    from loader_model.control.comfort_design import DEFAULT_MARGIN, comfort_plants, evaluate_gain
    from loader_model.control.settings import ControllerSettings
    from loader_model.simulation.simulator import SimulationError

    allowed = ControllerSettings.__dataclass_fields__["k_fb"].metadata["allowed"]
    sigma = DEFAULT_MARGIN if margin is None else float(margin)
    if isinstance(max_evaluations, bool) or int(max_evaluations) < 1:
        raise ValueError(f"max_evaluations must be an integer >= 1; got {max_evaluations!r}")
    plants = comfort_plants(tuple(loads), params=params)
    start = np.asarray(gain0, dtype=float).ravel()
    if start.size != 4:
        raise ValueError(f"gain0 must hold 4 gains; got {start.size}")
    seen: dict[tuple[float, ...], tuple[float, dict[str, float]]] = {}
    refused = 0
    bar = tqdm(total=max_evaluations, desc="course refinement", unit="eval", disable=not progress)

    def cost(k: np.ndarray) -> float:
        nonlocal refused
        key = tuple(np.round(k, 12))
        if key in seen:
            return seen[key][0]
        bar.update(1)
        if np.any(k < allowed.low) or np.any(k > allowed.high):  # the settings file's range
            refused += 1
            seen[key] = (np.inf, {})
            return np.inf
        if min(e.margin for e in evaluate_gain(plants, k.reshape(1, 4))) < sigma:
            refused += 1
            seen[key] = (np.inf, {})
            return np.inf
        try:
            totals = course_cost(k, loads, speed_kmh, params)
        except SimulationError:
            refused += 1
            seen[key] = (np.inf, {})
            return np.inf
        value = float(sum(a**2 for a in totals.values()))
        seen[key] = (value, totals)
        return value

    try:
        start_cost = cost(start)
        if not np.isfinite(start_cost):
            raise ValueError(
                f"gain0 {start.tolist()} misses the stability margin {sigma} rad/s or fails "
                "on the course; start from a stable design (loader-model design)"
            )
        simplex = np.vstack([start, start + np.diag(0.1 * np.maximum(np.abs(start), 1.0))])
        found = minimize(
            cost,
            start,
            method="Nelder-Mead",
            options={"maxfev": int(max_evaluations), "initial_simplex": simplex, "xatol": 1e-3},
        )
    finally:
        bar.close()
    best = np.asarray(found.x, dtype=float)
    value, totals = seen[tuple(np.round(best, 12))]
    return {
        "gain": best.reshape(1, 4),
        "cost": value,
        "a_total": totals,
        "start_cost": start_cost,
        "start_a_total": seen[tuple(np.round(start, 12))][1],
        "evaluations": len(seen),
        "refused": refused,
    }
