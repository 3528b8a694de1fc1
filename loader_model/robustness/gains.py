"""Skyhook gains of a study and their stability margin on each sampled plant.

Gains are resolved once, in the process that plans the study, and travel to the workers as numbers:

- ``table3``: K_fb of Table 3;
- ``lqr``: output-feedback LQR (Eq. 41, 42) on the nominal design plant of each bucket load
  (:func:`~loader_model.control.gain_design.design_gains`, ``"lqr"``);
- ``optimised``: the ISO 2631 optimisation over the nominal plants of the study's loads
  (:func:`~loader_model.control.gain_design.design_gains`, ``"optimise"``);
- ``robust``: the same optimisation over ``robust_plants`` plants drawn from the study's
  distributions with an independent design (stream 1), so the study's samples are a fresh sample.

Design plants (:func:`~loader_model.control.comfort_design.comfort_plants`): ISO 8608 road of the
study's class at its first nominal speed. The stability margin of a gain on a sample is the largest
real part of the closed-loop poles of the plant and skyhook (the design plant's loop poles: the
sampled plant linearised at its static equilibrium); positive means unstable, and the sample's run
of that gain is then in the ``"unstable"`` category (:mod:`~loader_model.robustness.outcomes`),
never among the evaluated ones.

Another machine (``[study] machine``): the same methods on its comfort plants, built
from its shipped flat parameter file (nominal) or from the sample's parameters
(:func:`~loader_model.robustness.machine_study.machine_sample_plant`, robust). Its gains, like
those of ``design --machine``, may exceed a settings file's ±100; the study hands them to the
controller as numbers, so they need no rescaling.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.robustness.sampling import SampleSpec, sample_specs
from loader_model.robustness.study import Study

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = ["Gains", "max_pole_real", "resolve_gains"]

#: Controller name -> bucket load -> K_fb (4 gains on the normalised ẋ_H, ẏ_H, θ̇1, φ).
Gains = dict[str, dict[str, tuple[float, ...]]]


def _row(gain: Any) -> tuple[float, ...]:
    return tuple(float(g) for g in np.asarray(gain, dtype=float).ravel())


def _sample_design_parameters(
    spec: SampleSpec, layout: PlantLayout, params_path: str | None
) -> Any:
    """The sample's plant vector (skid-steer) or resolved plant (another machine)."""
    if layout.machine.is_default:
        from loader_model.robustness.sampling import sample_plant_vector

        return sample_plant_vector(spec)[0]
    from loader_model.robustness.machine_study import machine_sample_plant

    return machine_sample_plant(spec, layout, params_path)


def _nominal_parameters(study: Study) -> dict[str, Any] | None:
    """None for the skid-steer (the shipped loader), else the machine's plant per study load."""
    if study.layout.machine.is_default:
        return None
    from loader_model.plant.scenario import resolve_plant

    return {load: resolve_plant(study.params, load, machine=study.layout) for load in study.loads}


def robust_gain(study: Study) -> tuple[tuple[float, ...], list[SampleSpec]]:
    """Optimise K_fb over ``study.robust_plants`` plants drawn from the study (stream 1).

    Returns the gain and the specs of the plants it was designed on. Samples whose plant cannot
    be built (parameter checks) are skipped.
    """
    from loader_model.control.comfort_design import comfort_plants
    from loader_model.control.gain_design import design_gains

    specs = sample_specs(study, study.robust_plants, stream=1)
    plants = []
    for spec in specs:
        try:
            params = _sample_design_parameters(spec, study.layout, study.params)
        except ValueError:
            continue
        speed = spec.speed_kmh * spec.speed_factor
        (plant,) = comfort_plants((spec.load,), study.road_class, speed, {spec.load: params})
        plants.append(plant)
    if not plants:
        raise ValueError("robust gains: no sampled plant passed the parameter checks")
    return _row(design_gains(plants, "optimise").gain), specs


def resolve_gains(study: Study) -> Gains:
    """K_fb per gain-based controller (``skyhook`` and ``controllers.gains``) and load.

    Parameters
    ----------
    study : Study
        The study (machine, loads, road class, first speed, gain methods, ``robust_plants``).

    Returns
    -------
    Gains
        Controller name -> load -> four gains, computed once (module notes).

    Raises
    ------
    ValueError
        If a design fails (e.g. no sampled plant for the robust gains passes the checks).
    """
    from loader_model.control.comfort_design import (
        TABLE3_GAIN,
        TABLE3_PRINTED_GAIN,
        comfort_plants,
    )
    from loader_model.control.gain_design import design_gains

    table3 = _row(TABLE3_GAIN)
    gains: Gains = {}
    if "skyhook" in study.compare:
        gains["skyhook"] = dict.fromkeys(study.loads, table3)
    methods = {spec for _, spec in study.gains if isinstance(spec, str)}
    nominal = ()
    if methods & {"lqr", "optimised"}:
        nominal = comfort_plants(
            study.loads, study.road_class, study.speeds_kmh[0], _nominal_parameters(study)
        )
    optimised = _row(design_gains(nominal, "optimise").gain) if "optimised" in methods else None
    robust = robust_gain(study)[0] if "robust" in methods else None
    for name, spec in study.gains:
        if spec == "table3":
            gains[name] = dict.fromkeys(study.loads, table3)
        elif spec == "table3-printed":
            gains[name] = dict.fromkeys(study.loads, _row(TABLE3_PRINTED_GAIN))
        elif spec == "lqr":
            lqr = design_gains(nominal, "lqr").gains
            gains[name] = {load: _row(gain) for load, gain in lqr.items()}
        elif spec == "optimised":
            gains[name] = dict.fromkeys(study.loads, optimised)
        elif spec == "robust":
            gains[name] = dict.fromkeys(study.loads, robust)
        else:
            gains[name] = dict.fromkeys(study.loads, tuple(spec))
    return gains


def max_pole_real(
    params: np.ndarray | PlantScenario,
    load: str,
    speed_kmh: float,
    road_class: str,
    gains: list[Any],
) -> list[float]:
    """Largest real part [rad/s] of the plant-and-skyhook poles for each gain on one plant
    (a parameter vector, or a resolved plant whose equilibrium is reused)."""
    from loader_model.control.comfort_design import comfort_plants, evaluate_gain

    (plant,) = comfort_plants((load,), road_class, speed_kmh, {load: params})
    return [float(np.max(evaluate_gain([plant], g)[0].loop_poles.real)) for g in gains]
