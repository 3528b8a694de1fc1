"""Range and consistency checks of the parameter sets, run by :func:`loader_model.parameters.validate`.

Ranges come from each field's metadata (:mod:`loader_model.parameter_fields`); the consistency
checks here are those that involve several fields. :func:`check_combination` checks a loader
together with a bucket load at the static equilibrium (hand statics, no generated code), so that
nothing that validates fails later in the model for a reason validation could have seen.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

from loader_model.parameter_schema import BucketLoad, LoaderParameters, Point
from loader_model.parameter_toml import iter_leaves, leaf_metadata

__all__ = [
    "COINCIDENCE_TOLERANCE_M",
    "END_STOP_MARGIN_M",
    "MAX_ROD_TO_PISTON_RATIO",
    "MAX_STATIC_PRESSURE_PA",
    "check_combination",
    "check_distinct",
    "check_hydraulics",
    "check_loader",
    "check_ranges",
    "static_equilibrium",
]

#: Two points closer than this are taken as coincident (degenerate geometry), in m.
COINCIDENCE_TOLERANCE_M = 1e-3
#: The cylinder must be at least this far from either end stop at the operating point, in m
#: (on its end stop it has no travel and the linear model of the hydraulic spring does not hold).
END_STOP_MARGIN_M = 1e-3
#: Largest rod-to-bore ratio: the annulus keeps at least 19 % of the piston area (area ratios of
#: built cylinders are 1.1 to about 5).
MAX_ROD_TO_PISTON_RATIO = 0.9
#: Largest static piston-side pressure, Pa (500 bar, above the relief setting of mobile hydraulics).
MAX_STATIC_PRESSURE_PA = 5e7


_PRESSURE_FIELDS = (
    "boom.mass, boom.cog, load.mass, load.cog, geometry.C, geometry.D, geometry.E, "
    "cylinders.count, cylinders.piston_diameter, cylinders.rod_diameter, "
    "hydraulics.charge_pressure and environment.gravity"
)


def _get(obj: Any, path: str) -> Any:
    for name in path.split("."):
        obj = getattr(obj, name)
    return obj


def _distance(p: Point, q: Point) -> float:
    return math.hypot(p[0] - q[0], p[1] - q[1])


def shown(value: Any) -> str:
    """``repr`` of a value for a message, with integers of more than 20 digits abbreviated."""
    if isinstance(value, tuple):
        return "(" + ", ".join(shown(v) for v in value) + ")"
    if isinstance(value, int) and len(str(abs(value))) > 20:
        return f"{str(value)[:20]}... ({len(str(abs(value)))} digits)"
    return repr(value)


def check_ranges(params: LoaderParameters | BucketLoad) -> None:
    """Raise ValueError naming field, value, range and reason for a value out of its range."""
    for path, cls, name in iter_leaves(type(params)):
        meta = leaf_metadata(cls, name)
        value = _get(params, path)
        for item in value if isinstance(value, tuple) else (value,):
            try:
                finite = math.isfinite(item)
            except (TypeError, OverflowError):
                finite = False
            if not finite or not meta["allowed"].contains(item):
                raise ValueError(
                    f"{path} = {shown(value)} {meta['unit']} is out of range; allowed: "
                    f"{meta['allowed'].describe()}"
                )


def check_distinct(points: Mapping[str, Point]) -> None:
    """Raise if two of the named points coincide (degenerate geometry)."""
    for (name_p, p), (name_q, q) in itertools.combinations(points.items(), 2):
        distance = _distance(p, q)
        if distance < COINCIDENCE_TOLERANCE_M:
            raise ValueError(
                f"degenerate geometry: {name_p} = {p} and {name_q} = {q} coincide "
                f"(distance {distance:g} m; allowed: >= {COINCIDENCE_TOLERANCE_M:g} m)"
            )


def check_hydraulics(params: LoaderParameters) -> None:
    """Pressures that must be ordered: charge and precharge below the relief setting."""
    relief = params.hydraulics.relief_pressure
    for path, value in (
        ("hydraulics.charge_pressure", params.hydraulics.charge_pressure),
        ("accumulator.precharge_pressure", params.accumulator.precharge_pressure),
    ):
        if value >= relief:
            raise ValueError(
                f"{path} = {value!r} Pa must be below hydraulics.relief_pressure = {relief!r} Pa; "
                f"allowed: < {relief:g} Pa"
            )


def check_loader(params: LoaderParameters) -> None:
    """Consistency of a loader: cylinder proportions and stroke, distinct points, axle order,
    pressure settings (:func:`check_hydraulics`)."""
    check_hydraulics(params)
    cyl, geo = params.cylinders, params.geometry
    if cyl.rod_diameter > MAX_ROD_TO_PISTON_RATIO * cyl.piston_diameter:
        raise ValueError(
            f"cylinders.rod_diameter = {cyl.rod_diameter!r} m must be at most "
            f"{MAX_ROD_TO_PISTON_RATIO:g} x cylinders.piston_diameter = {cyl.piston_diameter!r} m "
            "(an annulus of at least 19 % of the piston area, as built cylinders have)"
        )
    if cyl.retracted_length <= cyl.stroke:
        raise ValueError(
            f"cylinders.retracted_length = {cyl.retracted_length!r} m must exceed "
            f"cylinders.stroke = {cyl.stroke!r} m (the barrel holds the stroke)"
        )
    names = ("A", "B", "C", "D", "E")
    points = {f"geometry.{n}": getattr(geo, n) for n in names} | {"boom.cog": params.boom.cog}
    check_distinct(points)
    if geo.A[0] <= geo.B[0]:
        raise ValueError(
            f"geometry.A = {geo.A} must be ahead of geometry.B = {geo.B}; allowed: A_x > B_x "
            "(A is the front axle)"
        )
    length = _distance(geo.E, geo.C)
    low = cyl.retracted_length + END_STOP_MARGIN_M
    high = cyl.retracted_length + cyl.stroke - END_STOP_MARGIN_M
    if not low <= length <= high:
        raise ValueError(
            f"geometry.C, geometry.E: cylinder length |E - C| = {length:.6g} m at the operating point is "
            f"outside [{low:.6g}, {high:.6g}] m (cylinders.retracted_length to + cylinders.stroke, "
            f"{END_STOP_MARGIN_M * 1e3:g} mm clear of each end stop)"
        )


def static_equilibrium(loader: LoaderParameters, load: BucketLoad) -> dict[str, float]:
    """Static tyre loads, cylinder force and piston pressure of the plant at p = 0.

    Evaluated by the plant's own equilibrium (generated ``complete_parameters`` and
    :func:`loader_model.plant.equilibrium.equilibrium_function`), so validation and simulation
    agree by construction; ``tests/test_parameter_ranges.py`` checks it against hand statics.

    Returns
    -------
    dict
        ``F_Ay0``, ``F_By0`` (N, positive in compression), ``F_act0`` (N), ``p_A0`` (Pa gauge, the
        piston-side pressure with the rod side at the charge pressure) and the combined centre of
        gravity ``G`` of boom and load.
    """
    import loader_model_generated as generated
    from loader_model.parameters import combine_bodies
    from loader_model.plant.equilibrium import equilibrium_function
    from loader_model.plant.plant_parameters import plant_parameter_vector

    params = plant_parameter_vector(loader, load, check=False)
    state, _, force = equilibrium_function()(params)
    completed, _ = generated.function("complete_parameters")(
        params[: len(generated.PARAMETER_NAMES)]
    )
    names = generated.PARAMETER_NAMES
    boom = loader.boom
    _, cog, _ = combine_bodies(
        (boom.mass, load.mass), (boom.cog, load.cog), (boom.inertia, load.inertia)
    )
    return {
        "F_Ay0": float(completed[names.index("F_Ay0")]),
        "F_By0": float(completed[names.index("F_By0")]),
        "F_act0": float(force),
        "p_A0": float(state[10]),
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
