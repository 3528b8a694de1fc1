"""Range and consistency checks of the parameter sets, run by :func:`loader_model.parameters.sets.validate`.

Ranges come from each field's metadata (:mod:`loader_model.parameters.fields`); the consistency
checks here are those that involve several fields of one set. Whether a loader and a bucket load
stand together at rest needs the model's statics: :func:`loader_model.vehicle.statics.check_combination`
checks that one layer up, so this layer imports nothing of the model.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

from loader_model.parameters.schema import BucketLoad, LoaderParameters, Point
from loader_model.parameters.toml_format import iter_leaves, leaf_metadata

__all__ = [
    "COINCIDENCE_TOLERANCE_M",
    "END_STOP_MARGIN_M",
    "MAX_ROD_TO_PISTON_RATIO",
    "check_distinct",
    "check_hydraulics",
    "check_loader",
    "check_ranges",
]

#: Two points closer than this are taken as coincident (degenerate geometry), in m.
COINCIDENCE_TOLERANCE_M = 1e-3
#: The cylinder must be at least this far from either end stop at the operating point, in m
#: (on its end stop it has no travel and the linear model of the hydraulic spring does not hold).
END_STOP_MARGIN_M = 1e-3
#: Largest rod-to-bore ratio: the annulus keeps at least 19 % of the piston area (area ratios of
#: built cylinders are 1.1 to about 5).
MAX_ROD_TO_PISTON_RATIO = 0.9


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
