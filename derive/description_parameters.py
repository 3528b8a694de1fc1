"""The parameters of a machine description: their order, the static loads, their checked entries.

:func:`structural_parameters` is the order of the generated functions' parameter vector (masses
and inertias, gravity, the bodies' points, the tyres' springs and dampers, the internal elements
with their end stops, extensions, then the static loads); :func:`static_load_parameters` lists
the loads the derivation computes at rest (a description may leave them out);
:func:`parameter_infos` reads ``[parameters]`` into :class:`ParameterInfo` entries. Pure Python,
no SymPy (:mod:`derive.description`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from derive.description_checks import DescriptionError, required_entry, table_entry
from derive.description_keys import KEYS, parameter_names_problem

if TYPE_CHECKING:
    from derive.description import Body, Machine

__all__ = [
    "STATIC_LOAD_SOURCE",
    "ParameterInfo",
    "mount_parameters",
    "parameter_infos",
    "static_load_parameters",
    "structural_parameters",
]

#: Source of a static load the description leaves out (:func:`static_load_parameters`).
STATIC_LOAD_SOURCE = "computed by complete_parameters (static equilibrium)"


@dataclass(frozen=True)
class ParameterInfo:
    """One parameter of the description: unit, meaning, physical range and source."""

    name: str
    unit: str
    description: str
    range: tuple[float, float] | None = None
    source: str = ""


def mount_parameters(element: str) -> list[tuple[str, str]]:
    """(name, unit) of an element's end stops: travel limits from p = 0, stop stiffness and
    damping (:mod:`derive.elements`)."""
    return [
        (f"s_min_{element}", "m"),
        (f"s_max_{element}", "m"),
        (f"k_stop_{element}", "N/m"),
        (f"c_stop_{element}", "N*s/m"),
    ]


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


def parameter_infos(where: str, raw: dict[str, Any], machine: Machine) -> tuple[ParameterInfo, ...]:
    """Every parameter of ``machine`` in the order of :func:`structural_parameters`, from the
    description's ``[parameters]`` (``raw``): points described by the bodies, static loads
    left out described as computed, each other one with its unit checked (DescriptionError)."""
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
        item = table_entry(
            where, entry, required_entry(where, "parameters", table, name), KEYS["parameter"]
        )
        if "unit" not in item:
            raise DescriptionError(where, f"{entry}.unit", "missing unit")
        if item["unit"] != unit:
            raise DescriptionError(where, f"{entry}.unit", f"{item['unit']!r}, expected {unit!r}")
        bounds = tuple(float(v) for v in item["range"]) if "range" in item else None
        text = required_entry(where, entry, item, "description")
        out.append(ParameterInfo(name, unit, text, bounds, item.get("source", "")))  # type: ignore[arg-type]
    return tuple(out)
