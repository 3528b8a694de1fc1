"""Machine descriptions: read and check ``derive/machines/<name>.toml`` (pure Python, no SymPy).

A description names the bodies (one chassis free in the plane, others on a pin to a parent body at
a named point of it, or on a sliding mount with a spring-damper), the named points of each body,
the axles with tyres, the actuators (the driven lift cylinder group and hydraulically locked
cylinders), the sensor points and every parameter with its unit, description, range and source
(the static loads computed at rest may be left out: :func:`static_load_parameters` lists them),
and in ``[tyres]`` each axle's tyre road geometry (:mod:`derive.description_tyres`: free radius
and tandem cam), declared the same way: parameters of the road input, not of the generated
functions.
The format is drawn in ``derive/machine.schema.json``; :func:`load_machine` checks it and raises a
:class:`DescriptionError` naming the offending entry.

Only the standard library is imported, so the runtime may import this module later (it has no
SymPy dependency); the structural parameter order is :func:`structural_parameters`, the
parameters' reading :mod:`derive.description_parameters`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from derive.description_checks import (
    DescriptionError,
    check_entries,
    read_description,
    required_entry,
    table_entry,
)
from derive.description_keys import JOINTS, KEYS
from derive.description_parameters import (
    ParameterInfo,
    mount_parameters,
    parameter_infos,
    static_load_parameters,
    structural_parameters,
)
from derive.description_tyres import check_tyres, tyre_parameters

__all__ = [
    "MACHINES_DIR",
    "Actuator",
    "Body",
    "DescriptionError",
    "Machine",
    "ParameterInfo",
    "available_machines",
    "load_machine",
    "mount_elements",
    "mount_parameters",
    "static_load_parameters",
    "structural_parameters",
    "tyre_parameters",
]

MACHINES_DIR = Path(__file__).resolve().parent / "machines"
_JOINTS = JOINTS
_KEYS = KEYS


@dataclass(frozen=True)
class Body:
    """One rigid body; points are (x, y) in the chassis frame at p = 0, relative to H."""

    name: str
    joint: str
    label: str
    parent: str | None
    at: str | None
    coordinates: tuple[str, ...]
    joint_angle: str | None
    mass: str
    inertia: str
    centre_of_gravity: str
    points: dict[str, str]
    direction: tuple[float, float] | None = None
    mounts: tuple[str, ...] = ()
    """Two-point mount: the front and rear mount points (points of this body)."""
    end_stops: bool = False
    """Travel limits with a stop spring-damper on each mount (:func:`mount_parameters`)."""
    extension: str | None = None
    """Slider: the parameter that extends it along its direction at p = 0 (a telescope)."""

    @property
    def angle(self) -> str | None:
        """The coordinate that is this body's own absolute angle (None: its parent's)."""
        if self.joint == "two_mounts":
            return self.coordinates[1]
        return {"free": self.coordinates[-1], "pin": self.coordinates[0]}.get(self.joint)


@dataclass(frozen=True)
class Actuator:
    """A cylinder between a point of a body and a point of its parent across one joint."""

    name: str
    kind: str
    base: str
    rod: str


@dataclass(frozen=True)
class Machine:
    """A checked machine description."""

    name: str
    title: str
    path: Path
    bodies: tuple[Body, ...]
    axles: tuple[str, ...]
    actuators: tuple[Actuator, ...]
    sensors: dict[str, tuple[str, tuple[str, ...]]]
    parameters: tuple[ParameterInfo, ...]
    point_range: tuple[float, float]
    tyres: tuple[ParameterInfo, ...] = ()

    @property
    def root(self) -> Body:
        """The chassis (the one free body)."""
        return self.bodies[0]

    def body(self, name: str) -> Body:
        """The body called ``name``."""
        return next(body for body in self.bodies if body.name == name)

    def body_of(self, point: str) -> Body:
        """The body that carries ``point`` (the chassis for its reference point)."""
        if point == self.root.centre_of_gravity:
            return self.root
        return next(body for body in self.bodies if point in body.points)

    @property
    def driven(self) -> Actuator:
        """The lift cylinder group (driven by the hydraulic plant)."""
        return next(item for item in self.actuators if item.kind == "driven")

    @property
    def elements(self) -> tuple[str, ...]:
        """Names of the internal spring-dampers: locked cylinders, then the mounts in body order
        (a slider's is the body's name, a two-point mount's ``<body>_<point>``)."""
        locked = [item.name for item in self.actuators if item.kind == "locked"]
        return (*locked, *(name for body in self.bodies for name in mount_elements(body)))

    @property
    def stops(self) -> tuple[str, ...]:
        """The elements with end stops (mounts of bodies with ``end_stops = true``)."""
        return tuple(name for b in self.bodies if b.end_stops for name in mount_elements(b))


def mount_elements(body: Body) -> tuple[str, ...]:
    """The spring-damper elements of a body's joint: a slider one, a two-point mount two."""
    if body.joint == "slider":
        return (body.name,)
    return tuple(f"{body.name}_{point}" for point in body.mounts)


def _body(where: str, name: str, raw: Any) -> Body:
    entry = f"bodies.{name}"
    joint = raw.get("joint") if isinstance(raw, dict) else None
    if joint not in _JOINTS:
        raise DescriptionError(where, f"{entry}.joint", f"must be one of {', '.join(_JOINTS)}")
    table = table_entry(where, entry, raw, _KEYS[joint])
    need = lambda key: required_entry(where, entry, table, key)  # noqa: E731
    free = joint == "free"
    several = joint in ("free", "two_mounts")
    coordinates = tuple(need("coordinates")) if several else (need("coordinate"),)
    if free and len(coordinates) != 3:
        raise DescriptionError(where, f"{entry}.coordinates", "the chassis has (x, y, angle)")
    mounted = joint in ("slider", "two_mounts")
    direction = tuple(float(v) for v in need("direction")) if mounted else None
    return Body(
        name=name,
        joint=joint,
        label=table.get("label", name),
        parent=None if free else need("parent"),
        at=None if free else need("at"),
        coordinates=coordinates,
        joint_angle=table.get("joint_angle")
        if joint == "pin"
        else None
        if joint == "two_mounts"
        else coordinates[0],
        mass=need("mass"),
        inertia=need("inertia"),
        centre_of_gravity=need("reference") if free else need("centre_of_gravity"),
        points=dict(need("points")),
        direction=direction,  # type: ignore[arg-type]
        mounts=tuple(need("mounts")) if joint == "two_mounts" else (),
        end_stops=bool(table.get("end_stops", False)),
        extension=table.get("extension"),
    )


def _check_tree(where: str, bodies: tuple[Body, ...]) -> None:
    names = [body.name for body in bodies]
    roots = [body.name for body in bodies if body.joint == "free"]
    if roots != names[:1]:
        raise DescriptionError(where, "bodies", "the first body, and only it, must be free")
    points: dict[str, str] = {bodies[0].centre_of_gravity: bodies[0].name}
    for body in bodies:
        for point in body.points:
            if point in points:
                raise DescriptionError(
                    where, f"bodies.{body.name}.points.{point}", f"also on {points[point]}"
                )
            points[point] = body.name
    by_name = {body.name: body for body in bodies}
    for body in bodies[1:]:
        entry = f"bodies.{body.name}"
        if body.parent not in by_name:
            raise DescriptionError(
                where,
                f"{entry}.parent",
                f"unknown parent body {body.parent!r} (bodies: {', '.join(names)})",
            )
        chain, cursor = [body.name], by_name[body.parent]
        while cursor.parent is not None:
            chain.append(cursor.name)
            if cursor.name == body.name:
                raise DescriptionError(
                    where, f"{entry}.parent", "loop in the body tree: " + " -> ".join(chain)
                )
            cursor = by_name[cursor.parent]
        if body.at not in points:
            raise DescriptionError(where, f"{entry}.at", f"point {body.at!r} is on no body")
        if points[body.at] != body.parent:
            raise DescriptionError(
                where, f"{entry}.at", f"point {body.at!r} is not on the parent {body.parent!r}"
            )
        if body.centre_of_gravity not in body.points:
            raise DescriptionError(where, f"{entry}.centre_of_gravity", "not a point of the body")
        for index, mount in enumerate(body.mounts):
            if mount not in body.points:
                raise DescriptionError(
                    where,
                    f"{entry}.mounts[{index}]",
                    f"{mount!r} is not a point of the body (points: {', '.join(body.points)})",
                )
    order = {name: index for index, name in enumerate(names)}
    for body in bodies[1:]:
        if order[body.parent] > order[body.name]:  # type: ignore[index]
            raise DescriptionError(where, f"bodies.{body.name}", "list a parent before its child")


def _check_references(where: str, machine: Machine) -> None:
    def body_of(entry: str, point: str) -> Body:
        try:
            return machine.body_of(point)
        except StopIteration:
            raise DescriptionError(where, entry, f"point {point!r} is on no body") from None

    if len(machine.axles) < 2:
        raise DescriptionError(
            where, "axles", f"{len(machine.axles)} axle(s) given, a machine needs at least two"
        )
    for index, axle in enumerate(machine.axles):
        body_of(f"axles[{index}].point", axle)
    for point in machine.sensors:
        body_of(f"sensors.{point}", point)
    if [item.kind for item in machine.actuators].count("driven") != 1:
        raise DescriptionError(where, "actuators", "exactly one actuator of kind 'driven'")
    for item in machine.actuators:
        entry = f"actuators.{item.name}"
        base, rod = body_of(f"{entry}.base", item.base), body_of(f"{entry}.rod", item.rod)
        if base.name == rod.name:
            raise DescriptionError(
                where,
                entry,
                f"points {item.base!r} and {item.rod!r} are both on body {base.name!r}",
            )
        if rod.parent != base.name or rod.joint != "pin":
            raise DescriptionError(
                where, entry, f"the rod end's body {rod.name!r} must be pinned to {base.name!r}"
            )


def load_machine(source: str | Path) -> Machine:
    """Read and check a machine description (a name in ``derive/machines`` or a TOML path)."""
    path = Path(source)
    if path.suffix != ".toml":
        path = MACHINES_DIR / f"{source}.toml"
    where = path.name
    raw = read_description(path)
    check_entries(where, raw)
    raw = table_entry(where, "(top level)", raw, _KEYS[""])
    head = table_entry(
        where, "machine", required_entry(where, "(top level)", raw, "machine"), _KEYS["machine"]
    )
    bodies_raw = table_entry(
        where, "bodies", required_entry(where, "(top level)", raw, "bodies"), set(raw["bodies"])
    )
    bodies = tuple(_body(where, name, value) for name, value in bodies_raw.items())
    _check_tree(where, bodies)
    axles = []
    for index, axle in enumerate(raw.get("axles", [])):
        axles.append(
            required_entry(
                where,
                f"axles[{index}]",
                table_entry(where, f"axles[{index}]", axle, _KEYS["axle"]),
                "point",
            )
        )
    actuators = tuple(
        Actuator(name, required_entry(where, f"actuators.{name}", item, "kind"),
                 required_entry(where, f"actuators.{name}", item, "base"),
                 required_entry(where, f"actuators.{name}", item, "rod"))
        for name, item in raw.get("actuators", {}).items()
        if table_entry(where, f"actuators.{name}", item, _KEYS["actuator"]) is not None
    )  # fmt: skip
    sensors = {
        point: (
            item.get("label", point),
            tuple(required_entry(where, f"sensors.{point}", item, "axes")),
        )
        for point, item in raw.get("sensors", {}).items()
        if table_entry(where, f"sensors.{point}", item, _KEYS["sensor"]) is not None
    }
    machine = Machine(
        name=required_entry(where, "machine", head, "name"),
        title=required_entry(where, "machine", head, "title"),
        path=path,
        bodies=bodies,
        axles=tuple(axles),
        actuators=actuators,
        sensors=sensors,
        parameters=(),
        point_range=tuple(head.get("point_range", (-10.0, 10.0))),  # type: ignore[arg-type]
    )
    _check_references(where, machine)
    parameters = parameter_infos(
        where, required_entry(where, "(top level)", raw, "parameters"), machine
    )
    tyres = tuple(ParameterInfo(*item) for item in check_tyres(where, raw, machine.axles))
    return Machine(**{**machine.__dict__, "parameters": parameters, "tyres": tyres})


def available_machines() -> tuple[str, ...]:
    """Names of the described machines (``derive/machines/*.toml``), sorted."""
    return tuple(sorted(path.stem for path in MACHINES_DIR.glob("*.toml")))
