"""The loader with a bucket load at rest: static loads, and the checks that it stands (section 2.1).

The static tyre loads and the lift-cylinder force come from the generated ``complete_parameters``
(gravity on the multibody model at p = 0), the piston pressure from the cylinder's static balance.
:func:`check_combination` refuses a combination that the model cannot hold: an axle that lifts
off (the machine tips), a cylinder that would pull or exceed :data:`MAX_STATIC_PRESSURE_PA`, an
accumulator precharge at or above the static pressure. :func:`resolve_machine` is the one way
from files or objects to a loader and a load that stand together; for another described machine
(:mod:`loader_model.machines`) :func:`machine_static_equilibrium` and
:func:`resolve_machine_values` do the same with its flat parameter file, and also give the
preload of each locked cylinder (``F_<name>0``, e.g. the wheel loader's tilt cylinder).
"""

from __future__ import annotations

from pathlib import Path

import loader_model_generated as generated
from loader_model.machines import MachineInfo
from loader_model.parameters.checks import END_STOP_MARGIN_M, check_distinct
from loader_model.parameters.machine_files import (
    MachineParameters,
    machine_model_values,
    resolve_machine_parameters,
)
from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.sets import (
    combine_bodies,
    model_parameter_values,
    resolve_loader_and_load,
)
from loader_model.vehicle.cylinder import static_piston_pressure

__all__ = [
    "MAX_STATIC_PRESSURE_PA",
    "check_combination",
    "machine_static_equilibrium",
    "resolve_machine",
    "resolve_machine_values",
    "static_equilibrium",
]

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


def machine_static_equilibrium(
    info: MachineInfo, params: MachineParameters, load: str | None = None
) -> dict[str, float]:
    """Static loads of the described machine ``info`` at p = 0 with the bucket load case
    ``load``.

    Returns
    -------
    dict
        Every static load of the machine (``F_Ay0``, ``F_By0``, each locked cylinder's preload
        ``F_<name>0``; N, tyre loads positive in compression, a cylinder's positive pushing),
        ``F_act0`` (N), ``x_cyl0`` (m, the driven cylinder's pin-to-pin length) and ``p_A0``
        (Pa gauge, rod side at the charge pressure, or a valve circuit's tank pressure).
    """
    values = machine_model_values(params, load)
    completed, force = info.function("complete_parameters")(
        [values[n] for n in info.parameter_names]
    )
    zeros = [0.0] * info.n_coordinates
    x_cyl = float(info.function("cylinder_kinematics")(zeros, zeros, completed)[0])
    cyl = params.cylinders
    pressure = static_piston_pressure(
        float(force),
        cyl.count,
        cyl.piston_diameter,
        cyl.rod_diameter,
        params.rod_side_pressure,
    )
    names = info.parameter_names
    loads = {n: float(completed[names.index(n)]) for n in info.static_names}
    return loads | {"F_act0": float(force), "x_cyl0": x_cyl, "p_A0": float(pressure)}


def resolve_machine_values(
    info: MachineInfo,
    params: MachineParameters | str | Path | None = None,
    load: str | None = None,
) -> dict[str, float]:
    """Model values of the described machine ``info`` whose parameters and load stand together
    at rest.

    Raises
    ------
    ValueError
        If the parameter file is invalid, the load case unknown, an axle lifts off, the lift
        cylinder would pull or hold more than :data:`MAX_STATIC_PRESSURE_PA`, or its pin-to-pin
        length at p = 0 is not within the stroke (away from the end stops).
    """
    params = resolve_machine_parameters(info, params)
    statics = machine_static_equilibrium(info, params, load)
    where = f"machine {info.name!r} ({params.origin}) with load {load or 'as in [model]'}"
    axles = info.axles
    for axle in axles:
        key = f"F_{axle}y0"
        if not statics[key] > 0.0:
            raise ValueError(
                f"{where}: the static load of axle {axle} is {statics[key]:.4g} N; allowed: > 0 "
                "(the machine must stand on every axle; check the masses, centres of gravity "
                f"and the axle points {', '.join(axles)})"
            )
    if not (statics["F_act0"] > 0.0 and statics["p_A0"] <= MAX_STATIC_PRESSURE_PA):
        raise ValueError(
            f"{where}: the static lift-cylinder force is {statics['F_act0']:.4g} N, piston "
            f"pressure {statics['p_A0'] / 1e5:.4g} bar; allowed: a pushing force with at most "
            f"{MAX_STATIC_PRESSURE_PA / 1e5:g} bar (check [cylinders] and the boom's values)"
        )
    cyl = params.cylinders
    position = statics["x_cyl0"] - cyl.retracted_length
    if not END_STOP_MARGIN_M <= position <= cyl.stroke - END_STOP_MARGIN_M:
        raise ValueError(
            f"{where}: the lift cylinder's length at p = 0 is {statics['x_cyl0']:.4g} m, piston "
            f"position {position:.4g} m; allowed: within the stroke [0, {cyl.stroke:g}] m, "
            f"{END_STOP_MARGIN_M:g} m from either end stop (check [cylinders] retracted_length "
            "and stroke, and the cylinder points)"
        )
    return machine_model_values(params, load)
