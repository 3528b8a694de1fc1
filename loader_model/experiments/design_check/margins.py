"""Stability of a skyhook design on the linearised plant: per load, and over sampled plants.

The loop is the plant linearised by automatic differentiation at its static equilibrium with the
pressure loop (section 3.2) and the skyhook's output feedback u = −K_fb y (Eq. 40, 41), as the
gain design sees it (:func:`~loader_model.control.comfort_design.evaluate_gain`). Its margin is
min(−Re λ) over the loop's poles and its smallest damping ratio min(−Re λ / |λ|). Sampled plants
are drawn from a robustness study's parameter distributions (:mod:`loader_model.robustness`;
for the skid-steer by default the shipped example study: bulk modulus, tyre stiffness, pump
dynamics, sensor errors), each at its drawn load and speed.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from loader_model.experiments.design_check.runs import Design

__all__ = ["LinearMargin", "linear_margins", "sampled_margins", "sampled_plants"]


@dataclass(frozen=True)
class LinearMargin:
    """The designed loop's stability on one load's linearised plant.

    Attributes
    ----------
    load : str
        The load case.
    margin_rad_s : float
        min(−Re λ) over the loop's poles [rad/s]; negative: unstable.
    min_damping : float
        Smallest damping ratio of the loop's poles.
    sampled : int
        Sampled plants of this load (0: none drawn).
    sampled_unstable : int
        Of those, the ones whose loop has a pole with Re λ ≥ 0.
    worst_sampled_rad_s : float
        The smallest margin over the sampled plants (nan when none).
    """

    load: str
    margin_rad_s: float
    min_damping: float
    sampled: int = 0
    sampled_unstable: int = 0
    worst_sampled_rad_s: float = float("nan")


def _gain(design: Design) -> np.ndarray:
    """K_fb on the shipped norms, as the linear design gives it: a settings file whose norms
    were scaled with its gains (:func:`~loader_model.control.settings.with_scaled_gains`, the
    same control law) is read back to the raw gains."""
    from loader_model.control.settings import gain_norm_factors

    gain = np.asarray(design.settings.k_fb, dtype=float) / gain_norm_factors(design.settings)
    return gain.reshape(1, 4)


def _nominal_params(design: Design, loads: tuple[str, ...]) -> dict[str, Any] | None:
    if design.layout.machine.is_default and design.params is None:
        return None
    from loader_model.plant.scenario import resolve_plant

    return {load: resolve_plant(design.params, load, machine=design.layout) for load in loads}


def linear_margins(design: Design, loads: tuple[str, ...]) -> dict[str, LinearMargin]:
    """The skyhook loop's margin and damping per load on the nominal plant (module notes)."""
    from loader_model.control.comfort_design import comfort_plants, evaluate_gain

    plants = comfort_plants(loads, params=_nominal_params(design, loads))
    return {
        e.load: LinearMargin(e.load, e.loop_margin, e.min_damping)
        for e in evaluate_gain(plants, _gain(design))
    }


def sampled_plants(design: Design, count: int, study_path: str | None = None) -> list[Any]:
    """The linear comfort plants (:func:`~loader_model.control.comfort_design.comfort_plants`)
    of ``count`` plants drawn from a robustness study (module notes), each named by its load;
    empty when the machine has no study to draw from. Drawn sets the parameter checks refuse
    are skipped.

    Parameters
    ----------
    design : Design
        The design (its machine and parameter file choose the default study).
    count : int
        Plants drawn, >= 0.
    study_path : str, optional
        A robustness study file (default: the shipped example for the skid-steer with its
        shipped values, none otherwise).
    """
    from loader_model.control.comfort_design import comfort_plants
    from loader_model.robustness.sampling import sample_plant, sample_plant_vector, sample_specs
    from loader_model.robustness.study import load_study

    if count <= 0:
        return []
    if study_path is None:
        if not design.layout.machine.is_default or design.params is not None:
            return []
        with resources.as_file(
            resources.files("loader_model") / "data" / "robustness_example.toml"
        ) as path:
            study = load_study(path)
    else:
        study = load_study(study_path)
    plants = []
    for spec in sample_specs(study, count, stream=2):
        try:
            if study.layout.machine.is_default:
                params: Any = sample_plant_vector(spec)[0]
            else:
                params = sample_plant(spec, study.layout, study.params)
        except ValueError:  # a drawn set the parameter checks refuse: not a plant
            continue
        speed = spec.speed_kmh * spec.speed_factor
        plants += comfort_plants((spec.load,), study.road_class, speed, {spec.load: params})
    return plants


def sampled_margins(plants: list[Any], design: Design) -> dict[str, tuple[int, int, float]]:
    """(sampled, unstable, worst margin [rad/s]) per load of the design's loop on ``plants``
    (:func:`sampled_plants`)."""
    from loader_model.control.comfort_design import evaluate_gain

    found: dict[str, list[float]] = {}
    for plant in plants:
        (evaluation,) = evaluate_gain([plant], _gain(design))
        found.setdefault(plant.name, []).append(evaluation.loop_margin)
    return {
        load: (len(margins), int(np.sum(np.asarray(margins) <= 0.0)), float(np.min(margins)))
        for load, margins in found.items()
    }
