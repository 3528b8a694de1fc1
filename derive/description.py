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
SymPy dependency); the structural parameter order is :func:`structural_parameters`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from derive.description_checks import DescriptionError, check_entries, read_description
from derive.description_keys import JOINTS, KEYS, parameter_names_problem
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
#: Source of a static load the description leaves out (:func:`static_load_parameters`).
STATIC_LOAD_SOURCE = "computed by complete_parameters (static equilibrium)"


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
class ParameterInfo:
    """One parameter of the description: unit, meaning, physical range and source."""

    name: str
    unit: str
    description: str
    range: tuple[float, float] | None = None
    source: str = ""


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


def mount_parameters(element: str) -> list[tuple[str, str]]:
    """(name, unit) of an element's end stops: travel limits from p = 0, stop stiffness and
    damping (:mod:`derive.elements`)."""
    return [
        (f"s_min_{element}", "m"),
        (f"s_max_{element}", "m"),
        (f"k_stop_{element}", "N/m"),
        (f"c_stop_{element}", "N*s/m"),
    ]


def _table(where: str, entry: str, value: Any, allowed: set[str]) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise DescriptionError(where, entry, "expected a table")
    for key in value:
        if key not in allowed:
            raise DescriptionError(
                where, entry, f"unknown key {key!r} (allowed: {', '.join(sorted(allowed))})"
            )
    return value


def _need(where: str, entry: str, table: dict[str, Any], key: str) -> Any:
    if key not in table:
        raise DescriptionError(where, f"{entry}.{key}", "missing")
    return table[key]


def _body(where: str, name: str, raw: Any) -> Body:
    entry = f"bodies.{name}"
    joint = raw.get("joint") if isinstance(raw, dict) else None
    if joint not in _JOINTS:
        raise DescriptionError(where, f"{entry}.joint", f"must be one of {', '.join(_JOINTS)}")
    table = _table(where, entry, raw, _KEYS[joint])
    need = lambda key: _need(where, entry, table, key)  # noqa: E731
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


def structural_parameters(machine: Machine) -> list[tuple[str, str]]:
    """(name, unit) of the parameter vector, in the order of the generated functions."""
    out: list[tuple[str, str]] = []
    for body in machine.bodies:
        out += [(body.mass, "kg"), (body.inertia, "kg*m^2")]
    out.append(("g", "m/s^2"))
    for body in machine.bodies:
        out += [(f"{point}_{axis}", "m") for point in body.points for axis in "xy"]
    for axle in machine.axles:
        out += [(f"{kind}_{axle}{axis}", unit) for kind, unit in (("k", "N/m"), ("c", "N*s/m"))
                for axis in "xy"]  # fmt: skip
    out += [("mu_road", "-"), ("F_transition", "N"), ("tau_slip", "s")]
    stops = machine.stops
    for element in machine.elements:
        out += [(f"k_{element}", "N/m"), (f"c_{element}", "N*s/m")]
        out += mount_parameters(element) if element in stops else []
    out += [(body.extension, "m") for body in machine.bodies if body.extension]
    out += [(name, "N") for name in static_load_parameters(machine)]
    return out


def static_load_parameters(machine: Machine) -> dict[str, str]:
    """The static loads the derivation computes at rest, name -> description, in the order of
    the parameter vector: the vertical tyre load of each axle (``F_<axle>y0``), then the force of
    each internal spring-damper (``F_<element>0``: locked cylinders, then sliding mounts).

    The generated ``complete_parameters`` replaces whatever value is given for them, so a
    description may leave them out of ``[parameters]`` (they are then described as here).
    """
    out = {
        f"F_{axle}y0": f"static vertical tyre load at {axle} (from the static equilibrium)"
        for axle in machine.axles
    }
    locked = {item.name for item in machine.actuators if item.kind == "locked"}
    sliders = {body.name for body in machine.bodies if body.joint == "slider"}
    for element in machine.elements:
        kind = f"locked {element} cylinder" if element in locked else f"{element} sliding mount"
        kind = kind if element in locked | sliders else f"{element} mount"
        out[f"F_{element}0"] = f"static force of the {kind} (from the static equilibrium)"
    return out


def _point_parameter(machine_root: str, body: Body, point: str, axis: str, where: str) -> str:
    place = "chassis point" if body.joint == "free" else f"{body.label} point at p = 0"
    return f"{axis} of {body.points[point]} ({place}, relative to {machine_root})"


def _is_point_parameter(machine: Machine, name: str) -> bool:
    return name[-2:] in ("_x", "_y") and any(name[:-2] in body.points for body in machine.bodies)


def _parameters(where: str, raw: dict[str, Any], machine: Machine) -> tuple[ParameterInfo, ...]:
    if not isinstance(raw, dict):
        raise DescriptionError(where, "parameters", "expected a table")
    table = raw
    loads = static_load_parameters(machine)
    structure = structural_parameters(machine)
    points = {name for name, _ in structure if _is_point_parameter(machine, name)}
    problem = parameter_names_problem(table, structure, points, loads)
    if problem is not None:
        raise DescriptionError(where, "parameters", problem)
    out: list[ParameterInfo] = []
    reference = machine.root.centre_of_gravity
    for name, unit in structural_parameters(machine):
        body = next((b for b in machine.bodies if name[:-2] in b.points), None)
        if body is not None and name[-2:] in ("_x", "_y"):
            text = _point_parameter(reference, body, name[:-2], name[-1], where)
            out.append(ParameterInfo(name, unit, text, machine.point_range))
            continue
        if name in loads and name not in table:
            out.append(ParameterInfo(name, unit, loads[name], None, STATIC_LOAD_SOURCE))
            continue
        entry = f"parameters.{name}"
        item = _table(where, entry, _need(where, "parameters", table, name), _KEYS["parameter"])
        if "unit" not in item:
            raise DescriptionError(where, f"{entry}.unit", "missing unit")
        if item["unit"] != unit:
            raise DescriptionError(where, f"{entry}.unit", f"{item['unit']!r}, expected {unit!r}")
        bounds = tuple(float(v) for v in item["range"]) if "range" in item else None
        text = _need(where, entry, item, "description")
        out.append(ParameterInfo(name, unit, text, bounds, item.get("source", "")))  # type: ignore[arg-type]
    return tuple(out)


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
    raw = _table(where, "(top level)", raw, _KEYS[""])
    head = _table(where, "machine", _need(where, "(top level)", raw, "machine"), _KEYS["machine"])
    bodies_raw = _table(
        where, "bodies", _need(where, "(top level)", raw, "bodies"), set(raw["bodies"])
    )
    bodies = tuple(_body(where, name, value) for name, value in bodies_raw.items())
    _check_tree(where, bodies)
    axles = []
    for index, axle in enumerate(raw.get("axles", [])):
        axles.append(
            _need(
                where,
                f"axles[{index}]",
                _table(where, f"axles[{index}]", axle, _KEYS["axle"]),
                "point",
            )
        )
    actuators = tuple(
        Actuator(name, _need(where, f"actuators.{name}", item, "kind"),
                 _need(where, f"actuators.{name}", item, "base"),
                 _need(where, f"actuators.{name}", item, "rod"))
        for name, item in raw.get("actuators", {}).items()
        if _table(where, f"actuators.{name}", item, _KEYS["actuator"]) is not None
    )  # fmt: skip
    sensors = {
        point: (item.get("label", point), tuple(_need(where, f"sensors.{point}", item, "axes")))
        for point, item in raw.get("sensors", {}).items()
        if _table(where, f"sensors.{point}", item, _KEYS["sensor"]) is not None
    }
    machine = Machine(
        name=_need(where, "machine", head, "name"),
        title=_need(where, "machine", head, "title"),
        path=path,
        bodies=bodies,
        axles=tuple(axles),
        actuators=actuators,
        sensors=sensors,
        parameters=(),
        point_range=tuple(head.get("point_range", (-10.0, 10.0))),  # type: ignore[arg-type]
    )
    _check_references(where, machine)
    parameters = _parameters(where, _need(where, "(top level)", raw, "parameters"), machine)
    tyres = tuple(ParameterInfo(*item) for item in check_tyres(where, raw, machine.axles))
    return Machine(**{**machine.__dict__, "parameters": parameters, "tyres": tyres})


def available_machines() -> tuple[str, ...]:
    """Names of the described machines (``derive/machines/*.toml``), sorted."""
    return tuple(sorted(path.stem for path in MACHINES_DIR.glob("*.toml")))
