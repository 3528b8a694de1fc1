"""Second mode of the gain design: refine K_fb on the nonlinear obstacle course.

The linear design (:mod:`~loader_model.control.comfort_design`) minimises a_total on a random
road through the linearised plant. On the paper's course the tyres leave the ground and the
pump saturates, which the linear model cannot show. Here the cost is the nonlinear one,

.. math::

    J(K) = \\sum_{\\text{loads}} a_{total}(K)^2 \\quad (\\text{Eq. } 50),

each a_total from one nominal drive over the paper's course (section 5.3; no board jitter, exact
sensors) or over a course of the caller's (boards at any speed, a course file of obstacles) by
the closed-loop simulator with the skyhook at 1 kHz. The drive contains lift-off and
landing, so J is not smooth in K; it is minimised by Nelder-Mead (SciPy), not by gradients.
Stability is kept as a constraint: a K whose linearised closed loop has a margin below σ on any
load (:func:`~loader_model.control.comfort_design.evaluate_gain`), whose drive fails, or that
leaves the controller settings' validated range of k_fb costs +inf, so the search never ends at
an unstable gain.

Any described machine (:mod:`loader_model.machines`) is refined the same way. The skid-steer
drives its Table 6 trial plants (:func:`~loader_model.experiments.trials.plant_scenario`) with its
bucket loads' pressure norms (100 and 200 bar) and gains within the settings file's ±100. Another
machine drives its own plant per load case (:func:`~loader_model.plant.scenario.resolve_plant` on
the skyhook's circuit), its controllers reading the plant's sensors by name with ‖p_A‖∞ = 1.5 ×
the load's static piston pressure (:func:`~loader_model.plant.machine_parameters.pressure_norm`).
Its gains are raw gains on the shipped norms, as the linear design gives them; a gain beyond
the file's ±100 is driven with the norms scaled down by
:func:`~loader_model.control.settings.with_scaled_gains` (the same control law), so its range is
what the scaled norms' own validated ranges allow (each norm's lower limit).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout

if TYPE_CHECKING:
    from loader_model.control.settings import ControllerSettings
    from loader_model.plant.scenario import PlantScenario
    from loader_model.simulation.courses import Course

__all__ = ["course_cost", "refine_on_course"]


#: The name the refined gains' settings carry while they are driven.
_SOURCE = "skyhook-optimised"
#: Another machine's shipped plant per (machine, load), resolved once per process.
_SHIPPED: dict[tuple[PlantLayout, str], PlantScenario] = {}


def _settings(k_fb: np.ndarray, layout: PlantLayout) -> ControllerSettings:
    """The shipped settings with gains ``k_fb``: as given for the skid-steer, with the norms
    scaled for another machine (module notes); ValueError outside their validated ranges."""
    from loader_model.control.settings import default_settings, with_gains, with_scaled_gains

    if layout.machine.is_default:
        return with_gains(default_settings(), k_fb, _SOURCE)
    return with_scaled_gains(default_settings(), k_fb, _SOURCE)


def _admissible(k_fb: np.ndarray, layout: PlantLayout) -> bool:
    """True when ``k_fb`` is within the range the settings of the machine ``layout`` can
    carry."""
    from loader_model.control.settings import ControllerSettings

    if layout.machine.is_default:  # the settings file's range, ±100
        allowed = ControllerSettings.__dataclass_fields__["k_fb"].metadata["allowed"]
        return not (np.any(k_fb < allowed.low) or np.any(k_fb > allowed.high))
    try:
        _settings(k_fb, layout)
    except ValueError:
        return False
    return True


def _plant(
    load: str, layout: PlantLayout, given: np.ndarray | PlantScenario | None
) -> PlantScenario:
    """The plant ``load`` is driven on: ``given`` (a resolved plant or a parameter vector of
    the machine ``layout``) or the shipped one on the skyhook's circuit."""
    from loader_model.plant.plant_parameters import PlantOptions
    from loader_model.plant.scenario import PlantScenario, resolve_plant

    if isinstance(given, PlantScenario):
        if given.layout.machine != layout.machine:
            raise ValueError(
                f"params[{load!r}] is a plant of machine {given.layout.name!r}; allowed: plants of "
                f"machine {layout.name!r}"
            )
        return given
    if given is not None:
        return PlantScenario.from_vector(np.asarray(given, dtype=float), machine=layout)
    if layout.machine.is_default:
        from loader_model.experiments.trials import plant_scenario

        return plant_scenario(load, _SOURCE)
    if (layout, load) not in _SHIPPED:
        options = PlantOptions.for_controller("skyhook")
        _SHIPPED[layout, load] = resolve_plant(None, load, options, machine=layout)
    return _SHIPPED[layout, load]


def _drive(
    k_fb: np.ndarray,
    load: str,
    speed_kmh: float,
    params: np.ndarray | PlantScenario | None,
    layout: PlantLayout = SKID_STEER,
    duration_s: float | None = None,
    course: Course | None = None,
) -> float:
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import ride_scenario
    from loader_model.simulation.simulator import course_input, simulate

    plant = _plant(load, layout, params)
    norm = None  # another machine's: its plant's (ride_scenario)
    if layout.machine.is_default:
        from loader_model.parameters.sets import bucket_load

        norm = bucket_load(load).pressure_normalisation
    scenario = ride_scenario(plant, "skyhook", _settings(k_fb, layout), pressure_norm_pa=norm)
    driven = paper_course(speed_kmh) if course is None else course
    result = simulate(course_input(driven, scenario), scenario, duration_s=duration_s)
    return float(result.seat_evaluation().total_m_s2)


def _machine_params(
    layout: PlantLayout,
    loads: Sequence[str],
    params: dict[str, np.ndarray | PlantScenario] | None,
) -> dict[str, np.ndarray | PlantScenario] | None:
    """For another machine than the skid-steer a plant per load (``params`` as given, else its
    shipped plants), so that the linear checks and the drives share them."""
    if layout.machine.is_default or params is not None:
        return params
    return {load: _plant(load, layout, None) for load in loads}


def course_cost(
    k_fb: Any,
    loads: Sequence[str] = ("empty", "full"),
    speed_kmh: float = 9.0,
    params: dict[str, np.ndarray | PlantScenario] | None = None,
    *,
    machine: MachineSource = SKID_STEER,
    duration_s: float | None = None,
    course: Course | None = None,
) -> dict[str, float]:
    """a_total [m/s²] per load of one nominal drive over ``course`` (default: the paper's at
    ``speed_kmh``) with gains ``k_fb``.

    Parameters
    ----------
    k_fb : array_like
        The skyhook gains (4) on the shipped norms.
    loads : sequence of str
        Load cases driven.
    speed_kmh : float
        The course's speed.
    params : dict, optional
        Plant parameter vector or resolved plant per load (default the machine's shipped one).
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer; module notes).
    duration_s : float, optional
        Drive only the course's first ``duration_s`` seconds (default the whole course).
    course : Course, optional
        The course driven at its own speed (``speed_kmh`` then unused), for example boards at
        any speed (:func:`~loader_model.simulation.courses.board_course_at`) or a course file
        (:func:`~loader_model.simulation.obstacles.load_course_file`); default the paper's.

    Raises
    ------
    ValueError
        For gains the machine's settings cannot carry, or a plant of another machine.
    """
    gain = np.asarray(k_fb, dtype=float).ravel()
    layout = resolve_layout(machine)
    params = _machine_params(layout, loads, params)
    return {
        load: _drive(
            gain,
            load,
            speed_kmh,
            None if params is None else params[load],
            layout,
            duration_s,
            course,
        )
        for load in loads
    }


def refine_on_course(
    gain0: Any,
    *,
    loads: Sequence[str] = ("empty", "full"),
    speed_kmh: float = 9.0,
    margin: float | None = None,
    params: dict[str, np.ndarray | PlantScenario] | None = None,
    max_evaluations: int = 120,
    progress: bool = True,
    machine: MachineSource = SKID_STEER,
    duration_s: float | None = None,
    course: Course | None = None,
) -> dict[str, Any]:
    """Minimise Σ a_total² over ``loads`` on ``course`` (default: the paper's at ``speed_kmh``)
    from ``gain0`` (module notes).

    Parameters
    ----------
    gain0 : array_like
        Starting gains (4), e.g. the linear design's; must be stable with the margin.
    loads : sequence of str
        Bucket loads driven per evaluation.
    speed_kmh : float
        The paper course's speed, 9 or 18 km/h (unused with ``course``).
    margin : float, optional
        Linear stability margin σ [rad/s] (default: the linear design's).
    params : dict, optional
        Plant parameter vector or resolved plant per load (default: the machine's shipped one).
    max_evaluations : int
        Budget of cost evaluations (each drives every load once).
    progress : bool
        Show a progress bar.
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer; module notes).
    duration_s : float, optional
        Drive only the course's first ``duration_s`` seconds (default the whole course).

    course : Course, optional
        The course driven at its own speed (:func:`course_cost`); default the paper's.

    Returns
    -------
    dict
        ``gain`` (1 x 4), ``cost`` (Σ a_total²), ``a_total`` per load, ``start_cost``,
        ``start_a_total``, ``evaluations``, ``refused`` (unstable, failed or out-of-range
        evaluations).

    Raises
    ------
    ValueError
        For a bad budget or start, or a start that misses the margin or fails on the course.
    """
    from scipy.optimize import minimize
    from tqdm import tqdm

    from loader_model.control.comfort_design import DEFAULT_MARGIN, comfort_plants, evaluate_gain
    from loader_model.simulation.simulator import SimulationError

    sigma = DEFAULT_MARGIN if margin is None else float(margin)
    if isinstance(max_evaluations, bool) or int(max_evaluations) < 1:
        raise ValueError(f"max_evaluations must be an integer >= 1; got {max_evaluations!r}")
    layout = resolve_layout(machine)
    params = _machine_params(layout, loads, params)
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
        if not _admissible(k, layout):  # the range the machine's settings can carry
            refused += 1
            seen[key] = (np.inf, {})
            return np.inf
        if min(e.margin for e in evaluate_gain(plants, k.reshape(1, 4))) < sigma:
            refused += 1
            seen[key] = (np.inf, {})
            return np.inf
        try:
            totals = course_cost(
                k, loads, speed_kmh, params, machine=layout, duration_s=duration_s, course=course
            )
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
                f"gain0 {start.tolist()} misses the stability margin {sigma} rad/s, fails "
                f"on the course or leaves the range of machine {layout.name!r}'s settings; start from "
                "a stable design (loader-model design)"
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
