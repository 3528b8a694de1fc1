"""The loader with a bucket load at rest: static loads, and the checks that it stands (section 2.1).

The static tyre loads and the lift-cylinder force come from the generated ``complete_parameters``
(gravity on the multibody model at p = 0), the piston pressure from the cylinder's static balance.
:func:`check_combination` refuses a combination that the model cannot hold: an axle that lifts
off (the machine tips), a cylinder that would pull or exceed :data:`MAX_STATIC_PRESSURE_PA`, an
accumulator precharge at or above the static pressure. :func:`resolve_machine` is the one way
from files or objects to a loader and a load that stand together.
"""

from __future__ import annotations

from pathlib import Path

import loader_model_generated as generated
from loader_model.parameters.checks import check_distinct
from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.sets import (
    combine_bodies,
    model_parameter_values,
    resolve_loader_and_load,
)
from loader_model.vehicle.cylinder import static_piston_pressure

__all__ = ["MAX_STATIC_PRESSURE_PA", "check_combination", "resolve_machine", "static_equilibrium"]

#: Largest static piston-side pressure, Pa (500 bar, above the relief setting of mobile hydraulics).
MAX_STATIC_PRESSURE_PA = 5e7

_PRESSURE_FIELDS = (
    "boom.mass, boom.cog, load.mass, load.cog, geometry.C, geometry.D, geometry.E, "
    "cylinders.count, cylinders.piston_diameter, cylinders.rod_diameter, "
    "hydraulics.charge_pressure and environment.gravity"
)


def static_equilibrium(loader: LoaderParameters, load: BucketLoad) -> dict[str, float]:
    """Static tyre loads, cylinder force and piston pressure of the plant at p = 0.

    The forces come from the generated ``complete_parameters`` (the model's own statics), the
    pressure from :func:`loader_model.vehicle.cylinder.static_piston_pressure`, which the plant's
    equilibrium (:mod:`loader_model.plant.equilibrium`) uses too, so validation and simulation
    agree by construction; ``tests/parameters/test_parameter_ranges.py`` checks it against hand statics.

    Returns
    -------
    dict
        ``F_Ay0``, ``F_By0`` (N, positive in compression), ``F_act0`` (N), ``p_A0`` (Pa gauge, the
        piston-side pressure with the rod side at the charge pressure) and the combined centre of
        gravity ``G`` of boom and load.
    """
    names = generated.PARAMETER_NAMES
    values = model_parameter_values(loader, load) | {"F_Ay0": 0.0, "F_By0": 0.0}
    completed, force = generated.function("complete_parameters")([values[n] for n in names])
    cyl = loader.cylinders
    pressure = static_piston_pressure(
        float(force),
        cyl.count,
        cyl.piston_diameter,
        cyl.rod_diameter,
        loader.hydraulics.charge_pressure,
    )
    boom = loader.boom
    _, cog, _ = combine_bodies(
        (boom.mass, load.mass), (boom.cog, load.cog), (boom.inertia, load.inertia)
    )
    return {
        "F_Ay0": float(completed[names.index("F_Ay0")]),
        "F_By0": float(completed[names.index("F_By0")]),
        "F_act0": float(force),
        "p_A0": float(pressure),
        "G": cog,
    }


def check_combination(loader: LoaderParameters, load: BucketLoad) -> None:
    """Consistency of a loader with a bucket load at the static equilibrium.

    Raises
    ------
    ValueError
        If the combined centre of gravity coincides with a point, an axle lifts off (the machine
        tips), the cylinder would have to pull or hold more than
        :data:`MAX_STATIC_PRESSURE_PA`, or the accumulator precharge is not below the static
        piston pressure (it would hold no oil).
    """
    statics = static_equilibrium(loader, load)
    geo = loader.geometry
    check_distinct(
        {f"geometry.{n}": getattr(geo, n) for n in "ABCDE"}
        | {"combined G of boom.cog and load.cog": statics["G"]}
    )
    where = f"bucket load of {load.mass:g} kg at cog {load.cog}"
    for axle, key in (("front (A)", "F_Ay0"), ("rear (B)", "F_By0")):
        if not statics[key] > 0.0:
            raise ValueError(
                f"{where}: the static {axle} axle load is {statics[key]:.4g} N; allowed: > 0 "
                "(the machine must stand on both axles; check chassis.mass, boom.mass, boom.cog, "
                "load.mass, load.cog, geometry.A and geometry.B)"
            )
    pressure = statics["p_A0"]
    if not (statics["F_act0"] > 0.0 and pressure <= MAX_STATIC_PRESSURE_PA):
        raise ValueError(
            f"{where}: the static lift-cylinder force is {statics['F_act0']:.4g} N, piston "
            f"pressure {pressure / 1e5:.4g} bar; allowed: a pushing force with at most "
            f"{MAX_STATIC_PRESSURE_PA / 1e5:g} bar (the piston side carries the boom; check "
            f"{_PRESSURE_FIELDS})"
        )
    precharge = loader.accumulator.precharge_pressure
    if precharge >= pressure:
        raise ValueError(
            f"accumulator.precharge_pressure = {precharge!r} Pa must be below the static piston "
            f"pressure {pressure:.6g} Pa with the {where} (a higher precharge holds no oil; "
            f"the static pressure depends on {_PRESSURE_FIELDS})"
        )


def resolve_machine(
    loader: LoaderParameters | str | Path | None = None, load: BucketLoad | str | Path = "empty"
) -> tuple[LoaderParameters, BucketLoad]:
    """A loader and a bucket load, given as objects, TOML paths or defaults, that stand together.

    :func:`loader_model.parameters.sets.resolve_loader_and_load` (each set valid alone), then
    :func:`check_combination`.

    Raises
    ------
    ValueError
        If either set is invalid or they do not stand together (naming the fields).
    """
    loader, load = resolve_loader_and_load(loader, load)
    check_combination(loader, load)
    return loader, load
