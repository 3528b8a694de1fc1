"""The structure of a machine description as the registry reads it: axles, cylinders, sensor and
seat points, bodies, the coordinates of joints and lengths, parameter ranges, the static loads the
derivation completes, and the lift circuit's kind.

:func:`description_structure` turns a parsed description (already checked by ``derive``) into the
structural fields of :class:`~loader_model.machines.MachineInfo`; it reads no file and imports
nothing of the generated code.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["Cylinder", "description_structure"]


@dataclass(frozen=True)
class Cylinder:
    """A cylinder of the description between two points (base on the parent body, rod end)."""

    name: str
    kind: str
    """``"driven"`` (the lift cylinder group of the hydraulic plant) or ``"locked"`` (a spring)."""
    base: str
    rod: str


def _angle_coordinate(bodies: dict[str, Any], name: str) -> str:
    """The coordinate that is the absolute angle of body ``name`` (a slider: its parent's)."""
    body = bodies[name]
    if body["joint"] == "free":
        return body["coordinates"][2]
    if body["joint"] == "slider":
        return _angle_coordinate(bodies, body["parent"])
    if body["joint"] == "two_mounts":
        return body["coordinates"][1]
    return body["coordinate"]


def description_structure(raw: dict[str, Any]) -> dict[str, Any]:
    """Axles, cylinders, sensors, bodies and ranges of a parsed description (checked by derive),
    as keyword arguments of :class:`~loader_model.machines.MachineInfo`."""
    bodies = raw["bodies"]
    chassis = next(body for body in bodies.values() if body["joint"] == "free")
    sensors = {point: tuple(item["axes"]) for point, item in raw.get("sensors", {}).items()}
    seat = [p for p, item in raw.get("sensors", {}).items() if "seat" in item.get("label", "")]
    low, high = raw["machine"].get("point_range", (-10.0, 10.0))
    ranges = {n: tuple(item["range"]) for n, item in raw["parameters"].items() if "range" in item}
    points = [chassis["reference"]] + [p for body in bodies.values() for p in body["points"]]
    ranges |= {f"{p}_{axis}": (low, high) for p in points for axis in "xy"}
    cylinders = tuple(
        Cylinder(name, item["kind"], item["base"], item["rod"])
        for name, item in raw.get("actuators", {}).items()
    )
    axles = tuple(item["point"] for item in raw["axles"])
    tyres = raw.get("tyres", {})
    # the internal spring-dampers' preloads, as derive names them: locked cylinders, then the
    # mounts in body order (a slider F_<body>0, a two-point mount F_<body>_<point>0 per mount)
    locked = [f"F_{item.name}0" for item in cylinders if item.kind == "locked"]
    for name, body in bodies.items():
        if body["joint"] == "slider":
            locked.append(f"F_{name}0")
        locked += [f"F_{name}_{point}0" for point in body.get("mounts", ())]
    circuit = raw.get("circuit", {})
    return {
        "circuit": circuit.get("kind", "pump"),
        "circuit_supply": circuit.get("supply", "load_sensing"),
        "title": raw["machine"]["title"],
        "bodies": tuple(bodies),
        "joint_angles": tuple(b["joint_angle"] for b in bodies.values() if "joint_angle" in b),
        "joint_coordinates": tuple(
            (body["coordinate"], _angle_coordinate(bodies, body["parent"]))
            for body in bodies.values()
            if "joint_angle" in body
        ),
        "length_coordinates": (
            *chassis["coordinates"][:2],
            *(body["coordinate"] for body in bodies.values() if body["joint"] == "slider"),
            *(body["coordinates"][0] for body in bodies.values() if body["joint"] == "two_mounts"),
        ),
        "axles": axles,
        "cylinders": cylinders,
        "sensor_points": sensors,
        "seat_point": seat[0] if seat else "S",
        "parameter_ranges": ranges,
        "static_names": (*(f"F_{axle}y0" for axle in axles), *locked),
        "point_names": tuple(sorted(points)),
        "tyre_units": {name: item["unit"] for name, item in tyres.items()},
        "tyre_ranges": {name: tuple(item["range"]) for name, item in tyres.items()},
    }
