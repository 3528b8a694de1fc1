"""The study's samples: a Latin hypercube or Sobol design from the seed, one spec per index.

The design (``scipy.stats.qmc``, seeded with the study's seed) has one column per uncertain
parameter, then the nominal speed, the bucket load and the driven-speed factor. Each column is
mapped through the parameter's inverse CDF (:mod:`~loader_model.robustness.distributions`) or onto
the list of choices (equal shares). The road of sample ``i`` (board jitter of the course or the
ISO 8608 profile) is seeded by ``numpy.random.SeedSequence([seed, i])``. The design is drawn once,
in the process that plans the study; workers receive finished :class:`SampleSpec` objects, so the
results do not depend on the number of workers or the engine.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.robustness.study import Study

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = ["SampleSpec", "design_matrix", "sample_plant", "sample_plant_vector", "sample_specs"]


@dataclass(frozen=True)
class SampleSpec:
    """One sample: what the design and the seed drew for index ``index``.

    Attributes
    ----------
    index : int
        Sample index from 0.
    speed_kmh : float
        Nominal speed (the course's board spacing follows it).
    speed_factor : float
        Driven speed over nominal speed.
    load : str
        Bucket-load case.
    values : tuple of (str, float)
        Uncertain parameter values by parameter-file path, in SI units.
    road_seed : int
        Seed of the sample's road.
    """

    index: int
    speed_kmh: float
    speed_factor: float
    load: str
    values: tuple[tuple[str, float], ...]
    road_seed: int


def design_matrix(study: Study, count: int | None = None, stream: int = 0) -> np.ndarray:
    """Points in [0, 1)^d of the study's design (``count`` rows, default ``study.samples``).

    ``stream`` selects an independent design from the same seed (1: the plants the robust gains
    are optimised over, so that the study's own samples are a fresh sample for them).
    """
    from scipy.stats import qmc

    count = study.samples if count is None else count
    dimension = len(study.parameters) + 3
    generator = np.random.default_rng(np.random.SeedSequence([study.seed, 2**32 + stream]))
    engine = qmc.Sobol if study.sampling == "sobol" else qmc.LatinHypercube
    try:
        sampler = engine(dimension, rng=generator)
    except TypeError:  # SciPy < 1.15 names the argument seed
        sampler = engine(dimension, seed=generator)
    with warnings.catch_warnings():  # Sobol: "balance properties" warning unless count = 2^m
        warnings.simplefilter("ignore", UserWarning)
        return np.asarray(sampler.random(count), dtype=float)


def _choice(u: float, options: tuple) -> object:
    return options[min(int(u * len(options)), len(options) - 1)]


def sample_specs(study: Study, count: int | None = None, stream: int = 0) -> list[SampleSpec]:
    """Every sample of the study, by index (module notes).

    Parameters
    ----------
    study : Study
        A validated study.
    count : int, optional
        Number of samples (default ``study.samples``).
    stream : int
        Independent design from the same seed (0: the study's samples; 1: the robust gains' plants).

    Returns
    -------
    list of SampleSpec
        Ordered by index; the same for the same study, whatever runs them.
    """
    points = design_matrix(study, count, stream)
    values = [dist.ppf(points[:, j]) for j, (_, dist) in enumerate(study.parameters)]
    offset = len(study.parameters)
    specs = []
    for index, row in enumerate(points):
        sequence = np.random.SeedSequence([study.seed, index] + ([stream] if stream else []))
        road_seed = int(np.random.default_rng(sequence).integers(0, 2**31 - 1))
        spread = study.speed_spread
        specs.append(
            SampleSpec(
                index=index,
                speed_kmh=float(_choice(row[offset], study.speeds_kmh)),
                speed_factor=float(1.0 - spread + 2.0 * spread * row[offset + 2]),
                load=str(_choice(row[offset + 1], study.loads)),
                values=tuple(
                    (path, float(column[index]))
                    for (path, _), column in zip(study.parameters, values, strict=True)
                ),
                road_seed=road_seed,
            )
        )
    return specs


def _sample_sets(spec: SampleSpec) -> tuple[Any, Any]:
    """The sample's loader and bucket load: the shipped sets with its values, each validated."""
    from loader_model import parameters

    plant = [(p, v) for p, v in spec.values if not p.startswith("sensors.")]
    loader_updates = {p: v for p, v in plant if not p.startswith("load.")}
    load_updates = {p.removeprefix("load."): v for p, v in plant if p.startswith("load.")}
    loader, load = parameters.default_loader(), parameters.bucket_load(spec.load)
    if loader_updates:
        loader = parameters.replace(loader, loader_updates)
    if load_updates:
        load = parameters.replace(load, load_updates)
    return loader, load


def sample_plant_vector(spec: SampleSpec) -> tuple[np.ndarray, Any]:
    """Plant parameter vector (accumulator shut) and bucket load of a sample.

    Raises
    ------
    ValueError
        From the parameter files' range and consistency checks.
    """
    from loader_model.plant.plant_parameters import plant_parameter_vector

    loader, load = _sample_sets(spec)
    return plant_parameter_vector(loader, load, check=True), load


def sample_plant(
    spec: SampleSpec, layout: PlantLayout | None = None, params_path: str | None = None
) -> PlantScenario:
    """The sample's plant (accumulator shut), resolved once: the vector of
    :func:`sample_plant_vector` with its static equilibrium
    (:func:`~loader_model.plant.scenario.resolve_plant`).

    Parameters
    ----------
    spec : SampleSpec
        The sample.
    layout : PlantLayout, optional
        The described machine (default the skid-steer); another machine's plant comes from its
        flat parameter file
        (:func:`~loader_model.robustness.machine_study.machine_sample_plant`).
    params_path : str, optional
        That flat file (``[study] params``; default the machine's shipped one).

    Raises
    ------
    ValueError
        From the parameter files' range and consistency checks.
    """
    from loader_model.plant.scenario import resolve_plant

    if layout is not None and not layout.machine.is_default:
        from loader_model.robustness.machine_study import machine_sample_plant

        return machine_sample_plant(spec, layout, params_path)
    return resolve_plant(*_sample_sets(spec))
